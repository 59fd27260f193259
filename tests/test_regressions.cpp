// Inputs that once crashed graftal, hung it or took memory without bound. Each must end in a
// clear error with its location or in a bounded result.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>

#include <sys/resource.h>
#include <sys/wait.h>

#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parseError;
using graftal::testing::readFile;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace {

std::string regression(const std::string& name) {
    return std::string(GRAFTAL_TESTS_DIR) + "/regressions/" + name;
}

// CPU seconds of this process and of the children it has waited for: unlike the wall clock,
// not stretched when other work shares the machine.
double cpuSeconds() {
    double t = 0;
    for (int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
        rusage u{};
        getrusage(who, &u);
        t += static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
             static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
    }
    return t;
}

double secondsSince(double start) {
    return cpuSeconds() - start;
}

// The red, green and blue of pixel (x, y) of a PNG file, or -1 when it cannot be read.
int rgbAt(const std::string& path, int x, int y) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
    int v = -1;
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
        cairo_surface_flush(s);
        const unsigned char* row =
            cairo_image_surface_get_data(s) + y * cairo_image_surface_get_stride(s);
        std::uint32_t argb;
        std::memcpy(&argb, row + 4 * x, 4);
        v = static_cast<int>(argb & 0xffffff);
    }
    cairo_surface_destroy(s);
    return v;
}

}  // namespace

TEST(Regressions, AFormalMadeOfVerticalTabIsNotAName) {
    std::string text = readFile(regression("blank-formal.l"));
    ASSERT_EQ(text, "0(\v)->");
    EXPECT_EQ(
        parseError(text),
        "test.l:1:3: error: a predecessor names its parameters (e.g. A(x,y)); '' is not a name");
    auto r = runGraftal("derive " + regression("blank-formal.l"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("blank-formal.l:1:3"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(Regressions, DeeplyNestedParenthesesAreAnErrorNotAStackOverflow) {
    auto nested = [](int depth) {
        return "Lsystem: 1\naxiom: F(" + std::string(depth, '(') + "1" + std::string(depth, ')') +
               ")\nendlsystem\n";
    };
    EXPECT_EQ(parseError(nested(200)), "");
    EXPECT_EQ(parseError(nested(10200)),
              "test.l:2:266: error: expression nested more than 256 levels deep");
    EXPECT_EQ(parseError("Lsystem: 1\naxiom: F(" + std::string(10000, '-') + "1)\nendlsystem\n"),
              "test.l:2:266: error: expression nested more than 256 levels deep");
    TempDir t;
    auto f = t.write("deep.l", nested(10200));
    auto r = runGraftal("derive " + f.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("deep.l:2:266: error: expression nested"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(Regressions, DeeplyNestedBranchesAreDerivedAndDrawn) {
    const int depth = 100000;
    TempDir t;
    auto f = t.write("branches.l", "Lsystem: 1\nderivation length: 1\naxiom: A" +
                                       std::string(depth, '[') + "F" + std::string(depth, ']') +
                                       "B\nF --> F[+F]\nA > B --> C\nendlsystem\n");
    auto r = runGraftal("stats " + f.string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"segments\": 2"), std::string::npos) << r.out.substr(0, 300);
    r = runGraftal("render -o " + (t.path() / "b.png").string() + " " + f.string());
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST(Regressions, ADefineUsedTwiceInEachOfTwentyFiveLevelsIsRefusedAtItsUse) {
    // Each define uses the previous one twice: as text (cpfg's C preprocessor), Z is 2^25
    // terms. The preprocessor stops at its limit, with an error at the line of the use,
    // quickly and without running out of memory.
    double start = cpuSeconds();
    auto r = runGraftal("derive " + regression("define-doubling.l"));
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.err.find("define-doubling.l:27:1: error: a macro expands to more text"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_LT(secondsSince(start), 5);
}

TEST(Regressions, ADefineDoublingAParameterStopsAtAClearLimit) {
    std::string text = "Lsystem: 1\n#define A x\n";
    for (char c = 'B'; c <= 'Z'; ++c)
        text += std::string("#define ") + c + " " + char(c - 1) + "+" + char(c - 1) + "\n";
    text += "axiom: F(1)\nF(x) --> F(Z)\nendlsystem\n";
    EXPECT_EQ(parseError(text).rfind("test.l:29:1: error: a macro expands to more text", 0), 0u)
        << parseError(text);
    // Small chains still work, and a define that cannot be evaluated alone (1/0) is only an
    // error where it is evaluated.
    LSystem ls = graftal::testing::parse(
        "Lsystem: 1\nderivation length: 1\n#define A x\n#define B A+A\n#define C B*B\n"
        "#define BAD 1/0\naxiom: F(3)\nF(x) --> F(C)F(0 && BAD)\nendlsystem\n");
    // Macros are text, as in cpfg: C is x+x*x+x, not (x+x)*(x+x).
    EXPECT_EQ(graftal::testing::derived(ls, 1), "F(15)F(0)");
}

TEST(Regressions, AHugeWidthOnAZeroLengthSegmentFillsThePictureQuickly) {
    // A dot of width 1e12: its round cap covers the picture, and drawing it is bounded.
    TempDir t;
    for (std::string how : {"", "--stream "}) {
        auto png = (t.path() / "dot.png").string();
        double start = cpuSeconds();
        auto r = runGraftal("render " + how + "-o " + png + " " + regression("huge-width-dot.l"));
        EXPECT_EQ(r.status, 0) << how << r.err;
        EXPECT_LT(secondsSince(start), 10) << how;
        EXPECT_EQ(rgbAt(png, 0, 0), rgbAt(png, 400, 400)) << how << "the corner is inked too";
        EXPECT_NE(rgbAt(png, 0, 0), 0xffffff) << how;
    }
    auto pdf = (t.path() / "dot.pdf").string();
    double start = cpuSeconds();
    auto r = runGraftal("render -o " + pdf + " " + regression("huge-width-dot.l"));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_LT(secondsSince(start), 10);
    EXPECT_EQ(readFile(pdf).substr(0, 5), "%PDF-");
}

TEST(Regressions, AHugeSvgStrokeWidthIsClampedNotOverflowed) {
    TempDir t;
    auto f = t.write("wide.l", "axiom: !(1e30)F\n");
    auto svg = (t.path() / "wide.svg").string();
    auto r = runGraftal("render -o " + svg + " " + f.string());
    EXPECT_EQ(r.status, 0) << r.err;
    std::string text = readFile(svg);
    auto at = text.find("stroke-width=\"");
    ASSERT_NE(at, std::string::npos) << text;
    EXPECT_EQ(text.substr(at, 20), "stroke-width=\"3200\" ") << "twice width plus height";
}

TEST(Regressions, ATableCountAboveTheIntRangeIsNamedAsSuch) {
    EXPECT_EQ(
        parseError("table schedule: m 4e44\n").substr(0, 83),
        "test.l:1:19: error: a table runs for a whole number of steps from 0 to 2147483647, ");
    auto r = runGraftal("derive " + regression("schedule-count-too-large.l"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("schedule-count-too-large.l:8:22: error: a table runs for a whole "
                         "number of steps from 0 to 2147483647"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("may omit its step count"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(Regressions, ASeedBeyondSixtyFourBitsIsAnError) {
    std::string e = parseError("seed: 1e20\naxiom: F\n");
    EXPECT_EQ(e.substr(0, 7), "test.l:") << e;
    EXPECT_NE(e.find("seed must be a whole number from 0 to 2^64 - 1"), std::string::npos) << e;
    EXPECT_EQ(parseError("seed: 18446744073709549568\naxiom: F\n"), "") << "the largest below";
}

TEST(Regressions, OutOfRangeColourIndicesAreClamped) {
    LSystem ls = graftal::testing::parse(
        "Lsystem: 1\naxiom: F;(-1)F;(70000)F,(2.7)F'(1e300)F\nendlsystem\n");
    Scene s = interpret(ls, ViewSettings{}, derive(ls, 0));
    ASSERT_EQ(s.segments.size(), 5u);
    EXPECT_EQ(s.segments[1].color, 0);
    EXPECT_EQ(s.segments[2].color, 65535);
    EXPECT_EQ(s.segments[3].color, 2);
    EXPECT_EQ(s.segments[4].color, 65535);
}

TEST(Regressions, ATinyOccupancyCellKeepsCellIndicesInRange) {
    // 1e-300 cells: the cell index of x = 1 is 1e300, far beyond int64; clamped, the two
    // points far apart still fall in different cells and the two at the origin share one.
    LSystem ls = graftal::testing::parse(
        "Lsystem: 1\nenvironment: occupancy cell 1e-300\n"
        "axiom: ?E(9) ?E(9) f(1) ?E(9) [+(180) f(2) ?E(9)]\nendlsystem\n");
    EXPECT_EQ(graftal::testing::derived(ls, 0), "?E(1)?E(1)f(1)?E(0)[+(180)f(2)?E(0)]");
}

TEST(Regressions, OccupancyRadiusWithEveryModuleAtOnePointIsLinear) {
    // 2^16 modules at the origin: each sees the 65535 others, without comparing every pair.
    double start = cpuSeconds();
    auto r = runGraftal("derive -n 16 " + regression("occupancy-one-point.l"));
    EXPECT_EQ(r.status, 0) << r.err;
    std::string expected;
    for (int i = 0; i < 65536; ++i) expected += "?E(65535)";
    EXPECT_TRUE(r.out == expected + "\n") << r.out.substr(0, 100);
    EXPECT_LT(secondsSince(start), 10);
}

TEST(Regressions, OccupancyRadiusCountsEachNeighbourOnceAcrossBuckets) {
    // Points 0.3 apart on a line, radius 1: three neighbours on each side inside the line.
    std::string axiom;
    for (int i = 0; i < 12; ++i) axiom += "?E(9)f(0.3)";
    LSystem ls = graftal::testing::parse(
        "Lsystem: 1\nenvironment: occupancy radius 1\naxiom: " + axiom + "\nendlsystem\n");
    std::string expected;
    for (int i = 0; i < 12; ++i) {
        int n = std::min(i, 3) + std::min(11 - i, 3);
        expected += "?E(" + std::to_string(n) + ")f(0.3)";
    }
    EXPECT_EQ(graftal::testing::derived(ls, 0), expected);
}

TEST(Regressions, ATableCountThatFailsToEvaluateIsCollectedWithTheOtherErrors) {
    try {
        graftal::testing::parse(
            "Lsystem: 1\ntable: T\ntable schedule: T sqrt(-1)\naxiom: F(\nendlsystem\n");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        ASSERT_EQ(e.diagnostics().size(), 2u) << e.what();
        EXPECT_EQ(e.diagnostics()[0].location.line, 3);
        EXPECT_EQ(e.diagnostics()[1].location.line, 4);
    }
}

TEST(Regressions, GrowthPredictionStaysExactUpToAThousandDigitsThenEstimates) {
    LSystem ls = graftal::testing::parse("Lsystem: 1\naxiom: F\nF --> FF\nendlsystem\n");
    GrowthPrediction g = predictGrowth(ls, 3000);
    ASSERT_TRUE(g.exact);
    EXPECT_EQ(g.modules[3000].digits(), 904u) << "2^3000";
    EXPECT_EQ(g.modules[64].toString(), "18446744073709551616");
    double start = cpuSeconds();
    g = predictGrowth(ls, 1000000);
    EXPECT_LT(secondsSince(start), 5);
    EXPECT_FALSE(g.exact);
    EXPECT_TRUE(g.expected);
    ASSERT_EQ(g.expectedModules.size(), 1000001u);
    EXPECT_EQ(g.expectedModules[64], 18446744073709551616.0);
}

TEST(Regressions, AMillionDoublingsAreRefusedQuickly) {
    double start = cpuSeconds();
    auto r = runGraftal("derive " + regression("million-doublings.l"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("a string of more than 10^308 modules, far more than any memory; "
                         "lower -n\n"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "");
    r = runGraftal("stats --predict " + regression("million-doublings.l"));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"prediction\": \"expected\""), std::string::npos);
    EXPECT_LT(secondsSince(start), 10);
}

TEST(Regressions, SubtreeSummariesStayWithinTheMemoryLimit) {
    // 150,000 steps of F --> F: the summaries' table alone would take over a gigabyte.
    // Under a 512 MB address-space limit the render must still succeed.
    TempDir t;
    auto png = (t.path() / "long.png").string();
    std::string cmd = "ulimit -v 524288; " + std::string(GRAFTAL_EXE) + " render -o " + png +
                      " --memory-limit 64M " + regression("long-identity-derivation.l") +
                      " > /dev/null 2>&1";
    int raw = std::system(("sh -c '" + cmd + "'").c_str());
    EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << raw;
    EXPECT_EQ(readFile(png).substr(1, 3), "PNG");
    EXPECT_FALSE(streamedPictureIsSummarised(
        Model{graftal::testing::parse(readFile(regression("long-identity-derivation.l"))), {}},
        150000, std::size_t(64) << 20));
}

TEST(Regressions, StreamingKeepsEveryParameterOfAModule) {
    std::string args;
    for (int i = 0; i < 70; ++i) args += (i ? "," : "") + std::to_string(i);
    TempDir t;
    auto f = t.write("wide.l", "Lsystem: 1\nderivation length: 1\naxiom: A\nA --> B(" + args +
                                   ")\nendlsystem\n");
    auto held = runGraftal("derive " + f.string());
    auto streamed = runGraftal("derive --stream " + f.string());
    EXPECT_EQ(held.out, "B(" + args + ")\n");
    EXPECT_EQ(streamed.out, held.out) << streamed.err;
}

TEST(Regressions, ADerivationOwnsItsLSystem) {
    Derivation d(parseLSystem("Lsystem: 1\naxiom: b\na --> ab\nb --> a\nendlsystem\n"));
    d.run(5);
    EXPECT_EQ(d.current().toString(parseLSystem("Lsystem: 1\naxiom: b\nendlsystem\n").symbols),
              "abaababa");
    LSystem ls = parseLSystem("Lsystem: 1\naxiom: b\na --> ab\nb --> a\nendlsystem\n");
    Derivation e(ls);
    ls.productions.clear();
    e.run(2);
    EXPECT_EQ(e.current().toString(ls.symbols), "ab") << "a copy: later changes do not leak in";
}

TEST(Regressions, APopOnAnEmptyTurtleStackIsAnError) {
    // Files cannot say it (the parser balances brackets), but a program can build one.
    auto expectStackError = [](const std::function<void()>& f, const char* what) {
        try {
            f();
            ADD_FAILURE() << what << ": no error";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("pops an empty turtle stack"), std::string::npos)
                << what << ": " << e.what();
        }
    };
    LSystem ls = graftal::testing::parse("Lsystem: 1\naxiom: F\nendlsystem\n");
    ls.axiom = ModuleString();
    ls.axiom.push('F');
    ls.axiom.push(']');
    ls.axiom.push('F');
    const Model m{ls, {}};
    expectStackError([&] { interpret(m, derive(ls, 0)); }, "interpret");
    expectStackError([&] { interpretStreamed(m, 0); }, "interpretStreamed");
    expectStackError([&] { measureStreamed(m, 0); }, "measureStreamed");
    expectStackError([&] { measureModules(m, ls.axiom); }, "measureModules");

    // A homomorphism whose successor (changed after parsing) closes a branch never opened.
    LSystem h =
        graftal::testing::parse("Lsystem: 1\naxiom: FA\nhomomorphism\nA --> F\nendlsystem\n");
    h.homomorphism[0].successor.push_back(h.homomorphism[0].successor[0]);
    h.homomorphism[0].successor.back().symbol = ']';
    expectStackError([&] { interpret(h, ViewSettings{}, applyHomomorphism(h, derive(h, 0))); },
                     "homomorphism");
}
