// cpfg's curves (curveX/Y/Z and curveGAL over `curve:` files), contour sets (.cset), function
// sets with old-format items, and tfunc. cpfg cannot be run here, so every expected number
// is reasoned from cpfg's source (curveXYZ.cpp, curveXYZc.cpp, splinefun.cpp, splinearr.cpp,
// interpret.c's view-file reader, lsys_input.l), the reasoning in the test.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "graftal/graftal.hpp"
#include "graftal/lang/contour_file.hpp"
#include "graftal/lang/curve_xyz.hpp"
#include "graftal/lang/graphical_function.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

std::string derivedWith(const TempDir& dir, const std::string& l, const std::string& v) {
    ParseOptions o;
    o.viewFile = dir.write("m.v", v).string();
    Model m = loadModel(dir.write("m.l", l), o).orThrow();
    return derive(m, -1).toString(m.lsystem.symbols);
}

std::string firstError(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "no error";
}

// Four control points 0, 1, 2, 3 along x (dimension 2 and type bspline, the defaults).
const char* kRuler = "points: 4\n0 0\n1 0\n2 0\n3 0\n";

const char* kOneStep = "Lsystem: 1\nderivation length: 1\nAxiom: A\n";

}  // namespace

TEST(CpfgCurves, AUniformBSplineRunsFromTheSecondPointAlmostToTheThird) {
    // cpfg evaluates the uniform cubic B-spline at knot 3 + u (n - 3.000001): for four
    // points one span, knots 3 to 3.999999. Control points k along x reproduce the line
    // x = knot - 2, so x runs from 1 to 1.999999, evenly in u; the length table is then
    // linear and t maps to u unchanged: curveX(1, t) = 1 + 0.999999 t.
    CurveXYZ c = parseCurveFile(kRuler, "ruler.crv", 100);
    EXPECT_NEAR(c.atLength(0).x, 1.0, 1e-12);
    EXPECT_NEAR(c.atLength(0.5).x, 1.4999995, 1e-9);
    EXPECT_NEAR(c.atLength(1).x, 1.999999, 1e-9);
    EXPECT_NEAR(c.atLength(7).x, 1.999999, 1e-9) << "t is clamped to [0, 1]";
    EXPECT_NEAR(c.atLength(-1).x, 1.0, 1e-12);
    EXPECT_NEAR(c.length(), 0.999999, 1e-9) << "curveGAL: the sampled polyline's length";
    EXPECT_EQ(c.atLength(0.5).y, 0.0);
}

TEST(CpfgCurves, TIsAShareOfTheLengthNotTheCurveParameter) {
    // A Bézier of the points (0,0) (0,0) (1,0) (1,0): x(u) = 3u^2 - 2u^3 (u = t / 1.000001),
    // slow at both ends. By parameter, u = 0.25 gives x = 0.15625; by length, what curveX
    // reads, the point a quarter of the way along is x = 0.25, up to the linear
    // interpolation between cpfg's samples (100 here: within 1e-4).
    CurveXYZ c = parseCurveFile("points: 4\ntype: bezier\n0 0\n0 0\n1 0\n1 0\n", "s.crv", 100);
    EXPECT_NEAR(c.atParameter(0.25).x, 0.15625, 1e-6);
    EXPECT_NEAR(c.atLength(0.25).x, 0.25, 1e-4);
    EXPECT_NEAR(c.atLength(0.9).x, 0.9, 1e-4);
    EXPECT_NEAR(c.length(), 1.0, 1e-5);
}

TEST(CpfgCurves, EndPointPhantomAndClosedBSplines) {
    // bspline-endpoint: clamped knots, so four points make one Bézier-like span from the
    // first point to (almost) the last: on the line (0,0) .. (3,6), x = 3 * 0.999999 t.
    CurveXYZ e =
        parseCurveFile("points: 4\ntype: bspline-endpoint\n0 0\n1 2\n2 4\n3 6\n", "e.crv", 100);
    EXPECT_NEAR(e.atLength(0.5).x, 1.4999985, 1e-9);
    EXPECT_NEAR(e.atLength(0.5).y, 2.999997, 1e-9);
    // bspline-phantom: cpfg adds 2 p0 - p1 before and 2 p(n-1) - p(n-2) after, so the ruler
    // 0..3 becomes -1..4 (six points, knots 3 to 5.999999): x = knot - 3, 0 to 2.999999.
    CurveXYZ p =
        parseCurveFile("points: 4\ntype: bspline-phantom\n0 0\n1 0\n2 0\n3 0\n", "p.crv", 100);
    EXPECT_NEAR(p.atLength(0).x, 0.0, 1e-12);
    EXPECT_NEAR(p.atLength(1).x, 2.999999, 1e-9);
    // bspline-closed: the first three points are repeated at the end. At t = 0 the knot is
    // 3 and the basis weights are 1/6, 2/3, 1/6: (p0 + 4 p1 + p2) / 6 = (0, 2/3) for the
    // diamond (1,0) (0,1) (-1,0) (0,-1); at t = 1 the curve is back there.
    CurveXYZ d =
        parseCurveFile("points: 4\ntype: bspline-closed\n1 0\n0 1\n-1 0\n0 -1\n", "d.crv", 100);
    EXPECT_NEAR(d.atLength(0).x, 0.0, 1e-12);
    EXPECT_NEAR(d.atLength(0).y, 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(d.atLength(1).y, 2.0 / 3.0, 1e-5);
    EXPECT_NEAR(d.atLength(0.5).y, -2.0 / 3.0, 1e-5) << "half way round: the opposite point";
}

TEST(CpfgCurves, DimensionsMultiplicitiesAndSubCurves) {
    // dimension 3 reads z; dimension 4 a multiplicity: here the ruler along z with its
    // first point twice (five evaluation points, knots 3 to 4.999999; B-spline weights at
    // knot 3 give z = (0 + 4*0 + 1) / 6).
    CurveXYZ z = parseCurveFile("points: 4\ndimension: 4\n0 0 0 2\n0 0 1 1\n0 0 2 1\n0 0 3 1\n",
                                "z.crv", 100);
    EXPECT_NEAR(z.atParameter(0).z, 1.0 / 6.0, 1e-12);
    // A `points:` line after a point opens that point's sub-curve (cpfg's "variety"
    // curves); its points are not the curve's: the curve is still the ruler.
    CurveXYZ s = parseCurveFile(
        "version: 1.1\ncontact: 0 0 0\nheading: 0 1 0\nup: 0 0 -1\nsize: 1\npoints: 4\n0 0\n"
        "points: 2\n5 5\n6 6\n1 0\n2 0\n3 0\n",
        "sub.crv", 100);
    EXPECT_NEAR(s.atLength(0.5).x, 1.4999995, 1e-9);
}

TEST(CpfgCurves, ErrorsNameFileLineAndColumn) {
    EXPECT_EQ(firstError([] { parseCurveFile("points: 4\n0 0\n1 q\n2 0\n3 0\n", "b.crv", 100); }),
              "b.crv:3:3: error: expected a coordinate, found 'q'");
    EXPECT_EQ(firstError([] { parseCurveFile("points: 4\n0 0\n1 0 0\n", "b.crv", 100); }),
              "b.crv:3:1: error: expected a point of 2 numbers (the dimension), found 3 words");
    EXPECT_NE(firstError([] {
                  parseCurveFile("points: 4\n0 0\n1 0\n", "b.crv", 100);
              }).find("b.crv:3:1: error: the file ends before all the points"),
              std::string::npos);
    EXPECT_NE(firstError([] {
                  parseCurveFile("points: 3\n0 0\n1 0\n2 0\n", "b.crv", 100);
              }).find("at least 4 points"),
              std::string::npos);
}

TEST(CpfgCurves, CurveFunctionsReadTheViewFilesCurvesInOrder) {
    // `curve: FILE [samples]` (interpret.c, label 53; 100 samples when none is given); ids
    // count from 1 in the order of the lines (curveXYZc.cpp subtracts one).
    TempDir dir;
    dir.write("ruler.crv", kRuler);
    dir.write("up.crv", "points: 4\ndimension: 3\n0 0 0\n0 0 1\n0 0 2\n0 0 3\n");
    std::string got = derivedWith(dir,
                                  std::string(kOneStep) +
                                      "A --> B(curveX(1,0.5), curveY(1,0.5), curveGAL(1)) "
                                      "C(curveZ(2,1))\nendlsystem\n",
                                  "curve: ruler.crv\ncurve: up.crv 10\n");
    EXPECT_EQ(got, "B(1.4999995,0,0.999999)C(1.999999)");
}

TEST(CpfgCurves, AnUnknownCurveIdOrFileIsAnError) {
    TempDir dir;
    dir.write("ruler.crv", kRuler);
    std::string message = firstError([&] {
        derivedWith(dir, std::string(kOneStep) + "A --> B(curveY(2,0.5))\nendlsystem\n",
                    "curve: ruler.crv\n");
    });
    EXPECT_NE(message.find("curveY(2, t) names no curve: there are 1, counted from 1"),
              std::string::npos)
        << message;
    ParseOptions o;
    o.viewFile = dir.write("m.v", "\ncurve: missing.crv\n").string();
    // The view file's problems are warnings, as cpfg forgives its view files.
    ParseResult r = loadModel(dir.write("m.l", "Lsystem: 1\nAxiom: A\n\nendlsystem\n"), o);
    ASSERT_TRUE(r.ok());
    ASSERT_FALSE(r.warnings().empty());
    EXPECT_EQ(r.warnings().front().location.line, 2);
    EXPECT_NE(r.warnings().front().message.find("missing.crv"), std::string::npos);
    o.viewFile = dir.write("m.v", "curve: ruler.crv 1\n").string();
    r = loadModel(dir.write("m.l", "Lsystem: 1\nAxiom: A\n\nendlsystem\n"), o);
    ASSERT_FALSE(r.warnings().empty()) << "one sample cannot measure a length";
    EXPECT_NE(r.warnings().front().message.find("at least 2"), std::string::npos);
}

TEST(CpfgTfunc, IsNotACpfgFunctionAndSaysWhere) {
    // cpfg's lexer (lsys_input.l, CheckReserved) knows func, curveX/Y/Z and curveGAL but no
    // tfunc, and its grammar has no call of a plain name: `tfunc(` is a syntax error there.
    // tfunc is lpfg's (timeline functions, .tset files); graftal says so at the call.
    std::string message = parseError("Lsystem: 1\nAxiom: A(1+tfunc(1,0))\n\nendlsystem\n");
    EXPECT_NE(message.find("test.l:2:12: error: tfunc() is not a cpfg function"), std::string::npos)
        << message;
    EXPECT_NE(message.find("lpfg"), std::string::npos) << message;
}

TEST(CpfgFunctionSets, ItemsMayUseTheOldRangeLayout) {
    // splinearr.cpp reads each item of a set with the SplineFunction constructor that also
    // reads `range:` files (unsampled: bisection to 0.001). The line y = 1 + x: at x = 0.5
    // the first bisection step lands on it.
    std::vector<GraphicalFunction> set = parseFunctionSet(
        "funcgalleryver 1 1\nitems: 2\nrange: 0.0 1.0\npoints: 4\n0 1\n0.333333 1.333333\n"
        "0.666667 1.666667\n1 2\nfver 1 1\nname: flat\nsamples: 0\nflip: off\npoints: 4\n"
        "0 3\n0.3 3\n0.6 3\n1 3\n",
        "old.fset");
    ASSERT_EQ(set.size(), 2u);
    EXPECT_NEAR(set[0].value(0.5), 1.5, 1e-6);
    EXPECT_NEAR(set[1].value(0.5), 3.0, 1e-6) << "ids follow the file order";
    EXPECT_EQ(
        firstError([] { parseFunctionSet("funcgalleryver 1 1\nitems: 1\nfver 1 2\n", "v.fset"); }),
        "v.fset:3:1: error: function format version fver 1 2 is not supported (1 1 is)");
}

TEST(CpfgContourSets, ContoursTakeIdsInFileOrder) {
    // vlab's contour gallery: `contourgalleryver 1 1`, `items: k`, k contours in the cver
    // layouts. cpfg never reads one (its view file names one .con per `contour:` line);
    // lpfg numbers the set's contours from 1 (0 is its default circle), as graftal does.
    std::vector<Contour> set = parseContourSet(
        "contourgalleryver 1 1\nitems: 2\ncver 1 1\nname: square\npoints: 4 4\ntype: closed\n"
        "1 1 0 1\n1 -1 0 1\n-1 -1 0 1\n-1 1 0 1\ncver 1 3\nname: arc\npoints: 3 5\ntype: or\n"
        "samples: 8\n-1 0 0 2\n0 1 0 1\n1 0 0 2\n",
        "c.cset");
    ASSERT_EQ(set.size(), 2u);
    EXPECT_EQ(set[0].id, 1);
    EXPECT_EQ(set[0].name, "square");
    EXPECT_TRUE(set[0].closed);
    EXPECT_EQ(set[1].id, 2);
    EXPECT_EQ(set[1].name, "arc");
    EXPECT_FALSE(set[1].closed);
    EXPECT_EQ(set[1].controlPoints.size(), 5u) << "multiplicities 2 + 1 + 2";
    EXPECT_EQ(firstError([] {
                  parseContourSet(
                      "contourgalleryver 1 1\nitems: 2\ncver 1 1\nname: a\n"
                      "points: 3 3\ntype: closed\n1 0 0 1\n0 1 0 1\n-1 0 0 1\n",
                      "short.cset");
              }),
              "short.cset:9:9: error: expected 'cver 1 1' (contour 2 of 2), found the end of "
              "the file");
}

TEST(CpfgContourSets, AModelFolderGivesItsContourSetUnlessTheViewNamesContours) {
    TempDir dir;
    dir.write("m.l", "Lsystem: 1\nderivation length: 0\nAxiom: A\n\nendlsystem\n");
    dir.write("m.v", "angle increment: 30\n");
    dir.write("c.cset",
              "contourgalleryver 1 1\nitems: 1\ncver 1 1\nname: tri\npoints: 3 3\ntype: closed\n"
              "1 0 0 1\n0 1 0 1\n-1 0 0 1\n");
    Model m = loadModel(dir.path()).orThrow();
    ASSERT_EQ(m.view.materials.contours.size(), 1u);
    EXPECT_EQ(m.view.materials.contours[0].id, 1);
    EXPECT_EQ(m.view.materials.contours[0].name, "tri");
    dir.write("one.con", "4 2 closed\n1 0\n0 1\n-1 0\n0 -1\n");
    dir.write("m.v", "contour: 3 one.con\n");
    Model v = loadModel(dir.path()).orThrow();
    ASSERT_EQ(v.view.materials.contours.size(), 1u);
    EXPECT_EQ(v.view.materials.contours[0].id, 3) << "the view file's contour, not the set";
}
