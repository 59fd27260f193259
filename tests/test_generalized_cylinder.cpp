// cpfg's generalized cylinders (@Gs, @Gc, @Ge) and contours (.con, `contour:`, @#, @!):
// the centre line against the points cpfg writes, the swept surface, contour files read
// and refused with their line and column, and pictures that are not blank.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "graftal/geometry/contour_points.hpp"
#include "graftal/geometry/generalized_cylinder.hpp"
#include "graftal/graftal.hpp"
#include "graftal/lang/contour_file.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

void expectNear(const Vec3& got, const Vec3& want, double tolerance = 2e-5) {
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

// The oracle's v10_gencyl: `@Gs F+F @Gc(2) F&F @Ge(3) F` with a 90 degree angle.
const char* kGencyl =
    "Lsystem: 1\nangle increment: 90\nline width: 1\nderivation length: 1\nAxiom: A\n"
    "A --> @Gs F+F @Gc(2) F&F @Ge(3) F\nendlsystem\n";

Scene gencylScene() {
    Model m = parseModel(kGencyl);
    return interpret(m, deriveWithQueries(m));
}

int inkedPixels(const std::filesystem::path& png) {
    cairo_surface_t* img = cairo_image_surface_create_from_png(png.string().c_str());
    if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) return -1;
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    int stride = cairo_image_surface_get_stride(img);
    const unsigned char* data = cairo_image_surface_get_data(img);
    std::uint32_t corner = *reinterpret_cast<const std::uint32_t*>(data);
    int ink = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (*reinterpret_cast<const std::uint32_t*>(data + y * stride + x * 4) != corner) ++ink;
    cairo_surface_destroy(img);
    return ink;
}

}  // namespace

// cpfg's Hermite curve: P(t) = (2t³-3t²+1)A + (t³-2t²+t)·1.2·d·Ha + (3t²-2t³)B +
// (t³-t²)·1.2·d·Hb, d = |B - A|. From A = 0 heading +y to B = (-1, 1, 0) heading -x, at
// t = 0.5: x = -0.5 + 0.125·1.2·√2 = -0.287868, y = 0.5 + 0.125·1.2·√2 = 0.712132, the
// point cpfg's rayshade output of v10_gencyl ends its first cylinder at.
TEST(GeneralizedCylinder, TheCentreLineIsCpfgsHermiteCurve) {
    CylinderControlPoint a, b;
    a.position = {0, 0, 0};
    a.heading = {0, 1, 0};
    b.position = {-1, 1, 0};
    b.heading = {-1, 0, 0};
    expectNear(hermiteCentre(a, b, 0.5), {-0.287868, 0.712132, 0});
    expectNear(hermiteCentre(a, b, 0), a.position, 1e-12);
    expectNear(hermiteCentre(a, b, 1), b.position, 1e-12);
    // @Gt(a, b): b scales the tangent leaving a point, a the one arriving.
    a.tangentLeaving = 0;
    b.tangentArriving = 0;
    expectNear(hermiteCentre(a, b, 0.5), {-0.5, 0.5, 0}, 1e-12);
}

// The chain of cylinders cpfg writes for v10_gencyl (v10_gencyl.ray): 2 steps from the
// first control point to the second, 3 from the second to the third; the F segments are
// drawn as well.
TEST(GeneralizedCylinder, TheOraclesPiecesAreDrawnWhereCpfgDrawsThem) {
    Scene s = gencylScene();
    ASSERT_EQ(s.sweptTubes.size(), 2u);
    const SweptTube &first = s.sweptTubes[0], &second = s.sweptTubes[1];
    ASSERT_EQ(first.segmentCount, 2u);
    ASSERT_EQ(second.segmentCount, 3u);
    ASSERT_EQ(s.segments.size(), 5u + 5u);  // five F, five pieces of centre line
    const Segment* c = &s.segments[first.firstSegment];
    expectNear(c[0].a, {0, 0, 0});
    expectNear(c[0].b, {-0.287868, 0.712132, 0});
    expectNear(c[1].b, {-1, 1, 0});
    c = &s.segments[second.firstSegment];
    expectNear(c[0].a, {-1, 1, 0});
    expectNear(c[0].b, {-1.51067, 1, -0.133551});
    expectNear(c[1].b, {-1.86645, 1, -0.489325});
    expectNear(c[2].b, {-2, 1, -1});
    EXPECT_FLOAT_EQ(c[0].width, 1.0f);  // cpfg's radius 0.5: the initial line width
    EXPECT_TRUE(s.is3D);
}

// `contour sides: 4` gives four-sided cross-sections: a ring of 5 points (the first again),
// every point at the radius (half the line width) from the centre line.
TEST(GeneralizedCylinder, ContourSidesAndTheCircleShapeTheRings) {
    Model m = parseModel(kGencyl);
    m.view.materials.contourSides = 4;  // what the view file's line sets (see TheViewFileLoads...)
    Scene s = interpret(m, deriveWithQueries(m));
    ASSERT_EQ(s.sweptTubes.size(), 2u);
    const SweptTube& t = s.sweptTubes[0];
    EXPECT_EQ(t.ringSize, 5u);
    ASSERT_EQ(t.headings.size(), 3u);  // 2 steps: 3 rings
    for (std::uint32_t i = 0; i < t.ringSize; ++i)
        EXPECT_NEAR(length(t.points[i]), 0.5, 1e-12);  // ring 0 is around the origin
    expectNear(t.points[4], t.points[0], 1e-12);
    // The first point lies along cpfg's up vector (our -U, -z at the start).
    expectNear(t.points[0], {0, 0, -0.5}, 1e-12);
}

// @! sets the sides of the next control points; @# picks a contour (0: the circle).
TEST(GeneralizedCylinder, AtBangSetsTheSidesOfTheNextPiece) {
    Model m = parseModel(
        "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> @Gs f @!(6) @Gc(1) f @!(3) @Ge(1)\n"
        "endlsystem\n");
    Scene s = interpret(m, deriveWithQueries(m));
    ASSERT_EQ(s.sweptTubes.size(), 2u);
    EXPECT_EQ(s.sweptTubes[0].ringSize, 7u);
    EXPECT_EQ(s.sweptTubes[1].ringSize, 4u);
}

// Branches carry a cylinder on from its last control point; after ] the trunk goes on
// from its own last point (cpfg's spline stack).
TEST(GeneralizedCylinder, ABranchContinuesTheCylinderAndTheTrunkResumes) {
    Model m = parseModel(
        "Lsystem: 1\nangle increment: 90\nderivation length: 1\nAxiom: A\n"
        "A --> @Gs f(2) [+ f @Ge(1)] f @Ge(1)\nendlsystem\n");
    Scene s = interpret(m, deriveWithQueries(m));
    ASSERT_EQ(s.sweptTubes.size(), 2u);
    const Segment& branch = s.segments[s.sweptTubes[0].firstSegment];
    const Segment& trunk = s.segments[s.sweptTubes[1].firstSegment];
    expectNear(branch.a, {0, 0, 0});
    expectNear(branch.b, {-1, 2, 0});
    expectNear(trunk.a, {0, 0, 0});
    expectNear(trunk.b, {0, 3, 0});
}

// The mesh draws the swept surface, not the centre line: (steps x sides x 2) triangles per
// piece besides the F cylinders, with normals pointing away from the centre line.
TEST(GeneralizedCylinder, TheMeshSweepsTheSurfaceOutward) {
    Model m = parseModel(
        "Lsystem: 1\nangle increment: 45\nderivation length: 1\nAxiom: A\n"
        "A --> @Gs f(2) + f(2) @Gc(5)\nendlsystem\n");
    m.view.materials.contourSides = 6;
    Scene s = interpret(m, deriveWithQueries(m));
    ASSERT_EQ(s.sweptTubes.size(), 1u);
    Mesh mesh = buildMesh(s);
    EXPECT_EQ(mesh.triangleCount(), 5u * 6u * 2u);
    const SweptTube& t = s.sweptTubes[0];
    for (std::size_t k = 0; k < t.headings.size(); ++k) {
        Vec3 centre{0, 0, 0};
        for (std::uint32_t i = 0; i + 1 < t.ringSize; ++i)
            centre = centre + t.points[k * t.ringSize + i];
        centre = centre * (1.0 / (t.ringSize - 1));
        for (std::uint32_t i = 0; i < t.ringSize; ++i) {
            std::size_t v = k * t.ringSize + i;
            EXPECT_GT(dot(toVec3(mesh.normals[v]), toVec3(mesh.positions[v]) - centre), 0);
        }
    }
    // Every triangle faces the way its vertex normals point.
    for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
        Vec3 p0 = toVec3(mesh.positions[mesh.indices[3 * f]]);
        Vec3 p1 = toVec3(mesh.positions[mesh.indices[3 * f + 1]]);
        Vec3 p2 = toVec3(mesh.positions[mesh.indices[3 * f + 2]]);
        Vec3 n = toVec3(mesh.normals[mesh.indices[3 * f]]);
        EXPECT_GT(dot(cross(p1 - p0, p2 - p0), n), 0) << "triangle " << f;
    }
}

TEST(Contour, TheThreeFileLayoutsAreRead) {
    Contour old = parseContourFile("4 2 closed\n1 0\n0 1\n-1 0\n0 -1\n", "old.con", 3);
    EXPECT_EQ(old.id, 3);
    EXPECT_TRUE(old.closed);
    ASSERT_EQ(old.controlPoints.size(), 4u);
    expectNear(old.controlPoints[1], {0, 1, 0}, 0);

    Contour v11 = parseContourFile(
        "cver 1 1\nname: leaf\npoints: 3 5\ntype: open\n0 0 0 2\n1 1 0 1\n2 0 0 2\n", "v11.con");
    EXPECT_EQ(v11.name, "leaf");
    EXPECT_FALSE(v11.closed);
    ASSERT_EQ(v11.controlPoints.size(), 5u);  // the multiplicities repeat the points
    expectNear(v11.controlPoints[4], {2, 0, 0}, 0);

    Contour v13 = parseContourFile(
        "cver 1 3\nname: c\npoints: 4 4\ntype: cr\nsamples: 5\n1 0 0 1\n0 1 0 1\n-1 0 0 1\n"
        "0 -1 0 1\n",
        "v13.con");
    EXPECT_TRUE(v13.closed);
    EXPECT_EQ(v13.controlPoints.size(), 4u);
}

TEST(Contour, ABadFileIsAnErrorAtItsLineAndColumn) {
    auto messageOf = [](const std::string& text) {
        try {
            parseContourFile(text, "bad.con");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::string badNumber = "cver 1 1\nname: x\npoints: 4 4\ntype: open\n0 0 0 1\n1 q 0 1\n";
    EXPECT_NE(messageOf(badNumber).find("bad.con:6:3"), std::string::npos) << messageOf(badNumber);
    EXPECT_NE(messageOf("cver 1 2\nname: x\npoints: 4 4\ntype: xx\n").find("bad.con:4:7"),
              std::string::npos);
    EXPECT_NE(messageOf("cver 2 0\n").find("bad.con:1:6"), std::string::npos);
    // Too few points: the end of the last line.
    EXPECT_NE(messageOf("3 2 closed\n0 0\n1 1\n").find("bad.con:3:4"), std::string::npos)
        << messageOf("3 2 closed\n0 0\n1 1\n");
    EXPECT_NE(messageOf("").find("bad.con:1:1"), std::string::npos);
}

// Points spaced evenly along the curve; a closed contour starts on +x and ends where it
// started. A square's B-spline is symmetric, so the 4 points of a 4-sided section are
// at right angles.
TEST(Contour, TheCrossSectionIsSpacedEvenlyAndStartsOnX) {
    Contour square = parseContourFile("4 2 closed\n1 1\n-1 1\n-1 -1\n1 -1\n", "sq.con");
    std::vector<Vec3> p = contourPoints(square, 4);
    ASSERT_EQ(p.size(), 5u);
    EXPECT_NEAR(p[0].y, 0, 1e-9);
    EXPECT_GT(p[0].x, 0);
    expectNear(p[4], p[0], 0);
    for (int i = 1; i < 4; ++i) EXPECT_NEAR(dot(p[i], p[0]), i == 2 ? -dot(p[0], p[0]) : 0, 2e-3);
    std::vector<Vec3> c = circleContourPoints(8);
    ASSERT_EQ(c.size(), 9u);
    expectNear(c[2], {0, 1, 0}, 1e-12);
}

// The view file's `contour: ID FILE` loads a .con beside it; @#(ID) picks it.
TEST(Contour, TheViewFileLoadsContoursForAtHash) {
    TempDir dir;
    dir.write("star.con",
              "cver 1 1\nname: star\npoints: 6 6\ntype: closed\n1 0 0 1\n0.3 0.3 0 1\n0 1 0 1\n"
              "-1 0 0 1\n0 -1 0 1\n0.3 -0.3 0 1\n");
    ParseOptions o;
    o.viewFile = dir.write("m.v", "contour sides: 12\ncontour: 2 star.con\n").string();
    ParseResult r = loadModel(dir.write("m.l",
                                        "Lsystem: 1\nderivation length: 1\nAxiom: A\n"
                                        "A --> @#(2) @Gs f(2) @Ge(2)\nendlsystem\n"),
                              o);
    ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].toString());
    ASSERT_EQ(r.model.view.materials.contours.size(), 1u);
    EXPECT_EQ(r.model.view.materials.contours[0].id, 2);
    EXPECT_EQ(r.model.view.materials.contourSides, 12);
    Scene s = interpret(r.model, deriveWithQueries(r.model));
    ASSERT_EQ(s.sweptTubes.size(), 1u);
    EXPECT_EQ(s.sweptTubes[0].ringSize, 13u);
    // Not the circle: the points lie at different distances from the centre line.
    double nearest = 1e9, farthest = 0;
    for (std::uint32_t i = 0; i < 12; ++i) {
        Vec3 q = s.sweptTubes[0].points[i];
        nearest = std::min(nearest, length(q));
        farthest = std::max(farthest, length(q));
    }
    EXPECT_GT(farthest - nearest, 0.2 * farthest);

    o.viewFile = dir.write("bad.v", "contour: 2 missing.con\n").string();
    r = loadModel(dir.path() / "m.l", o);
    ASSERT_TRUE(r.ok());  // view-file problems are warnings
    ASSERT_FALSE(r.warnings().empty());
    EXPECT_NE(r.warnings()[0].toString().find("bad.v:1"), std::string::npos)
        << r.warnings()[0].toString();
    dir.write("broken.con", "cver 1 1\nname: b\npoints: x 4\n");
    o.viewFile = dir.write("bad2.v", "contour: 2 broken.con\n").string();
    r = loadModel(dir.path() / "m.l", o);
    ASSERT_TRUE(r.ok());  // view-file problems are warnings
    ASSERT_FALSE(r.warnings().empty());
    EXPECT_NE(r.warnings()[0].toString().find("broken.con:3:9"), std::string::npos)
        << r.warnings()[0].toString();
    o.viewFile = dir.write("bad3.v", "contour sides: 2\n").string();
    r = loadModel(dir.path() / "m.l", o);
    ASSERT_TRUE(r.ok());  // view-file problems are warnings
    ASSERT_FALSE(r.warnings().empty());
    EXPECT_NE(r.warnings()[0].toString().find("bad3.v:1:16"), std::string::npos)
        << r.warnings()[0].toString();
}

// A flat model made of generalized cylinders draws its centre lines in 2D, and its swept
// surfaces in a ray-traced 3D picture: neither is blank.
TEST(GeneralizedCylinder, PicturesIn2DAnd3DAreNotBlank) {
    TempDir dir;
    auto l = dir.write("g.l",
                       "Lsystem: 1\nangle increment: 30\nline width: 0.4\nderivation length: 1\n"
                       "Axiom: A\nA --> @Gs f + f - f @Gc(6) f + f @Ge(6)\nendlsystem\n");
    auto png = dir.path() / "g.png";
    auto r = runGraftal("render '" + l.string() + "' -q --size 160x160 -o '" + png.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(inkedPixels(png), 200) << "a blank 2D picture";

    auto l3 = dir.write("g3.l",
                        "Lsystem: 1\nangle increment: 30\nline width: 0.4\nderivation length: 1\n"
                        "Axiom: A\nA --> @Gs f & f / f @Gc(6) f ^ f @Ge(6)\nendlsystem\n");
    auto png3 = dir.path() / "g3.png";
    r = runGraftal("render '" + l3.string() + "' -q --size 160x160 --spp 1 -o '" + png3.string() +
                   "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(inkedPixels(png3), 200) << "a blank 3D picture";
}

namespace {

// cpfg's `{(n[, rings])` ... `}(n)` cylinders (cpfg's InitializeSpline and FinishSpline):
// n = 1 open and 2 closed with the Hermite centre line of @Gc, 3 open and 4 closed with a
// uniform cubic B-spline one; F and f set a control point where they end, `.` where the
// turtle is. The square f+f+f+f below has the control points (0,1), (-1,1), (-1,0), (0,0).
std::string splineModel(int type) {
    std::string n = std::to_string(type);
    return "Lsystem: 1\nangle increment: 90\nline width: 1\nderivation length: 0\nAxiom: {(" + n +
           ",2)f+f+f+f}(" + n + ")\nendlsystem\n";
}

Scene splineScene(int type) {
    Model m = parseModel(splineModel(type));
    return interpret(m, deriveWithQueries(m));
}

}  // namespace

// The B-spline span of the four points, in 2 steps (`{(3,2)`): from (P0+4P1+P2)/6 =
// (-5/6, 5/6) heading along P2-P0, through (P0+23P1+23P2+P3)/48 = (-23/24, 1/2) at its
// middle, to (P1+4P2+P3)/6 = (-5/6, 1/6). Three points make no piece: the first is drawn
// when the fourth comes.
TEST(GeneralizedCylinder, AnOpenBSplineCylinderRunsThroughTheSpanOfFourControlPoints) {
    Scene s = splineScene(3);
    ASSERT_EQ(s.sweptTubes.size(), 1u);
    const SweptTube& t = s.sweptTubes[0];
    ASSERT_EQ(t.segmentCount, 2u);
    const Segment* c = &s.segments[t.firstSegment];
    expectNear(c[0].a, {-5.0 / 6, 5.0 / 6, 0}, 1e-12);
    expectNear(c[0].b, {-23.0 / 24, 0.5, 0}, 1e-12);
    expectNear(c[1].b, {-5.0 / 6, 1.0 / 6, 0}, 1e-12);
    expectNear(t.headings[0], {-std::sqrt(0.5), -std::sqrt(0.5), 0}, 1e-12);
    expectNear(t.headings[2], {std::sqrt(0.5), -std::sqrt(0.5), 0}, 1e-12);
    EXPECT_EQ(s.segments.size(), 2u);  // f draws nothing of its own
}

// A closed B-spline goes on through its first three control points at `}(4)`: four spans,
// a loop, each ending where the next starts.
TEST(GeneralizedCylinder, AClosedBSplineCylinderIsALoop) {
    Scene s = splineScene(4);
    ASSERT_EQ(s.sweptTubes.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
        const SweptTube &t = s.sweptTubes[k], &next = s.sweptTubes[(k + 1) % 4];
        const Segment& last = s.segments[t.firstSegment + t.segmentCount - 1];
        expectNear(last.b, s.segments[next.firstSegment].a, 1e-12);
    }
    expectNear(s.segments[s.sweptTubes[0].firstSegment].a, {-5.0 / 6, 5.0 / 6, 0}, 1e-12);
}

// Hermite cylinders: `{(1)` draws a piece from each control point to the next; `{(2)`
// draws one more, from the last back to the first.
TEST(GeneralizedCylinder, HermiteCylindersOpenAndClosed) {
    Scene open = splineScene(1), closed = splineScene(2);
    ASSERT_EQ(open.sweptTubes.size(), 3u);
    ASSERT_EQ(closed.sweptTubes.size(), 4u);
    expectNear(open.segments[open.sweptTubes[0].firstSegment].a, {0, 1, 0}, 1e-12);
    const SweptTube& back = closed.sweptTubes[3];
    expectNear(closed.segments[back.firstSegment].a, {0, 0, 0}, 1e-12);
    expectNear(closed.segments[back.firstSegment + back.segmentCount - 1].b, {0, 1, 0}, 1e-12);
}

// `.` sets a control point, `.(n)` one whose piece has n steps; G moves without setting
// one. `{(5)` is no cylinder type: cpfg ignores it (nothing is drawn between its points),
// and `{` without a parameter (or `{(0)`) is still a polygon.
TEST(GeneralizedCylinder, DotSetsControlPointsAndOtherBracesStayPolygons) {
    Model m = parseModel(
        "Lsystem: 1\nangle increment: 90\nderivation length: 0\n"
        "Axiom: {(1).G+G.(3)}(1) {(5).f.f}(5) {(0).f+f+f}(0) {.f+f+f}\nendlsystem\n");
    Scene s = interpret(m, deriveWithQueries(m));
    ASSERT_EQ(s.sweptTubes.size(), 1u);
    EXPECT_EQ(s.sweptTubes[0].segmentCount, 3u);
    expectNear(s.segments[s.sweptTubes[0].firstSegment + 2].b, {-1, 1, 0}, 1e-12);
    EXPECT_EQ(s.polygonCount(), 2u);
}
