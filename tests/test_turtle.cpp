#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "test_helpers.hpp"
#include "turtle/planar_measure.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseModel;

namespace {

Scene draw(const std::string& text, int steps = -1) {
    Model ls = parseModel(text);
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
    Model ls = parseModel("Lsystem: 1\naxiom: F\nendlsystem\n");
    ModuleString bad;
    bad.push('F');
    bad.push(']');
    EXPECT_THROW(interpret(ls, bad), Error);
    Model open = parseModel("Lsystem: 1\naxiom: {F\nendlsystem\n");
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

// The planar walk (src/turtle/planar_measure.hpp) must give bit for bit what the generic
// 3D turtle gives: EXPECT_EQ on every double.
namespace {

void expectSameMeasure(const StreamedMeasure& fast, const StreamedMeasure& generic) {
    EXPECT_EQ(fast.modules, generic.modules);
    EXPECT_EQ(fast.symbolCounts, generic.symbolCounts);
    EXPECT_EQ(fast.segments, generic.segments);
    EXPECT_EQ(fast.polygons, generic.polygons);
    EXPECT_EQ(fast.bounds.min, generic.bounds.min);
    EXPECT_EQ(fast.bounds.max, generic.bounds.max);
    // EXPECT_EQ on Vec3 cannot tell 0 from -0, which a JSON bbox prints differently.
    EXPECT_EQ(std::signbit(fast.bounds.min.x), std::signbit(generic.bounds.min.x));
    EXPECT_EQ(std::signbit(fast.bounds.max.z), std::signbit(generic.bounds.max.z));
    EXPECT_EQ(fast.ink, generic.ink);
    EXPECT_EQ(fast.baseWidth, generic.baseWidth);
    EXPECT_EQ(fast.is3D, generic.is3D);
}

// Measures `modules` both ways; the planar walk must take it.
void expectPlanarMatchesGeneric(const Model& ls, const ModuleString& modules) {
    ASSERT_TRUE(turtle::staysPlanar(ls));
    std::optional<StreamedMeasure> fast = turtle::measurePlanar(ls, modules);
    ASSERT_TRUE(fast.has_value()) << "the planar walk gave up";
    StreamedMeasure generic = turtle::measureGeneric(ls, modules);
    expectSameMeasure(*fast, generic);
    // And the generic measure is what the stored geometry gives.
    Scene scene = interpret(ls, modules);
    double ink = 0;
    for (const Segment& s : scene.segments) ink += inkLength(s, scene.baseWidth);
    EXPECT_EQ(generic.ink, ink);
    EXPECT_EQ(generic.segments, scene.segments.size());
    EXPECT_EQ(generic.bounds.min, scene.bounds().min);
    EXPECT_EQ(generic.bounds.max, scene.bounds().max);
    expectSameMeasure(measureModules(ls, modules), generic);
}

void expectPlanarMatchesGeneric(const std::string& text, int steps = -1) {
    Model ls = parseModel(text);
    expectPlanarMatchesGeneric(ls, derive(ls, steps));
}

}  // namespace

TEST(PlanarMeasure, MatchesTheGenericTurtleOnFlatExamples) {
    // Koch island (90 degrees, > 4096 turns: the frame is orthonormalised on the way),
    // bracketed plants, 60-degree curves (hypot of both sides), a filled polygon.
    for (const char* name : {"fig2.2-quadratic-koch-island.l", "fig2.3b-quadratic-snowflake.l",
                             "fig2.4-islands-and-lakes.l", "fig2.8b-hexagonal-gosper.l",
                             "fig2.9-filled-polygon-fractal.l", "fig3.2a-bracketed-plant.l",
                             "fig3.2d-bracketed-plant.l", "fig3.2f-bracketed-plant.l",
                             "fig2.6-dragon-curve-pfg.l", "lecture-parametric-plant.l"}) {
        SCOPED_TRACE(name);
        Model ls = loadExample(std::string(GRAFTAL_EXAMPLES_DIR) + "/" + name);
        ModuleString m = derive(ls);
        if (!ls.lsystem.homomorphism.empty()) m = applyHomomorphism(ls.lsystem, m);
        expectPlanarMatchesGeneric(ls, m);
    }
    Model koch = loadExample(std::string(GRAFTAL_EXAMPLES_DIR) + "/fig2.2-quadratic-koch-island.l");
    expectPlanarMatchesGeneric(koch, derive(koch, 5));  // 112,000 turns
}

TEST(PlanarMeasure, MatchesTheGenericTurtleOnEveryFlatOperation) {
    // Moves, turning around, widths with and without arguments, colours, branches.
    expectPlanarMatchesGeneric(
        "Lsystem: 1\nangle increment: 25.7\naxiom: X\n"
        "X --> F[+X]f[-!X]|'F[!!X]#F,;+gG-X\nF --> FF\nendlsystem\n",
        5);
    // Enough turns by an angle whose rounding drifts for the frame to be orthonormalised
    // several times, at the generic turtle's cadence.
    expectPlanarMatchesGeneric(
        "Lsystem: 1\nangle increment: 7.3\naxiom: F\nF --> F+F-F++F[-F]\nendlsystem\n", 6);
    // Parametric steps, turns and widths, with the parameter-free forms mixed in.
    expectPlanarMatchesGeneric(
        "Lsystem: 1\nangle increment: 30\naxiom: A(1)\n"
        "A(x) --> F(x)[+(x*17)!(x/9)A(x*0.7)]-F(x/3)[-(45)A(x*0.6)]!F+A(x*0.9)\n"
        "endlsystem\n",
        7);
    // Polygons with vertices from F, f and '.', and G and g that add none.
    expectPlanarMatchesGeneric(
        "Lsystem: 1\nangle increment: 72\naxiom: F{.F+f+G.-g+F}F[{F+F+F}]f{F}F\nendlsystem\n");
    // A pfg data file (+ turns right) and a turned start.
    expectPlanarMatchesGeneric(
        "derivation length: 3\nangle factor: 6\nscale factor: 100\naxiom: F++F++F\n"
        "* < F > * --> F-F++F-F\n");
    expectPlanarMatchesGeneric(
        "Lsystem: 1\ninitial heading: 37\nangle increment: 90\naxiom: F+F+F\nendlsystem\n");
}

TEST(PlanarMeasure, ThreeDimensionalSymbolsTakeTheGenericTurtle) {
    Model ls = parseModel("Lsystem: 1\nangle increment: 30\naxiom: F&F/F\nendlsystem\n");
    EXPECT_FALSE(turtle::staysPlanar(ls));
    ModuleString m = derive(ls);
    EXPECT_FALSE(turtle::measurePlanar(ls, m).has_value());
    StreamedMeasure generic = turtle::measureGeneric(ls, m);
    EXPECT_TRUE(generic.is3D);
    expectSameMeasure(measureModules(ls, m), generic);

    // A pitch the productions do not show (a string built by hand) still leaves the plane.
    Model flat = parseModel("Lsystem: 1\naxiom: F\nendlsystem\n");
    ASSERT_TRUE(turtle::staysPlanar(flat));
    ModuleString pitched;
    for (Symbol s : {Symbol('F'), Symbol('&'), Symbol('F')}) pitched.push(s);
    EXPECT_FALSE(turtle::measurePlanar(flat, pitched).has_value());
    EXPECT_TRUE(measureModules(flat, pitched).is3D);

    Model tropism = parseModel(
        "Lsystem: 1\ntropism direction: 0, -1, 0\ntropism elasticity: 0.2\naxiom: F+F\n"
        "endlsystem\n");
    EXPECT_FALSE(turtle::staysPlanar(tropism));
}

TEST(PlanarMeasure, MalformedStringsGetTheGenericTurtlesErrors) {
    Model ls = parseModel("Lsystem: 1\naxiom: F\nendlsystem\n");
    ModuleString bad;
    bad.push('F');
    bad.push(']');
    EXPECT_FALSE(turtle::measurePlanar(ls, bad).has_value());
    EXPECT_THROW(measureModules(ls, bad), Error);
    Model open = parseModel("Lsystem: 1\naxiom: {F\nendlsystem\n");
    EXPECT_THROW(measureModules(open, derive(open, 0)), Error);
}
