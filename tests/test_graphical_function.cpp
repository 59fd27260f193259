// cpfg's graphical functions: func(id, x) over .func files and .fset function sets named by
// the view file. The expected numbers are cpfg's (its oracle: s07_func, s07_fset) or follow
// from cpfg's method, reasoned in each test.
#include <gtest/gtest.h>

#include <string>

#include "graftal/graftal.hpp"
#include "graftal/lang/graphical_function.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

// The line y = 1 + x: four control points evenly spaced, so the B-spline is the line and
// x(t) = t.
const char* kLine =
    "fver 1 1\nname: line\nsamples: 0\nflip: off\npoints: 4\n"
    "0 1\n0.333333 1.333333\n0.666667 1.666667\n1 2\n";

// y = 3t(1 - t) with x = t, sampled at 5 points.
const char* kBump =
    "fver 1 1\nname: bump\nsamples: 5\nflip: off\npoints: 4\n"
    "0 0\n0.333333 1\n0.666667 1\n1 0\n";

std::string derivedWith(const TempDir& dir, const std::string& l, const std::string& v) {
    ParseOptions o;
    o.viewFile = dir.write("m.v", v).string();
    Model m = loadModel(dir.write("m.l", l), o).orThrow();
    return derive(m, -1).toString(m.lsystem.symbols);
}

}  // namespace

TEST(GraphicalFunction, BisectionStopsWithinAThousandthAsCpfgDoes) {
    GraphicalFunction f = parseFunctionFile(kLine, "line.func");
    EXPECT_EQ(f.name(), "line");
    EXPECT_NEAR(f.value(0.5), 1.5, 1e-6) << "t = 0.5 at once";
    // t: 0.5, 0.25, 0.375, 0.3125, 0.28125, 0.296875, 0.3046875, 0.30078125 (within 0.001).
    EXPECT_NEAR(f.value(0.3), 1.30078125, 1e-5);
    // x is clamped to [0, 1]; the search then stops at t = 2^-10 and 1 - 2^-10.
    EXPECT_NEAR(f.value(-1), 1.0009765625, 1e-5);
    EXPECT_NEAR(f.value(2), 1.9990234375, 1e-5);
}

TEST(GraphicalFunction, SamplesAreInterpolatedLinearly) {
    GraphicalFunction f = parseFunctionFile(kBump, "bump.func");
    EXPECT_EQ(f.samples(), 5);
    EXPECT_NEAR(f.value(0.25), 0.5625, 1e-5);
    EXPECT_NEAR(f.value(0.6), 0.75 + 0.4 * (0.5625 - 0.75), 1e-5) << "between f(0.5) and f(0.75)";
    EXPECT_NEAR(f.value(0), 0.00292683, 1e-6) << "the sample at 0 is y(2^-10)";
}

TEST(GraphicalFunction, TheOldFormatTakesItsSamplesFromTheViewLine) {
    GraphicalFunction f = parseFunctionFile(
        "range: 0.0 1.0\npoints: 4\n0 0\n0.25 0.5\n0.75 1.5\n1 2\n", "old.func", 3);
    EXPECT_EQ(f.samples(), 3);
    EXPECT_NEAR(f.value(0.5), 1, 1e-6);
    EXPECT_NEAR(f.value(0.25), 0.500733, 1e-5) << "cpfg: O(1,0.500733,1.49927)";
    EXPECT_NEAR(f.value(0.75), 1.49927, 1e-5);
}

TEST(GraphicalFunction, ARepeatedPointAndAFunctionSet) {
    std::vector<GraphicalFunction> set =
        parseFunctionSet("funcgalleryver 1 1\nitems: 2\n" + std::string(kLine) +
                             "fver 1 1\nname: hump\nsamples: 3\nflip: off\npoints: 4\n"
                             "0 0\n0.25 1 2\n0.75 1\n1 0\n",
                         "set.fset");
    ASSERT_EQ(set.size(), 2u);
    EXPECT_EQ(set[1].name(), "hump");
    EXPECT_EQ(set[1].points().size(), 5u) << "the third number repeats the point";
    // cpfg's string for these functions: H(2,0.980419,0.491673).
    EXPECT_NEAR(set[1].value(0.5), 0.980419, 1e-5);
    EXPECT_NEAR(set[1].value(0.25), 0.491673, 1e-5);
}

TEST(GraphicalFunction, ErrorsNameTheFileAndLine) {
    try {
        parseFunctionFile("fver 1 1\nname: x\nsamples: 0\nflip: off\npoints: 4\n0 0\n1 q\n",
                          "bad.func");
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.diagnostics().front().toString().rfind("bad.func:7:", 0), 0u)
            << e.diagnostics().front().toString();
    }
    EXPECT_THROW(
        parseFunctionFile("fver 1 1\nname: x\nsamples: 0\nflip: off\npoints: 3\n", "few.func"),
        Error)
        << "a B-spline of cpfg needs four points";
}

TEST(GraphicalFunction, FuncReadsTheViewFilesFunctions) {
    TempDir dir;
    dir.write("line.func", kLine);
    dir.write("bump.func", kBump);
    std::string got = derivedWith(dir,
                                  "Lsystem: 1\nderivation length: 1\nAxiom: A\n"
                                  "A --> L(func(1,0.5), func(1,2)) B(func(2,0.6))\nendlsystem\n",
                                  "function: line.func\nfunction: bump.func\n");
    EXPECT_EQ(got.rfind("L(1.5,1.99902", 0), 0u) << got << " (cpfg: L(1.5,1.99902)B(0.675))";
    EXPECT_NE(got.find(")B(0.675)"), std::string::npos) << got;
    dir.write("set.fset", "funcgalleryver 1 1\nitems: 1\n" + std::string(kBump));
    EXPECT_EQ(derivedWith(dir,
                          "Lsystem: 1\nderivation length: 1\nAxiom: A\n"
                          "A --> B(func(1,0.25))\nendlsystem\n",
                          "function set: set.fset\n"),
              "B(0.5625)");
}

TEST(GraphicalFunction, AnUnknownIdOrFileIsAnError) {
    TempDir dir;
    dir.write("line.func", kLine);
    EXPECT_THROW(derivedWith(dir,
                             "Lsystem: 1\nderivation length: 1\nAxiom: A\n"
                             "A --> B(func(2,0.5))\nendlsystem\n",
                             "function: line.func\n"),
                 Error);
    ParseOptions o;
    o.viewFile = dir.write("m.v", "\nfunction: missing.func\n").string();
    // A view file's problem is a warning (cpfg forgives its view files).
    ParseResult r = loadModel(dir.write("m.l", "Lsystem: 1\nAxiom: A\n\nendlsystem\n"), o);
    ASSERT_TRUE(r.ok());
    ASSERT_FALSE(r.warnings().empty());
    EXPECT_EQ(r.warnings().front().location.line, 2);
    EXPECT_NE(r.warnings().front().message.find("missing.func"), std::string::npos);
    EXPECT_NE(parseError("Lsystem: 1\nAxiom: A(tfunc(1,0))\n\nendlsystem\n").find("tfunc"),
              std::string::npos);
}

TEST(GraphicalFunction, AModelFolderGivesItsFunctionSetAndColourMap) {
    // cpfg takes a .map on its command line (-m) and a .fset through the view file; a folder
    // given alone uses its one of each (a view file's function lines win over the set).
    TempDir dir;
    dir.write("m.l",
              "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> B(func(1,0.25))\nendlsystem\n");
    dir.write("m.v", "angle increment: 30\n");
    dir.write("functions.fset", "funcgalleryver 1 1\nitems: 1\n" + std::string(kBump));
    dir.write("colours.map", std::string(768, '\x40'));
    Model m = loadModel(dir.path()).orThrow();
    EXPECT_NEAR(derive(m, -1).params(0)[0], 0.5625, 1e-5);
    EXPECT_EQ(m.view.materials.colorMap, "colours.map");
    dir.write("line.func", kLine);
    dir.write("m.v", "function: line.func\n");
    Model v = loadModel(dir.path()).orThrow();
    EXPECT_NEAR(derive(v, -1).params(0)[0], 1.25, 1e-5);
}
