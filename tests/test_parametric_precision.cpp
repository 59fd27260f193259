// Parameters stored as 32-bit floats (the default, as cpfg) or as doubles: the same
// modules either way, values within float rounding of each other, the same string for any
// thread count, and `stats` counting the last step without writing it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "graftal/rewrite/derivation.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parse;
using graftal::testing::runGraftal;

namespace {

std::string benchModel(const std::string& name) {
    return std::string(GRAFTAL_TESTS_DIR) + "/../bench/lsystems/" + name;
}

ModuleString deriveWith(const LSystem& ls, int steps, Precision precision, unsigned threads) {
    DerivationOptions o;
    o.precision = precision;
    o.threads = threads;
    return derive(ls, steps, o);
}

// Honda's tree, multi-parameter conditions, context with parameters, statement blocks:
// the parametric cases of the benchmark, at sizes past the engine's parallel threshold
// (2^16 modules) so that 2 and 7 threads really split the steps.
struct Case {
    const char* file;
    int steps;
};
const Case kCases[] = {{"honda-2.6a.l", 14},
                       {"param-conditions.l", 14},
                       {"param-context.l", 14},
                       {"param-blocks.l", 14}};

}  // namespace

TEST(ParametricPrecision, SameStringForOneTwoAndSevenThreads) {
    for (const Case& c : kCases) {
        LSystem ls = loadLSystem(benchModel(c.file));
        for (Precision p : {Precision::Single, Precision::Double}) {
            ModuleString one = deriveWith(ls, c.steps, p, 1);
            ASSERT_GT(one.size(), std::size_t(1) << 16) << c.file;
            const std::string text = one.toString(ls.symbols);
            for (unsigned threads : {2u, 7u}) {
                ModuleString many = deriveWith(ls, c.steps, p, threads);
                EXPECT_TRUE(many == one) << c.file << " with " << threads << " threads";
                EXPECT_EQ(many.toString(ls.symbols), text) << c.file << " with " << threads;
            }
        }
    }
}

// Floats hold about 7 significant digits: every value of the single string is its double
// counterpart to within the rounding of one float per step (the values are recomputed from
// rounded parameters every step, so the error can grow by one rounding a step).
TEST(ParametricPrecision, SingleIsDoubleWithinFloatRounding) {
    for (const Case& c : kCases) {
        LSystem ls = loadLSystem(benchModel(c.file));
        const int steps = 10;
        ModuleString single = deriveWith(ls, steps, Precision::Single, 1);
        ModuleString dbl = deriveWith(ls, steps, Precision::Double, 1);
        ASSERT_EQ(single.size(), dbl.size()) << c.file;
        ASSERT_EQ(single.precision(), Precision::Single);
        ASSERT_EQ(dbl.precision(), Precision::Double);
        EXPECT_TRUE(
            std::equal(single.symbols().begin(), single.symbols().end(), dbl.symbols().begin()))
            << c.file;
        ASSERT_EQ(single.paramCount(), dbl.paramCount()) << c.file;
        double worst = 0;
        for (std::size_t i = 0; i < single.size(); ++i) {
            ParamView a = single.params(i), b = dbl.params(i);
            ASSERT_EQ(a.size(), b.size());
            for (std::size_t k = 0; k < a.size(); ++k) {
                double rel = std::fabs(a[k] - b[k]) / std::max(1e-30, std::fabs(b[k]));
                worst = std::max(worst, rel);
            }
        }
        EXPECT_LE(worst, (steps + 1) * std::ldexp(1.0, -24)) << c.file;
    }
}

// The double path is the representation graftal had before floats: values as computed,
// printed in shortest round-trip form. Honda's tree at n = 2, as it printed then.
TEST(ParametricPrecision, DoublePathPrintsTheDoublesAsBefore) {
    LSystem ls = loadLSystem(benchModel("honda-2.6a.l"));
    EXPECT_EQ(deriveWith(ls, 1, Precision::Double, 1).toString(ls.symbols),
              "!(10)F(1)[&(45)B(0.6,7.069999999999999)]/(137.5)A(0.9,7.069999999999999)");
    EXPECT_EQ(deriveWith(ls, 1, Precision::Single, 1).toString(ls.symbols),
              "!(10)F(1)[&(45)B(0.6,7.07)]/(137.5)A(0.9,7.07)");
}

TEST(ParametricPrecision, FloatsPrintInTheirShortestForm) {
    EXPECT_EQ(formatSingle(0.1f), "0.1");
    EXPECT_EQ(formatSingle(static_cast<float>(0.6 * 0.6)), "0.36");
    EXPECT_EQ(formatSingle(3.0f), "3");
    EXPECT_EQ(formatSingle(-0.0f), "0");
    EXPECT_EQ(formatSingle(1e20f), "1e+20");
    ModuleString s(Precision::Single);
    s.push('A', std::vector<double>{0.1, 1.0 / 3.0});
    EXPECT_EQ(s.toString(SymbolTable()), "A(0.1,0.33333334)");
    s.setPrecision(Precision::Double);
    EXPECT_EQ(s.toString(SymbolTable()), "A(0.10000000149011612,0.3333333432674408)")
        << "converting to double keeps the float's value";
}

// Where the two differ in what is derived, not only in digits: a condition that compares
// a sum of tenths with 1. In double, ten additions of 0.1 give 0.9999999999999999 < 1 and
// the production applies an eleventh time; stored as floats, the tenth sum is already
// 1.0000001 and the derivation stops there, as a float sum of ten 0.1f does in cpfg.
TEST(ParametricPrecision, ConditionOnARoundedSumCanGoEitherWay) {
    LSystem ls = parse(
        "Lsystem: 1\nderivation length: 12\naxiom: A(0)\n"
        "A(t) : t < 1 --> A(t+0.1)\nendlsystem\n");
    EXPECT_EQ(deriveWith(ls, -1, Precision::Double, 1).toString(ls.symbols),
              "A(1.0999999999999999)");
    EXPECT_EQ(deriveWith(ls, -1, Precision::Single, 1).toString(ls.symbols), "A(1.0000001)");
}

// `stats` counts the last step without writing it: the counts must be those of the
// string the step writes, for every path that counts (and none for blocks, which run in
// string order and are done in full).
TEST(ParametricPrecision, CountingTheNextStepAgreesWithDoingIt) {
    for (const Case& c : kCases) {
        LSystem ls = loadLSystem(benchModel(c.file));
        for (unsigned threads : {1u, 2u, 7u}) {
            DerivationOptions o;
            o.threads = threads;
            Derivation d(ls, o);
            d.run(c.steps - 1);
            std::vector<std::uint64_t> counted = d.countNextStep();
            if (std::string(c.file) == "param-blocks.l") {
                EXPECT_TRUE(counted.empty()) << "blocks are not counted";
                continue;
            }
            ASSERT_FALSE(counted.empty()) << c.file;
            EXPECT_EQ(d.stepsDone(), c.steps - 1) << "counting leaves the derivation as it was";
            d.step();
            EXPECT_EQ(counted, countSymbols(d.current(), ls.symbols.size(), 1))
                << c.file << " with " << threads << " threads";
        }
    }
}

// A memory limit the last step would pass is met by counting as by writing.
TEST(ParametricPrecision, CountingTheNextStepMeetsTheMemoryLimit) {
    LSystem ls = loadLSystem(benchModel("honda-2.6a.l"));
    DerivationOptions o;
    o.memoryLimit = 60'000;  // step 9 takes about 50 kB with step 8, step 10 about 100 kB
    Derivation d(ls, o);
    d.run(9);
    EXPECT_THROW(d.countNextStep(), Error);
}

// The command line: --precision picks the storage, the streamed string prints as the held
// one, a bad value is refused, and `stats --no-geometry` (the last step counted) gives the
// counts of `stats` (which walks the whole string with the turtle).
TEST(ParametricPrecision, CommandLine) {
    const std::string honda = benchModel("honda-2.6a.l");
    auto single = runGraftal("derive " + honda + " -n 1 -q");
    ASSERT_EQ(single.status, 0) << single.err;
    EXPECT_EQ(single.out, "!(10)F(1)[&(45)B(0.6,7.07)]/(137.5)A(0.9,7.07)\n");
    auto dbl = runGraftal("derive " + honda + " -n 1 -q --precision double");
    EXPECT_EQ(dbl.out,
              "!(10)F(1)[&(45)B(0.6,7.069999999999999)]/(137.5)A(0.9,7.069999999999999)\n");
    for (const char* p : {"", " --precision double"}) {
        auto held = runGraftal("derive " + honda + " -n 6 -q" + p);
        auto streamed = runGraftal("derive " + honda + " -n 6 -q --stream" + p);
        EXPECT_EQ(streamed.out, held.out) << p;
    }
    auto bad = runGraftal("derive " + honda + " -n 1 --precision half");
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.err.find("--precision"), std::string::npos) << bad.err;
    EXPECT_TRUE(bad.out.empty());

    for (const char* file : {"honda-2.6a.l", "param-conditions.l", "param-context.l"}) {
        auto counted = runGraftal("stats " + benchModel(file) + " -n 12 -q --no-geometry");
        auto walked = runGraftal("stats " + benchModel(file) + " -n 12 -q");
        ASSERT_EQ(counted.status, 0) << counted.err;
        ASSERT_EQ(walked.status, 0) << walked.err;
        auto c = nlohmann::json::parse(counted.out), w = nlohmann::json::parse(walked.out);
        EXPECT_EQ(c["modules"], w["modules"]) << file;
        EXPECT_EQ(c["symbols"], w["symbols"]) << file;
    }
}
