// Decomposition, homomorphism and the cut symbol, with cpfg's semantics.
#include <gtest/gtest.h>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseError;
using graftal::testing::parseModel;

TEST(Decomposition, AppliesRecursivelyAfterEveryStep) {
    Model ls = parseModel(
        "Lsystem: 1\naxiom: A\nA --> AB\n"
        "decomposition\nmaximum depth: 5\nB --> CC\nC --> D\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 1), "ADD");
    EXPECT_EQ(derived(ls.lsystem, 2), "ADDDD");
}

TEST(Decomposition, StopsAtTheMaximumDepth) {
    Model ls =
        parseModel("Lsystem: 1\naxiom: A\ndecomposition\nmaximum depth: 3\nA --> aA\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 1), "aaaA");
}

// cpfg decomposes what a derivation step produces (and the modules it copies), never the
// axiom as written: with derivation length 0 its string is the axiom, and a ring L-system
// whose axiom decomposes into ABBB (vlab's m-Ring) gives ABBB after one step, not the
// rewriting of ABBB.  Both measured with cpfg 6.6 in batch mode (-g -str).
TEST(Decomposition, LeavesTheAxiomAsWritten) {
    Model ls =
        parseModel("Lsystem: 1\naxiom: A\ndecomposition\nmaximum depth: 3\nA --> aA\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 0), "A");
    Model ring = parseModel(
        "Lsystem: 1\nring lsystem\naxiom: X(4)\nA < B --> A\nA --> B\n"
        "decomposition\nmaximum depth: 10\nX(n) : n>1 --> X(n-1)B\nX(n) : n==1 --> A\n"
        "endlsystem\n");
    EXPECT_EQ(derived(ring.lsystem, 1), "ABBB");
    EXPECT_EQ(derived(ring.lsystem, 2), "BABB");
}

TEST(Homomorphism, OnlyChangesWhatTheTurtleSees) {
    Model ls = parseModel(
        "Lsystem: 1\naxiom: I\nI --> II\n"
        "homomorphism\nmaximum depth: 2\nI --> S\nS --> F\nendlsystem\n");
    ModuleString s = derive(ls, 2);
    EXPECT_EQ(s.toString(ls.lsystem.symbols), "IIII");
    EXPECT_EQ(applyHomomorphism(ls.lsystem, s).toString(ls.lsystem.symbols), "FFFF");
    EXPECT_EQ(interpret(ls, applyHomomorphism(ls.lsystem, s)).segments.size(), 4u);
}

TEST(Homomorphism, ParametersFlowThrough) {
    Model ls = parseModel(
        "Lsystem: 1\naxiom: L(2)\nL(i) --> L(i+1)\n"
        "homomorphism\nL(s) --> [+F(s)][-F(s)]\nendlsystem\n");
    EXPECT_EQ(applyHomomorphism(ls.lsystem, derive(ls, 1)).toString(ls.lsystem.symbols),
              "[+F(3)][-F(3)]");
}

// cpfg allows contexts in homomorphism productions (oracle s08_homomorphism), not in
// decomposition ones.
TEST(Homomorphism, ContextIsAllowedInHomomorphismOnly) {
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: A\nhomomorphism\nB < A --> F\nendlsystem\n"), "");
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: A\ndecomposition\nB < A --> F\nendlsystem\n"),
              "test.l:4:1: error: decomposition productions are context-free: remove the context");
}

TEST(Cut, RemovesTheRestOfItsBranchAtTheNextStep) {
    Model ls = parseModel("Lsystem: 1\naxiom: A\nA --> B[C%DE[G]H]X\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 1), "B[C%DE[G]H]X");
    EXPECT_EQ(derived(ls.lsystem, 2), "B[C]X");
}

TEST(Cut, OnTheMainAxisRemovesEverythingAfter) {
    Model ls = parseModel("Lsystem: 1\naxiom: AB%C[D]E\nA --> AA\nendlsystem\n");
    EXPECT_EQ(derived(ls.lsystem, 1), "AAB");
}
