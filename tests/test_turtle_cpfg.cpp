// The 3D turtle against cpfg 6.6: end points of every segment and the boxes cpfg wrote
// for the turtle cases of the cpfg oracle pack (t09_*, v10_circles), with the view
// settings of their view files written into the .l text.
#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "graftal/geometry/projection.hpp"
#include "graftal/graftal.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parseModel;

namespace {

std::vector<Diagnostic> warningsOf(const std::string& text) {
    ParseOptions options;
    options.fileName = "test.l";
    return graftal::parse(text, options).warnings();
}

// `successor` drawn in a cpfg file with `view` as its view settings.
Scene cpfgScene(const std::string& successor, const std::string& view) {
    Model ls = parseModel("Lsystem: 1\n" + view + "derivation length: 1\naxiom: A\nA --> " +
                          successor + "\nendlsystem\n");
    return interpret(ls, deriveWithQueries(ls));
}

void expectNear(const Vec3& got, const Vec3& want, const std::string& what) {
    // cpfg prints six significant digits.
    EXPECT_NEAR(got.x, want.x, 2e-5) << what;
    EXPECT_NEAR(got.y, want.y, 2e-5) << what;
    EXPECT_NEAR(got.z, want.z, 2e-5) << what;
}

struct OracleCase {
    const char* name;
    const char* successor;
    const char* view;
    std::vector<Vec3> ends;  // start and end of every cylinder cpfg wrote, in order
};

// The cylinders of the oracle's .ray files.
const std::vector<OracleCase>& oracleCases() {
    static const std::vector<OracleCase> cases = {
        {"t09_plus",
         "F+F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {-0.5, 1.86603, 0}}},
        {"t09_minus",
         "F-F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0.5, 1.86603, 0}}},
        {"t09_and",
         "F&F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1.86603, -0.5}}},
        {"t09_caret",
         "F^F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1.86603, 0.5}}},
        {"t09_slash", "F/F", "angle increment: 30\n", {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 2, 0}}},
        {"t09_backslash",
         "F\\F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 2, 0}}},
        {"t09_pipe", "F|F", "angle increment: 30\n", {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 0}}},
        {"t09_dollar",
         "F$F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 2, 0}}},
        {"t09_roll_plus",
         "F/+F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {-0.433013, 1.86603, -0.25}}},
        {"t09_roll_and",
         "F/&F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0.25, 1.86603, -0.433013}}},
        {"t09_combo1",
         "F&F/F+F",
         "angle increment: 30\n",
         {{0, 0, 0},
          {0, 1, 0},
          {0, 1, 0},
          {0, 1.86603, -0.5},
          {0, 1.86603, -0.5},
          {0, 2.73205, -1},
          {0, 2.73205, -1},
          {-0.433013, 3.35705, -1.64952}}},
        {"t09_combo2",
         "F^F\\F-F",
         "angle increment: 30\n",
         {{0, 0, 0},
          {0, 1, 0},
          {0, 1, 0},
          {0, 1.86603, 0.5},
          {0, 1.86603, 0.5},
          {0, 2.73205, 1},
          {0, 2.73205, 1},
          {0.433013, 3.60705, 1.21651}}},
        {"t09_param_angles",
         "F+(90)F&(45)F/(90)F-(60)F^(20)F\\(45)F",
         "angle increment: 30\n",
         {{0, 0, 0},
          {0, 1, 0},
          {0, 1, 0},
          {-1, 1, 0},
          {-1, 1, 0},
          {-1.70711, 1, -0.707107},
          {-1.70711, 1, -0.707107},
          {-2.41421, 1, -1.41421},
          {-2.41421, 1, -1.41421},
          {-3.38014, 1, -1.15539},
          {-3.38014, 1, -1.15539},
          {-4.28781, 0.65798, -0.912184},
          {-4.28781, 0.65798, -0.912184},
          {-5.19549, 0.31596, -0.668974}}},
        {"t09_at_v",
         "F&/(45)F@v+F",
         "angle increment: 30\n",
         {{0, 0, 0},
          {0, 1, 0},
          {0, 1, 0},
          {0, 1.86603, -0.5},
          {0, 1.86603, -0.5},
          {-0.5, 2.61603, -0.933013}}},
        {"t09_at_R",
         "F@R(1,0,0)F@R(0,1,1)F+F",
         "angle increment: 30\n",
         {{0, 0, 0},
          {0, 1, 0},
          {0, 1, 0},
          {1, 1, 0},
          {1, 1, 0},
          {1, 1.70711, 0.707107},
          {1, 1.70711, 0.707107},
          {0.646447, 2.56948, 1.06948}}},
        {"t09_at_R_up",
         "F@R(0,0,1,0,1,0)F+F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 1}, {0, 1, 1}, {-0.5, 1, 1.86603}}},
        {"t09_at_M",
         "F@M(2,3)F@M(-1,0.5,2)F",
         "angle increment: 30\n",
         {{0, 0, 0}, {0, 1, 0}, {2, 3, 0}, {2, 4, 0}, {-1, 0.5, 2}, {-1, 1.5, 2}}},
        {"t09_default_angle",
         "F+F&F/F-F",
         "",
         {{0, 0, 0},
          {0, 1, 0},
          {0, 1, 0},
          {-0.707107, 1.70711, 0},
          {-0.707107, 1.70711, 0},
          {-1.20711, 2.20711, -0.707107},
          {-1.20711, 2.20711, -0.707107},
          {-1.70711, 2.70711, -1.41421},
          {-1.70711, 2.70711, -1.41421},
          {-1.95711, 3.66421, -1.56066}}},
        {"t09_start_moved",
         "f(3)F+(90)F",
         "angle increment: 90\n",
         {{0, 3, 0}, {0, 4, 0}, {0, 4, 0}, {-1, 4, 0}}},
    };
    return cases;
}

}  // namespace

// cpfg starts with H = (0,1,0), L = (-1,0,0) and rolls L toward its up vector (0,0,-1) at
// '/': after a pitch down and a roll right, '+' turns toward -x and further into -z.
TEST(TurtleCpfg, RollRightTurnsTheNextTurnIntoTheScreen) {
    Scene s = cpfgScene("F&F/F+F", "angle increment: 30\n");
    ASSERT_EQ(s.segments.size(), 4u);
    EXPECT_NEAR(s.segments.back().b.y, 3.357, 1e-3);
    EXPECT_NEAR(s.segments.back().b.z, -1.650, 1e-3);
    expectNear(s.segments.back().b, {-0.433013, 3.35705, -1.64952}, "t09_combo1");
}

TEST(TurtleCpfg, EverySymbolEndsWhereCpfgsCylindersEnd) {
    for (const OracleCase& c : oracleCases()) {
        SCOPED_TRACE(c.name);
        Scene s = cpfgScene(c.successor, c.view);
        ASSERT_EQ(2 * s.segments.size(), c.ends.size());
        for (std::size_t i = 0; i < s.segments.size(); ++i) {
            expectNear(s.segments[i].a, c.ends[2 * i], "start of segment " + std::to_string(i));
            expectNear(s.segments[i].b, c.ends[2 * i + 1], "end of segment " + std::to_string(i));
        }
    }
}

// cpfg's box for the cases where it covers only what is drawn (no f move, no @M, no
// start away from the drawing): the `box` lines of the oracle's .box files.
TEST(TurtleCpfg, BoxesOfDrawnCasesAreCpfgs) {
    struct Box {
        const char* successor;
        const char* view;
        Vec3 min, max;
    };
    const Box boxes[] = {
        {"F&F/F+F", "angle increment: 30\n", {-0.433013, 0, -1.64952}, {0, 3.35705, 0}},
        {"F^F\\F-F", "angle increment: 30\n", {0, 0, 0}, {0.433013, 3.60705, 1.21651}},
        {"F/&F", "angle increment: 30\n", {0, 0, -0.433013}, {0.25, 1.86603, 0}},
        {"F/+F", "angle increment: 30\n", {-0.433013, 0, -0.25}, {0, 1.86603, 0}},
        {"F&/(45)F@v+F", "angle increment: 30\n", {-0.5, 0, -0.933013}, {0, 2.61603, 0}},
        {"F@R(1,0,0)F@R(0,1,1)F+F", "angle increment: 30\n", {0, 0, 0}, {1, 2.56948, 1.06948}},
        {"F@R(0,0,1,0,1,0)F+F", "angle increment: 30\n", {-0.5, 0, 0}, {0, 1, 1.86603}},
        {"F+(90)F&(45)F/(90)F-(60)F^(20)F\\(45)F",
         "angle increment: 30\n",
         {-5.19549, 0, -1.41421},
         {0, 1, 0}},
        {"F+F&F/F-F", "", {-1.95711, 0, -1.56066}, {0, 3.66421, 0}},
    };
    for (const Box& b : boxes) {
        SCOPED_TRACE(b.successor);
        Bounds got = cpfgScene(b.successor, b.view).bounds();
        expectNear(got.min, b.min, "min");
        expectNear(got.max, b.max, "max");
    }
}

// p11_query: cpfg's up vector starts at (0,0,-1), and L = H x U.
TEST(TurtleCpfg, QueryUpIsCpfgsUpVector) {
    Model ls = parseModel(
        "Lsystem: 1\naxiom: ?U(0,0,0) +(90) F &(90) ?U(0,0,0) ?L(0,0,0) ?H(0,0,0)\n"
        "endlsystem\n");
    ModuleString m = deriveWithQueries(ls, 0);
    auto at = [&](std::size_t i) {
        auto p = m.params(i);
        return Vec3{p[0], p[1], p[2]};
    };
    expectNear(at(0), {0, 0, -1}, "start");
    expectNear(at(4), {1, 0, 0}, "?U after +(90) &(90), as cpfg prints it");
    expectNear(at(5), {0, -1, 0}, "?L");
    expectNear(cross(at(6), at(4)), at(5), "L = H x U");
}

TEST(TurtleCpfg, DefaultAngleIs45DegreesAndPfgFilesKeep90) {
    EXPECT_EQ(parseModel("Lsystem: 1\naxiom: F\nendlsystem\n").view.turtle.angleDegrees, 45);
    EXPECT_EQ(parseModel("Lsystem: 1\nangle increment: 30\naxiom: F\nendlsystem\n")
                  .view.turtle.angleDegrees,
              30);
    EXPECT_EQ(parseModel("axiom: F\n").view.turtle.angleDegrees, 90) << "a pfg data file";
}

// '$' ends a sub-L-system in cpfg; an unmatched one is ignored with a warning.
TEST(TurtleCpfg, DollarIsNoTurtleSymbolInCpfgFiles) {
    const std::string text = "Lsystem: 1\nangle increment: 30\naxiom: A\nA --> F&F$F\nendlsystem\n";
    Model ls = parseModel(text);
    const std::vector<Diagnostic> warnings = warningsOf(text);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].toString(),
              "test.l:4:1: warning: '$' ends a sub-L-system in cpfg; there is none here, so "
              "the turtle ignores it (cpfg: \"unmatched $ ignored\")");
    Scene s = interpret(ls, deriveWithQueries(ls, 1));
    ASSERT_EQ(s.segments.size(), 3u);
    expectNear(s.segments[2].b, {0, 1.86603 + 0.866025, -1}, "no roll at $");
    EXPECT_TRUE(warningsOf("Lsystem: 1\naxiom: F@vF\nendlsystem\n").empty());
}

// In a pfg data file '$' is the book's roll to horizontal, and the rolls keep the book's
// names: '\' lowers L toward -U, '/' raises it.
TEST(TurtleCpfg, PfgDataFilesKeepTheBooksRollsAndDollar) {
    Model ls = parseModel("angle increment: 90\naxiom: F&(30)/(40)$?L(0,0,0)\n");
    EXPECT_TRUE(warningsOf("angle increment: 90\naxiom: F&(30)/(40)$?L(0,0,0)\n").empty());
    ModuleString m = deriveWithQueries(ls, 0);
    auto l = m.params(m.size() - 1);
    EXPECT_NEAR(l[1], 0, 1e-12) << "L horizontal after $";
    Model roll = parseModel("angle increment: 90\naxiom: \\?L(0,0,0)\n");
    ModuleString r = deriveWithQueries(roll, 0);
    EXPECT_NEAR(r.params(1)[2], -1, 1e-12) << "\\ rolls L toward -U (into the screen)";
}

TEST(TurtleCpfg, DiscsAndSpheresAreWhereCpfgPutsThem) {
    // v10_circles, with cpfg's default line width of 1 (graftal's is 0.1).
    Scene s = cpfgScene("F@o(1)&F@c(0.5)F@O(3)+F@o@O", "angle increment: 90\nline width: 1\n");
    ASSERT_EQ(s.discs.size(), 3u);
    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_EQ(s.segments.size(), 4u) << "@ followed by o, c, O draws no segment";
    expectNear(s.discs[0].centre, {0, 1, 0}, "@o(1)");
    EXPECT_DOUBLE_EQ(s.discs[0].radius, 0.5);
    expectNear(s.discs[0].normal, {0, 0, 1}, "@o faces the viewer");
    expectNear(s.discs[1].centre, {0, 1, -1}, "@c(0.5)");
    EXPECT_DOUBLE_EQ(s.discs[1].radius, 0.25);
    EXPECT_NEAR(std::abs(s.discs[1].normal.y), 1, 1e-12) << "@c faces along the turtle's up";
    expectNear(s.discs[2].centre, {-1, 1, -2}, "@o");
    EXPECT_DOUBLE_EQ(s.discs[2].radius, 0.5) << "no parameter: the line width";
    expectNear(s.spheres[0].centre, {0, 1, -2}, "@O(3)");
    EXPECT_DOUBLE_EQ(s.spheres[0].radius, 1.5);
    expectNear(s.spheres[1].centre, {-1, 1, -2}, "@O");
    EXPECT_DOUBLE_EQ(s.spheres[1].radius, 0.5);
    // cpfg's box: -1.5 -0.5 -3.5 1.5 2.5 0.
    Bounds b = s.bounds();
    expectNear(b.min, {-1.5, -0.5, -3.5}, "box min");
    expectNear(b.max, {1.5, 2.5, 0}, "box max");
    // The streamed measure (graftal stats) has the same box.
    Model ls = parseModel(
        "Lsystem: 1\nangle increment: 90\nline width: 1\naxiom: F@o(1)&F@c(0.5)F@O(3)+F@o@O\n"
        "endlsystem\n");
    StreamedMeasure m = measureModules(ls, deriveWithQueries(ls, 0));
    expectNear(m.bounds.min, {-1.5, -0.5, -3.5}, "measured min");
    expectNear(m.bounds.max, {1.5, 2.5, 0}, "measured max");
}

// A phyllotaxis pattern drawn with circles alone (no F) must still be a picture.
TEST(TurtleCpfg, APatternOfCirclesIsDrawn) {
    Model ls = parseModel(
        "Lsystem: 1\nderivation length: 40\naxiom: A(0)\n"
        "A(n) --> [+(n*137.5)f(sqrt(n))@c(1)]A(n+1)\nendlsystem\n");
    Scene s = interpret(ls, deriveWithQueries(ls));
    ASSERT_EQ(s.discs.size(), 40u);
    EXPECT_TRUE(s.segments.empty());
    EXPECT_FALSE(s.is3D) << "circles facing the viewer keep a flat picture";
    Scene art = projectScene(s, ViewDirection::Front);
    EXPECT_EQ(art.polygonCount(), 40u) << "line art fills each circle's outline";
    std::ostringstream svg;
    writeSvg(art, RenderOptions{}, svg);
    const std::string text = svg.str();
    std::size_t fills = 0;
    for (std::size_t at = text.find("<path fill="); at != std::string::npos;
         at = text.find("<path fill=", at + 1))
        ++fills;
    EXPECT_EQ(fills, 40u);

    // The PNG has ink: every circle is a filled disc of about 1/16 of the picture's width.
    auto png = std::filesystem::temp_directory_path() / "graftal-test-circles.png";
    RenderOptions o;
    o.width = o.height = 200;
    writePng(art, o, png);
    cairo_surface_t* image = cairo_image_surface_create_from_png(png.c_str());
    ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
    const unsigned char* data = cairo_image_surface_get_data(image);
    const int stride = cairo_image_surface_get_stride(image);
    int inked = 0;
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) {
            const unsigned char* px = data + y * stride + 4 * x;  // B, G, R, A
            if (px[0] < 128 && px[1] < 128 && px[2] < 128) ++inked;
        }
    cairo_surface_destroy(image);
    std::filesystem::remove(png);
    EXPECT_GT(inked, 200 * 200 / 10) << "the circles cover a good part of the picture";

    // In 3D a sphere is a closed ball in the mesh.
    Scene ball = cpfgScene("@O(2)", "");
    ASSERT_EQ(ball.spheres.size(), 1u);
    Mesh mesh = buildMesh(ball);
    ASSERT_GT(mesh.triangleCount(), 0u);
    Bounds mb = mesh.bounds();
    expectNear(mb.min, {-1, -1, -1}, "ball min");
    expectNear(mb.max, {1, 1, 1}, "ball max");
}
