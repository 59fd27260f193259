#include <gtest/gtest.h>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::derived;

TEST(Context, BookExampleLeftContextOfGIsD) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nD < G --> X\nendlsystem\n", 1),
              "ABCD[EF][X[HI[JKL]M]NOPQ]");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nF < G --> X\nendlsystem\n", 1),
              "ABCD[EF][G[HI[JKL]M]NOPQ]")
        << "a sibling branch is not context";
}

TEST(Context, BookExampleRightContextOfGIsN) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nG > N --> X\nendlsystem\n", 1),
              "ABCD[EF][X[HI[JKL]M]NOPQ]");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nG > H --> X\nendlsystem\n", 1),
              "ABCD[EF][G[HI[JKL]M]NOPQ]")
        << "a lateral branch is not on the axis";
}

TEST(Context, RightContextFailsAtTheEndOfTheBranch) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A[B]C\nB > C --> X\nendlsystem\n", 1), "A[B]C");
}

TEST(Context, LeftContextEntersTheParentAtTheBracket) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A[B[C]D]\nA < D --> X\nB < C --> Y\nendlsystem\n", 1),
              "A[B[Y]D]")
        << "D's parent axis is B...A; B is the nearest, so A < D fails";
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A[B[C]D]\nB < D --> X\nendlsystem\n", 1), "A[B[C]X]");
}

TEST(Context, IgnoredSymbolsAreSkippedBothWays) {
    EXPECT_EQ(
        derived("Lsystem: 1\nignore: +-F\naxiom: A+F-B-F+C\nA < B > C --> X\nendlsystem\n", 1),
        "A+F-X-F+C");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: A+B\nA < B --> X\nendlsystem\n", 1), "A+B");
}

TEST(Context, ConsiderListsTheOnlySymbolsThatCount) {
    EXPECT_EQ(derived("Lsystem: 1\nconsider: AB\naxiom: AxyzB\nA < B --> X\nendlsystem\n", 1),
              "AxyzX");
}

TEST(Context, MultiModuleContexts) {
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCDE\nAB < C > DE --> X\nendlsystem\n", 1), "ABXDE");
    EXPECT_EQ(derived("Lsystem: 1\naxiom: ABCDE\nBB < C --> X\nendlsystem\n", 1), "ABCDE");
}

TEST(Context, AcropetalSignalMatchesFigure312) {
    LSystem ls =
        graftal::testing::parse("Lsystem: 1\naxiom: J[I]I[I]I[I]I\nJ < I --> J\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "J[J]J[I]I[I]I");
    EXPECT_EQ(derived(ls, 2), "J[J]J[J]J[I]I");
    EXPECT_EQ(derived(ls, 3), "J[J]J[J]J[J]J");
}

TEST(Context, BasipetalSignalMatchesFigure313) {
    LSystem ls =
        graftal::testing::parse("Lsystem: 1\naxiom: I[I]I[I]I[I]J\nI > J --> J\nendlsystem\n");
    EXPECT_EQ(derived(ls, 1), "I[I]I[I]J[I]J");
    EXPECT_EQ(derived(ls, 2), "I[I]J[I]J[I]J");
    EXPECT_EQ(derived(ls, 3), "J[I]J[I]J[I]J");
}

TEST(Context, ContextSearchCostDoesNotDependOnBranchSize) {
    // A[ huge branch ]B: B's left context is A across a branch of a million modules.
    // With a bracket index the whole step is linear; rescanning would be quadratic.
    std::string axiom = "A";
    for (int i = 0; i < 2000; ++i) axiom += "[" + std::string(500, 'x') + "]";
    axiom += "B";
    LSystem ls = graftal::testing::parse("Lsystem: 1\naxiom: " + axiom +
                                         "\nA < B --> C\nA < x --> y\nendlsystem\n");
    ModuleString s = derive(ls, 1);
    EXPECT_EQ(ls.symbols.name(s.symbol(s.size() - 1)), "C");
}
