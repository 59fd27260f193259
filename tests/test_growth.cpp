#include <gtest/gtest.h>

#include <cmath>

#include "graftal/growth.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parse;

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
