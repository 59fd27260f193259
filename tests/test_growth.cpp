#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "graftal/rewrite/growth.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
namespace fs = std::filesystem;

TEST(BigCount, ArithmeticIsExact) {
    BigCount a(999999999);
    a += BigCount(1);
    EXPECT_EQ(a.toString(), "1000000000");
    EXPECT_EQ(BigCount(123456789012345678ull).times(1000).toString(), "123456789012345678000");
    BigCount big(1);
    for (int i = 0; i < 100; ++i) big = big.times(2);
    EXPECT_EQ(big.toString(), "1267650600228229401496703205376");
    EXPECT_FALSE(big.toUint64().has_value());
    EXPECT_EQ(BigCount(42).toUint64(), 42u);
    EXPECT_TRUE(BigCount(3) < BigCount(1000000000));
}

TEST(GrowthPrediction, PredictedCountsEqualDerivedCounts) {
    const char* systems[] = {
        "Lsystem: 1\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n",
        "Lsystem: 1\naxiom: X\nX --> F[+X]F[-X]+X\nF --> FF\nendlsystem\n",
        "module ar, al, br, bl;\nLsystem: 1\naxiom: ar\nar --> al br\nal --> bl ar\nbr --> ar\nbl "
        "--> al\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nA --> *\nendlsystem\n",
        "Lsystem: 1\naxiom: X\ntable: a\nX --> XA\nA --> AA\ntable: b\nX --> XB\n"
        "table schedule: a 3, b\nendlsystem\n",
    };
    for (const char* text : systems) {
        LSystem ls = parse(text);
        GrowthPrediction g = predictGrowth(ls, 6);
        ASSERT_TRUE(g.exact) << text << g.reason;
        for (int n = 0; n <= 6; ++n) {
            ModuleString s = derive(ls, n);
            EXPECT_EQ(g.modules[static_cast<std::size_t>(n)].toString(), std::to_string(s.size()))
                << text << " n=" << n;
        }
        ModuleString last = derive(ls, 6);
        for (Symbol sym = 0; sym < ls.symbols.size(); ++sym) {
            std::size_t c = 0;
            for (Symbol x : last.symbols()) c += x == sym;
            EXPECT_EQ(g.symbolsAtEnd[sym].toString(), std::to_string(c));
        }
    }
}

TEST(GrowthPrediction, KochIslandPastSixtyFourBits) {
    LSystem ls = parse("Lsystem: 1\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n");
    GrowthPrediction g = predictGrowth(ls, 30);
    // 7 + 52 (8^30 - 1) / 7
    EXPECT_EQ(g.modules[8].toString(), "124630747");
    EXPECT_EQ(g.modules[30].toString(), "9196126006119967756393494235");
}

TEST(GrowthPrediction, StochasticGivesExpectedCounts) {
    LSystem ls = parse("Lsystem: 1\naxiom: F\nF --> FF : 1\nF --> F : 3\nendlsystem\n");
    GrowthPrediction g = predictGrowth(ls, 4);
    ASSERT_TRUE(g.expected);
    EXPECT_FALSE(g.exact);
    EXPECT_DOUBLE_EQ(g.expectedModules[4], std::pow(1.25, 4));
}

TEST(GrowthPrediction, SaysWhyItCannotPredict) {
    EXPECT_NE(predictGrowth(parse("Lsystem: 1\naxiom: ba\nb < a --> b\nendlsystem\n"), 3)
                  .reason.find("context"),
              std::string::npos);
    EXPECT_NE(
        predictGrowth(parse("Lsystem: 1\naxiom: A(1)\nA(x) : x < 3 --> A(x+1)B\nendlsystem\n"), 3)
            .reason.find("conditions"),
        std::string::npos);
}

// Productions match a module by its symbol and its number of parameters: `L(i) --> L` turns
// an `L(i)` into an `L`, which the next production rewrites. Counting both as one module
// predicted 1 module at every step.
TEST(GrowthPrediction, CountsModulesWithAndWithoutParametersApart) {
    std::ifstream in(fs::path(GRAFTAL_EXAMPLES_DIR) / ".." / "fuzz" / "regressions" / "derive" /
                     "growth-prediction-mixed-arity.l");
    std::stringstream text;
    text << in.rdbuf();
    ASSERT_FALSE(text.str().empty());
    LSystem ls = parse(text.str());
    GrowthPrediction g = predictGrowth(ls, 3);
    ASSERT_TRUE(g.exact) << g.reason;
    const char* expected[] = {"L(0)", "L", "FF", "FF"};
    for (int n = 0; n <= 3; ++n) {
        ModuleString s = derive(ls, n);
        EXPECT_EQ(s.toString(ls.symbols), expected[n]);
        EXPECT_EQ(g.modules[static_cast<std::size_t>(n)].toString(), std::to_string(s.size()))
            << "n=" << n;
    }
    EXPECT_EQ(g.symbolsAtEnd[static_cast<std::size_t>(ls.symbols.find("F"))].toString(), "2");
    EXPECT_EQ(g.symbolsAtEnd[static_cast<std::size_t>(ls.symbols.find("L"))].toString(), "0");
}

// A production for one number of parameters leaves a module with another number alone.
TEST(GrowthPrediction, LeavesModulesOfAnotherArityAlone) {
    LSystem ls = parse("Lsystem: 1\naxiom: A A(1) A(1,2)\nA(x) --> A(x)A(x)\nendlsystem\n");
    GrowthPrediction g = predictGrowth(ls, 4);
    ASSERT_TRUE(g.exact) << g.reason;
    EXPECT_EQ(g.modules[4].toString(), "18");  // A, 16 A(1), A(1,2)
    EXPECT_EQ(derive(ls, 4).size(), 18u);
}

// The 3D fern turns its leaflets L(i) into L, whose polygon grows: 1530 predicted at 6 steps
// while the derivation makes 4014 modules, before counts were kept per arity.
TEST(GrowthPrediction, FernPredictionEqualsDerivation) {
    Model fern = loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig3.8-fern-3d.l");
    GrowthPrediction g = predictGrowth(fern.lsystem, 6);
    ASSERT_TRUE(g.exact) << g.reason;
    for (int n = 0; n <= 6; ++n)
        EXPECT_EQ(g.modules[static_cast<std::size_t>(n)].toString(),
                  std::to_string(derive(fern, n).size()))
            << "n=" << n;
    EXPECT_EQ(g.modules[6].toString(), "4014");
}

// Every example with an exact prediction: predicted equals derived at every step (up to the
// file's derivation length, while the string stays small enough to derive in the test).
TEST(GrowthPrediction, EveryExactExamplePredictionEqualsDerivation) {
    int checked = 0;
    for (const auto& e : fs::directory_iterator(GRAFTAL_EXAMPLES_DIR)) {
        if (e.path().extension() != ".l" || isMapLSystemFile(e.path())) continue;
        SCOPED_TRACE(e.path().filename().string());
        Model model = loadExample(e.path());
        const int steps = std::min(model.lsystem.derivationLength, 12);
        GrowthPrediction g = predictGrowth(model.lsystem, steps);
        if (!g.exact) continue;
        Derivation derivation(model);
        for (int n = 0;; ++n) {
            std::optional<std::uint64_t> predicted =
                g.modules[static_cast<std::size_t>(n)].toUint64();
            ASSERT_TRUE(predicted.has_value());
            EXPECT_EQ(*predicted, derivation.current().size()) << "n=" << n;
            if (n == steps || *predicted > 200'000) break;
            derivation.step();
        }
        ++checked;
    }
    EXPECT_GE(checked, 10);
}
