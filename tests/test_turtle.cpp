#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::parse;

namespace {

Scene draw(const std::string& text, int steps = -1) {
    LSystem ls = parse(text);
    return interpret(ls, derive(ls, steps));
}

void expectNear(const Vec3& a, const Vec3& b) {
    EXPECT_NEAR(a.x, b.x, 1e-9);
    EXPECT_NEAR(a.y, b.y, 1e-9);
    EXPECT_NEAR(a.z, b.z, 1e-9);
}

}  // namespace

TEST(Turtle, HeadingStartsUpAndPlusTurnsLeft) {
    Scene s = draw("Lsystem: 1\nangle increment: 90\naxiom: F+F\nendlsystem\n");
    ASSERT_EQ(s.segments.size(), 2u);
    expectNear(s.segments[0].a, {0, 0, 0});
    expectNear(s.segments[0].b, {0, 1, 0});
    expectNear(s.segments[1].b, {-1, 1, 0});
}

TEST(Turtle, PfgFilesTurnRightOnPlus) {
    Scene s = draw("derivation length: 0\nangle factor: 4\nscale factor: 100\naxiom: F+F\n");
    ASSERT_EQ(s.segments.size(), 2u);
    expectNear(s.segments[1].b, {1, 1, 0});
}

TEST(Turtle, MoveWithoutDrawingAndTurnAround) {
    Scene s = draw("Lsystem: 1\naxiom: fF|F\nendlsystem\n");
    ASSERT_EQ(s.segments.size(), 2u);
    expectNear(s.segments[0].a, {0, 1, 0});
    expectNear(s.segments[1].b, {0, 1, 0});
}

TEST(Turtle, BracketsRestorePositionAndHeading) {
    Scene s = draw("Lsystem: 1\nangle increment: 45\naxiom: F[+F]F\nendlsystem\n");
    ASSERT_EQ(s.segments.size(), 3u);
    expectNear(s.segments[2].a, {0, 1, 0});
    expectNear(s.segments[2].b, {0, 2, 0});
}

TEST(Turtle, QuadraticKochIslandStaysASquare) {
    Scene s =
        draw("Lsystem: 1\nangle factor: 4\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n", 2);
    EXPECT_EQ(s.segments.size(), 4u * 64);
    Bounds b = s.bounds();
    // Each side of length 16 (step 1): the island spans the square plus the bumps.
    EXPECT_NEAR(b.max.x - b.min.x, b.max.y - b.min.y, 1e-9);
    expectNear(s.segments.back().b, {0, 0, 0});  // closed curve
}

TEST(Turtle, FilledPolygonTakesAVertexAtEachMove) {
    Scene s = draw("Lsystem: 1\nangle increment: 90\naxiom: {F+F+F+F}\nendlsystem\n");
    EXPECT_EQ(s.segments.size(), 0u) << "edges inside braces belong to the polygon";
    ASSERT_EQ(s.polygonCount(), 1u);
    EXPECT_EQ(s.polygon(0).size(), 5u);
}

TEST(Turtle, PopOnEmptyStackIsAnError) {
    // The parser refuses unbalanced successors; a string built by hand can still be wrong.
    LSystem ls = parse("Lsystem: 1\naxiom: F\nendlsystem\n");
    ModuleString bad;
    bad.push('F');
    bad.push(']');
    EXPECT_THROW(interpret(ls, bad), Error);
    LSystem open = parse("Lsystem: 1\naxiom: {F\nendlsystem\n");
    EXPECT_THROW(interpret(open, derive(open, 0)), Error);
}

TEST(Turtle, ExplicitLengthAndAngleParameters) {
    Scene s = draw("Lsystem: 1\naxiom: F(2)+(90)F(3)\nendlsystem\n");
    ASSERT_EQ(s.segments.size(), 2u);
    expectNear(s.segments[0].b, {0, 2, 0});
    expectNear(s.segments[1].b, {-3, 2, 0});
}

TEST(Turtle, ColourAndWidthAttributesArePushedWithTheState) {
    Scene s = draw("Lsystem: 1\naxiom: F['!F]F\nendlsystem\n");
    ASSERT_EQ(s.segments.size(), 3u);
    EXPECT_EQ(s.segments[1].color, 1);
    EXPECT_LT(s.segments[1].width, 1.0f);
    EXPECT_EQ(s.segments[2].color, 0);
    EXPECT_EQ(s.segments[2].width, s.baseWidth);
    EXPECT_FLOAT_EQ(s.baseWidth, 0.1f) << "the default stem diameter";
}
