// cpfg's random numbers (`random: cpfg`, `--random cpfg`, and models read with a view file):
// the 48-bit generator of POSIX's drand48 family on cpfg's two states, drawn in cpfg's
// order (cpfg/generate.c, utility.c, control.c). The expected values are computed here with
// the C library's own seed48/drand48/erand48, the generator cpfg calls.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "graftal/core/cpfg_random.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

std::string derivedWith(const std::string& text, int steps, std::optional<RandomStreams> random,
                        std::optional<std::uint64_t> seed = std::nullopt) {
    LSystem ls = parse(text);
    DerivationOptions o;
    o.random = random;
    o.seed = seed;
    o.threads = 4;
    return derive(ls, steps, o).toString(ls.symbols);
}

}  // namespace

TEST(CpfgRandom, TheGeneratorIsTheCLibrarysDrand48) {
    unsigned short x[3] = {0x330E, 7, 0};
    Rand48 r(0x330E, 7, 0);
    for (int k = 0; k < 1000; ++k) ASSERT_EQ(r.next(), ::erand48(x)) << "draw " << k;

    unsigned short seed[3] = {1234, 0, 155};
    ::seed48(seed);
    CpfgRandom cpfg(1234);
    for (int k = 0; k < 1000; ++k) ASSERT_EQ(cpfg.production(), ::drand48()) << "draw " << k;
}

TEST(CpfgRandom, SrandAndRanFollowCpfgsState) {
    CpfgRandom cpfg;
    unsigned short x[3] = {0x330E, 0, 0};  // cpfg's state before any srand(), as srand(0)
    EXPECT_EQ(cpfg.ran(10), ::erand48(x) * 10);
    cpfg.srand(70000);  // 70000 = 0x11170: the low and high 16 bits go to words 1 and 2
    unsigned short y[3] = {0x330E, 0x1170, 0x1};
    for (int k = 0; k < 5; ++k) EXPECT_EQ(cpfg.ran(1), ::erand48(y));
    // biran counts draws <= p.
    cpfg.srand(3);
    unsigned short z[3] = {0x330E, 3, 0};
    int hits = 0;
    for (int k = 0; k < 20; ++k) hits += ::erand48(z) <= 0.3 ? 1 : 0;
    EXPECT_EQ(cpfg.biran(20, 0.3), hits);
}

// cpfg's nran: before any srand() the first call gives the mean; then pairs from the polar
// method, the second of each pair kept for the next call.
TEST(CpfgRandom, NranIsThePolarMethodInPairs) {
    CpfgRandom cpfg;
    EXPECT_EQ(cpfg.nran(5, 2), 5);
    cpfg.srand(11);
    unsigned short x[3] = {0x330E, 11, 0};
    double v1, v2, rsq;
    do {
        v1 = 2 * ::erand48(x) - 1;
        v2 = 2 * ::erand48(x) - 1;
        rsq = v1 * v1 + v2 * v2;
    } while (rsq >= 1 || rsq == 0);
    const double fac = std::sqrt(-2 * std::log(rsq) / rsq);
    EXPECT_DOUBLE_EQ(cpfg.nran(1, 3), v2 * fac * 3 + 1);
    EXPECT_DOUBLE_EQ(cpfg.nran(0, 1), v1 * fac);
    const double b = cpfg.bran(2, 3);
    EXPECT_GT(b, 0);
    EXPECT_LT(b, 1);
}

// A stochastic L-system (cpfg: one with a `seed:` line) draws once per module, whether a
// production applies to it or not, and counts the draw down through the applicable
// productions' probabilities in 32-bit floats. cpfg's batch run (the string it saves)
// starts from the C library's initial state whatever `seed:` says; a seed given to the
// derivation sets it as cpfg's interactive run does with that seed (seed48).
TEST(CpfgRandom, StochasticProductionsDrawOncePerModule) {
    const std::string text =
        "Lsystem: 1\nseed: 42\nderivation length: 1\nAxiom: AXAXAXAXAXAXAXAX\n"
        "A --> B : 0.3\nA --> C : 0.7\nendlsystem\n";
    auto expectedFrom = [](auto draw) {
        std::string expected;
        for (int k = 0; k < 8; ++k) {
            float u = static_cast<float>(static_cast<double>(1.0f) * draw());
            expected += (u -= 0.3f) <= 0 ? "B" : "C";
            draw();  // X draws too
            expected += "X";
        }
        return expected;
    };
    Rand48 fresh;  // glibc's drand48 before any seeding: X = 0
    const std::string batch = expectedFrom([&] { return fresh.next(); });
    EXPECT_EQ(derivedWith(text, 1, RandomStreams::Cpfg), batch);
    // The same with `random: cpfg` in the file, for any thread count.
    std::string inFile = text;
    inFile.replace(inFile.find("seed: 42"), 8, "seed: 42\nrandom: cpfg");
    EXPECT_EQ(derivedWith(inFile, 1, std::nullopt), batch);

    unsigned short seed[3] = {42, 0, 155};
    ::seed48(seed);
    const std::string seeded = expectedFrom([] { return ::drand48(); });
    EXPECT_EQ(derivedWith(text, 1, RandomStreams::Cpfg, 42), seeded);
    EXPECT_NE(seeded, batch);
}

// Without `seed:` cpfg's L-system is deterministic: the probabilities are not read and the
// first applicable production applies. A seed of 0 is a stochastic L-system drawing from
// the C library's initial state (X = 0).
TEST(CpfgRandom, WithoutASeedLineTheFirstProductionApplies) {
    const std::string body =
        "derivation length: 1\nAxiom: AAAA\nA --> B : 0.1\nA --> C : 0.9\nendlsystem\n";
    EXPECT_EQ(derivedWith("Lsystem: 1\n" + body, 1, RandomStreams::Cpfg), "BBBB");
    Rand48 fresh;  // glibc's drand48 before any seeding
    std::string expected;
    for (int k = 0; k < 4; ++k) {
        float u = static_cast<float>(static_cast<double>(1.0f) * fresh.next());
        expected += (u -= 0.1f) <= 0 ? "B" : "C";
    }
    EXPECT_EQ(derivedWith("Lsystem: 1\nseed: 0\n" + body, 1, RandomStreams::Cpfg), expected);
}

// ran() and srand() in blocks and successors share cpfg's second state, in string order.
TEST(CpfgRandom, RanInBlocksAndSuccessorsDrawsInStringOrder) {
    const std::string text =
        "Lsystem: 1\nderivation length: 1\nStart: {srand(9);}\nAxiom: A(0)A(0)A(0)\n"
        "A(x) --> A(ran(100))B(ran(1))\nendlsystem\n";
    unsigned short x[3] = {0x330E, 9, 0};
    std::vector<float> v;
    for (int k = 0; k < 6; ++k) v.push_back(static_cast<float>(::erand48(x) * (k % 2 ? 1 : 100)));
    ModuleString s = [&] {
        LSystem ls = parse(text);
        DerivationOptions o;
        o.random = RandomStreams::Cpfg;
        return derive(ls, 1, o);
    }();
    ASSERT_EQ(s.size(), 6u);
    for (std::size_t k = 0; k < 6; ++k) EXPECT_FLOAT_EQ(s.params(k)[0], v[k]) << "module " << k;
}

// graftal's streams stay the default for a .l file read alone; a model read with a view
// file is cpfg's, unless its .l says `random: graftal`.
TEST(CpfgRandom, AViewFileAsksForCpfgsNumbers) {
    TempDir dir;
    const std::string text =
        "Lsystem: 1\nseed: 7\nderivation length: 1\nAxiom: AAAAAAAAAAAAAAAAAAAA\n"
        "A --> B : 1\nA --> C : 1\nendlsystem\n";
    EXPECT_EQ(parse(text).random, RandomStreams::Graftal);
    ParseOptions o;
    o.viewFile = dir.write("m.v", "angle increment: 30\n").string();
    ParseResult r = loadModel(dir.write("m.l", text), o);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.model.lsystem.random, RandomStreams::Cpfg);
    EXPECT_EQ(derive(r.model.lsystem, 1).toString(r.model.lsystem.symbols),
              derivedWith(text, 1, RandomStreams::Cpfg));
    std::string own = text;
    own.replace(own.find("seed: 7"), 7, "seed: 7\nrandom: graftal");
    r = loadModel(dir.write("m.l", own), o);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.model.lsystem.random, RandomStreams::Graftal);
    EXPECT_EQ(derive(r.model.lsystem, 1).toString(r.model.lsystem.symbols),
              derivedWith(text, 1, RandomStreams::Graftal));
}

TEST(CpfgRandom, TheRandomLineIsCheckedAndPrinted) {
    EXPECT_NE(parseError("Lsystem: 1\nrandom: dice\nAxiom: A\nendlsystem\n").find("random:"),
              std::string::npos);
    std::ostringstream printed;
    parse("Lsystem: 1\nrandom: cpfg\nAxiom: A\nendlsystem\n").print(printed);
    EXPECT_NE(printed.str().find("random: cpfg"), std::string::npos) << printed.str();
}

// cpfg cuts a branch at `%` as the step reaches it, so a module before the `%` still sees
// what follows it in its context; graftal's own derivation cuts before the step.
TEST(CpfgRandom, ACutHappensWhereTheStepReachesIt) {
    const std::string text =
        "Lsystem: 1\nderivation length: 1\nignore: %\nAxiom: B[A%C]D\n"
        "A > C --> X\nendlsystem\n";
    EXPECT_EQ(derivedWith(text, 1, RandomStreams::Cpfg), "B[X]D");
    EXPECT_EQ(derivedWith(text, 1, RandomStreams::Graftal), "B[A]D");
}

// A model read with a view file asks for cpfg's streams, but one that never draws keeps the
// parallel rewriting and the counted last step: what it draws decides, not the setting.
TEST(CpfgRandom, OnlyAModelThatDrawsIsHeldToCpfgsOrder) {
    const std::string honda =
        "Lsystem: 1\nderivation length: 6\naxiom: A(1,10)\n"
        "A(l,w) : * --> !(w)F(l)[&(45)B(l*0.6,w*0.707)]/(137.5)A(l*0.9,w*0.707)\n"
        "B(l,w) : * --> !(w)F(l)[-(45)@vB(l*0.6,w*0.707)]B(l*0.9,w*0.707)\nendlsystem\n";
    EXPECT_FALSE(parse(honda).drawsRandomNumbers());
    EXPECT_TRUE(parse("Lsystem: 1\naxiom: A\nA --> B : 0.3\nA --> C : 0.7\nendlsystem\n")
                    .drawsRandomNumbers());
    EXPECT_TRUE(parse("Lsystem: 1\naxiom: A(1)\nA(x) --> A(x+ran(1))\nendlsystem\n")
                    .drawsRandomNumbers());
    EXPECT_TRUE(parse("Lsystem: 1\naxiom: A(1)\nA(x) : ran(1) < 0.5 --> B\nendlsystem\n")
                    .drawsRandomNumbers());
    EXPECT_TRUE(parse("Lsystem: 1\naxiom: A(1)\nA(x) : { y = nran(0, 1); } * --> A(y)\n"
                      "endlsystem\n")
                    .drawsRandomNumbers());
    // The string is the same with either generator, and for any thread count.
    EXPECT_EQ(derivedWith(honda, 6, RandomStreams::Cpfg),
              derivedWith(honda, 6, RandomStreams::Graftal));
}
