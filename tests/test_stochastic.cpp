#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parse;

namespace {

const char* kBush =
    "Lsystem: 1\nseed: 3\naxiom: F\n"
    "F --> F[+F]F[-F]F : 0.33\nF --> F[+F]F : 0.33\nF --> F[-F]F : 0.34\nendlsystem\n";

ModuleString deriveWith(const LSystem& ls, int n, std::uint64_t seed, unsigned threads = 1) {
    DerivationOptions o;
    o.seed = seed;
    o.threads = threads;
    return derive(ls, n, o);
}

}  // namespace

TEST(Stochastic, SameSeedSameString) {
    LSystem ls = parse(kBush);
    EXPECT_TRUE(deriveWith(ls, 5, 11) == deriveWith(ls, 5, 11));
    EXPECT_TRUE(derive(ls, 5) == deriveWith(ls, 5, 3)) << "the file's seed is used by default";
}

TEST(Stochastic, DifferentSeedsDifferentStrings) {
    LSystem ls = parse(kBush);
    std::set<std::string> seen;
    for (std::uint64_t s = 0; s < 16; ++s) seen.insert(deriveWith(ls, 5, s).toString(ls.symbols));
    EXPECT_EQ(seen.size(), 16u);
}

TEST(Stochastic, OneThreadEqualsManyThreads) {
    LSystem ls = parse(kBush);
    ModuleString a = deriveWith(ls, 8, 5, 1);
    ASSERT_GT(a.size(), 100000u) << "large enough to be split across threads";
    for (unsigned t : {2u, 3u, 7u}) EXPECT_TRUE(a == deriveWith(ls, 8, 5, t)) << t << " threads";
}

TEST(Stochastic, ProductionFrequenciesMatchTheProbabilities) {
    // 10^6 independent choices between B (weight 1) and C (weight 3).
    LSystem ls = parse(
        "Lsystem: 1\naxiom: X\nX --> YYYYYYYYYY\nY --> ZZZZZZZZZZ\nZ --> AAAAAAAAAA\n"
        "A --> B : 1\nA --> C : 3\nendlsystem\n");
    // X -> 10 Y -> 100 Z -> 1000 A: derive 3 steps, then grow the count with a wider axiom.
    std::string axiom(1000, 'X');
    LSystem wide = parse("Lsystem: 1\naxiom: " + axiom +
                         "\nX --> YYYYYYYYYY\nY --> ZZZZZZZZZZ\nZ --> AAAAAAAAAA\n"
                         "A --> B : 1\nA --> C : 3\nendlsystem\n");
    ModuleString s = deriveWith(wide, 4, 99, 2);
    ASSERT_EQ(s.size(), 1000000u);
    std::size_t b = 0;
    for (Symbol x : s.symbols()) b += x == 'B';
    double n = 1e6, p = 0.25, sigma = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(b / n, p, 5 * sigma) << "B chosen " << b << " times";
}

TEST(Stochastic, WeightsAreExpressionsNormalisedOverApplicableProductions) {
    // The second production's condition fails for x >= 5, so A(7) always takes the first.
    LSystem ls = parse(
        "Lsystem: 1\naxiom: A(7)A(7)A(7)A(7)A(7)A(7)A(7)A(7)\n"
        "A(x) --> B : x / 100\nA(x) : x < 5 --> C : 1000\nendlsystem\n");
    EXPECT_EQ(graftal::testing::derived(ls, 1), "BBBBBBBB");
}

// cpfg (oracle p11_probabilities): with every weight 0 the first applicable production
// applies.
TEST(Stochastic, ZeroTotalWeightTakesTheFirstApplicableProduction) {
    LSystem ls = parse("Lsystem: 1\naxiom: AA\nA --> B : 0\nA --> C : 0\nendlsystem\n");
    EXPECT_EQ(graftal::testing::derived(ls, 1), "BB");
    LSystem cs = parse("Lsystem: 1\naxiom: XAA\nX < A --> B : 0\nA --> C : 0\nendlsystem\n");
    EXPECT_EQ(graftal::testing::derived(cs, 1), "XBC");
}

TEST(Stochastic, RandomFunctionsAreReproducible) {
    LSystem ls = parse("Lsystem: 1\naxiom: A(0)\nA(x) --> A(ran(10))B(nran(5, 1))\nendlsystem\n");
    std::string a = deriveWith(ls, 6, 1).toString(ls.symbols);
    EXPECT_EQ(a, deriveWith(ls, 6, 1, 4).toString(ls.symbols));
    EXPECT_NE(a, deriveWith(ls, 6, 2).toString(ls.symbols));
    ModuleString s = deriveWith(ls, 1, 1);
    EXPECT_GE(s.params(0)[0], 0);
    EXPECT_LT(s.params(0)[0], 10);
}

TEST(Stochastic, CommandLineSeedOverridesTheFile) {
    LSystem ls = parse(kBush);
    EXPECT_FALSE(derive(ls, 5) == deriveWith(ls, 5, 4));
}
