// The 3D turtle: frames after each rotation, tropism, the attributes 3D outputs rely on.
#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseModel;

namespace {

// The turtle's frames are checked to 1e-12 from the query modules' answers: parameters
// stored as doubles, not rounded to floats (the default).
DerivationOptions doubles() {
    DerivationOptions o;
    o.precision = Precision::Double;
    return o;
}

struct Frame {
    Vec3 h, l, u;
};

// The frame the turtle has when it reaches the ?H ?L ?U queries at the end of `modules`.
Frame frameAfter(const std::string& modules, double angle = 90) {
    Model ls = parseModel("Lsystem: 1\nangle increment: " + std::to_string(angle) +
                          "\naxiom: " + modules + "?H(0,0,0)?L(0,0,0)?U(0,0,0)\nendlsystem\n");
    ModuleString s = deriveWithQueries(ls, 0, doubles());
    auto v = [&](std::size_t i) {
        auto p = s.params(i);
        return Vec3{p[0], p[1], p[2]};
    };
    std::size_t n = s.size();
    // ?U reports cpfg's up vector, -U.
    return {v(n - 3), v(n - 2), v(n - 1) * -1.0};
}

void expectVec(const Vec3& a, const Vec3& b, double tol = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace

TEST(Turtle3D, InitialFrameHeadsUpWithLeftToMinusX) {
    Frame f = frameAfter("");
    expectVec(f.h, {0, 1, 0});
    expectVec(f.l, {-1, 0, 0});
    expectVec(f.u, {0, 0, 1});
    expectVec(cross(f.h, f.l), f.u);
}

// Hand-computed frames for each rotation by 90 degrees from the initial frame
// H = (0,1,0), L = (-1,0,0), U = (0,0,1).
TEST(Turtle3D, TurnLeftRotatesHeadingTowardLeft) {
    Frame f = frameAfter("+");
    expectVec(f.h, {-1, 0, 0});
    expectVec(f.l, {0, -1, 0});
    expectVec(f.u, {0, 0, 1});
    expectVec(frameAfter("-").h, {1, 0, 0});
}

TEST(Turtle3D, PitchDownTurnsHeadingAwayFromUp) {
    Frame f = frameAfter("&");
    expectVec(f.h, {0, 0, -1});
    expectVec(f.u, {0, 1, 0});
    expectVec(f.l, {-1, 0, 0});
    expectVec(frameAfter("^").h, {0, 0, 1});
}

// The rolls are cpfg's: / turns L toward -U (into the screen at the start), \ toward U.
TEST(Turtle3D, RollsTurnTheLeftVectorAsCpfgDoes) {
    Frame f = frameAfter("/");
    expectVec(f.h, {0, 1, 0});
    expectVec(f.l, {0, 0, -1});
    expectVec(f.u, {-1, 0, 0});
    expectVec(frameAfter("\\").l, {0, 0, 1});
}

TEST(Turtle3D, TurnAroundAndExplicitAngles) {
    Frame f = frameAfter("|");
    expectVec(f.h, {0, -1, 0});
    expectVec(f.l, {1, 0, 0});
    Frame g = frameAfter("+(30)");
    expectVec(g.h, {-0.5, std::sqrt(3) / 2, 0});
}

TEST(Turtle3D, RollToVerticalMakesLeftHorizontal) {
    Frame f = frameAfter("&(30)/(40)@v", 90);
    EXPECT_NEAR(f.l.y, 0, 1e-12) << "L horizontal";
    EXPECT_NEAR(dot(f.h, f.l), 0, 1e-12);
    expectVec(cross(f.h, f.l), f.u);
    Frame before = frameAfter("&(30)/(40)", 90);
    expectVec(f.h, before.h);  // @v only rolls
}

TEST(Turtle3D, FrameStaysOrthonormalAfterAMillionRotations) {
    // Irrational-looking angles so nothing cancels exactly.
    std::string axiom;
    for (int i = 0; i < 350000; ++i) axiom += "+&/";  // 1.05 million rotations
    Model big = parseModel("Lsystem: 1\nangle increment: 13.7\naxiom: " + axiom +
                           "?H(0,0,0)?L(0,0,0)?U(0,0,0)\nendlsystem\n");
    ModuleString s = deriveWithQueries(big, 0, doubles());
    std::size_t n = s.size();
    auto v = [&](std::size_t i) {
        auto p = s.params(i);
        return Vec3{p[0], p[1], p[2]};
    };
    Vec3 h = v(n - 3), l = v(n - 2), u = v(n - 1) * -1.0;  // ?U is cpfg's up, -U
    EXPECT_NEAR(dot(h, h), 1, 1e-9);
    EXPECT_NEAR(dot(l, l), 1, 1e-9);
    EXPECT_NEAR(dot(u, u), 1, 1e-9);
    EXPECT_NEAR(dot(h, l), 0, 1e-9);
    EXPECT_NEAR(dot(h, u), 0, 1e-9);
    expectVec(cross(h, l), u, 1e-9);
}

TEST(Turtle3D, TropismBendsTowardTheVectorByElasticityTimesSine) {
    // Heading up, T pointing right: after one segment H turns toward T by e·|H×T| = e rad.
    Model ls = parseModel(
        "Lsystem: 1\ntropism direction: 1,0,0\ntropism elasticity: 0.2\n"
        "axiom: F?H(0,0,0)\nendlsystem\n");
    ModuleString s = deriveWithQueries(ls, 0, doubles());
    auto h = s.params(1);
    EXPECT_NEAR(h[0], std::sin(0.2), 1e-12);
    EXPECT_NEAR(h[1], std::cos(0.2), 1e-12);
}

TEST(Turtle3D, NegativeElasticityBendsAway) {
    Model ls = parseModel(
        "Lsystem: 1\ntropism direction: 1,0,0\ntropism elasticity: -0.2\n"
        "axiom: F?H(0,0,0)\nendlsystem\n");
    EXPECT_NEAR(deriveWithQueries(ls, 0, doubles()).params(1)[0], -std::sin(0.2), 1e-12);
}

TEST(Turtle3D, TropismVanishesAlongTheVector) {
    Model ls = parseModel(
        "Lsystem: 1\ntropism direction: 0,1,0\ntropism elasticity: 0.5\n"
        "axiom: FFF?H(0,0,0)\nendlsystem\n");
    ModuleString s = deriveWithQueries(ls, 0, doubles());
    auto h = s.params(3);
    EXPECT_NEAR(h[0], 0, 1e-15);
    EXPECT_NEAR(h[1], 1, 1e-15);
}

TEST(Turtle3D, ConsecutiveSegmentsOfAnAxisAreLinked) {
    Model ls = parseModel("Lsystem: 1\naxiom: FF[+F]F f F\nendlsystem\n");
    Scene s = interpret(ls, deriveWithQueries(ls, 0));
    ASSERT_EQ(s.segments.size(), 5u);
    EXPECT_EQ(s.segments[0].previous, kNoSegment);
    EXPECT_EQ(s.segments[1].previous, 0u);
    EXPECT_EQ(s.segments[2].previous, kNoSegment) << "a branch starts a new axis";
    EXPECT_EQ(s.segments[3].previous, 1u) << "the axis resumes after the branch";
    EXPECT_EQ(s.segments[4].previous, kNoSegment) << "f breaks the axis";
}

TEST(Turtle3D, WidthAttributes) {
    Model ls = parseModel(
        "Lsystem: 1\nline width: 2\nwidth factor: 0.5\naxiom: F!F#F!(0.3)F\nendlsystem\n");
    Scene s = interpret(ls, deriveWithQueries(ls, 0));
    ASSERT_EQ(s.segments.size(), 4u);
    EXPECT_FLOAT_EQ(s.segments[0].width, 2);
    EXPECT_FLOAT_EQ(s.segments[1].width, 1);
    EXPECT_FLOAT_EQ(s.segments[2].width, 2);
    EXPECT_FLOAT_EQ(s.segments[3].width, 0.3f);
}

TEST(Turtle3D, PolygonVerticesAndGMoves) {
    Model ls = parseModel("Lsystem: 1\naxiom: {.G+fG+f.}F g F\nendlsystem\n");
    Scene s = interpret(ls, deriveWithQueries(ls, 0));
    ASSERT_EQ(s.polygonCount(), 1u);
    EXPECT_EQ(s.polygon(0).size(), 5u) << "start, '.', f, f, '.' (G adds no vertex)";
    EXPECT_EQ(s.segments.size(), 2u) << "G draws nothing inside a polygon; F, g, F outside";
}

TEST(Turtle3D, SurfacesArePlacedAtTheTurtleFrame) {
    Model ls =
        parseModel("Lsystem: 1\nangle increment: 90\naxiom: F~leaf&F~leaf(2)~petal\nendlsystem\n");
    Scene s = interpret(ls, deriveWithQueries(ls, 0));
    ASSERT_EQ(s.surfaces.size(), 3u);
    ASSERT_EQ(s.surfaceNames.size(), 2u);
    EXPECT_EQ(s.surfaceNames[s.surfaces[0].surface], "leaf");
    expectVec(s.surfaces[0].origin, {0, 1, 0});
    expectVec(s.surfaces[1].origin, {0, 1, -1});
    EXPECT_EQ(s.surfaces[1].scale, 2);
    expectVec(s.surfaces[1].heading, {0, 0, -1});
    EXPECT_TRUE(s.is3D);
}

TEST(Turtle3D, FlatStringsStayTwoDimensional) {
    Model ls = parseModel("Lsystem: 1\naxiom: F+F[-F]\nendlsystem\n");
    EXPECT_FALSE(interpret(ls, deriveWithQueries(ls, 0)).is3D);
    Model rolled = parseModel("Lsystem: 1\naxiom: F/(180)F[+F]/(180)F[+F]\nendlsystem\n");
    EXPECT_FALSE(interpret(rolled, deriveWithQueries(rolled, 0)).is3D)
        << "a half roll keeps a plant flat";
    Model pitched = parseModel("Lsystem: 1\naxiom: F&F\nendlsystem\n");
    EXPECT_TRUE(interpret(pitched, deriveWithQueries(pitched, 0)).is3D);
}

TEST(ViewSettings, BadValuesAreRejectedWithTheirPlace) {
    using graftal::testing::parseError;
    EXPECT_EQ(parseError("Lsystem: 1\nviewpoint: 1,2\naxiom: F\n"),
              "test.l:2:12: error: expected three numbers x, y, z");
    EXPECT_EQ(parseError("Lsystem: 1\nprojection: fisheye\naxiom: F\n"),
              "test.l:2:13: error: projection is 'perspective' or 'parallel', not 'fisheye'");
    EXPECT_EQ(parseError("Lsystem: 1\nfield of view: 200\naxiom: F\n"),
              "test.l:2:16: error: field of view must be between 0 and 180 degrees");
    EXPECT_EQ(parseError("Lsystem: 1\nlight direction: 0 0 0\naxiom: F\n"),
              "test.l:2:18: error: the light direction must not be zero");
    EXPECT_EQ(parseError("Lsystem: 1\nsurface: l\naxiom: F\n"),
              "test.l:2:10: error: expected 'surface: NAME FILE [SCALE [S T [TEXTURE]]]', e.g. "
              "'surface: l leaf.s 0.5'");
}
