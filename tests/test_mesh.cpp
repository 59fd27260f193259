// buildMesh: segments as closed tubes that share their joint rings, polygons and placed
// surfaces as triangles. Scenes are built by hand, as the turtle would fill them.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

#include "graftal/core/vec3.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/graftal.hpp"

namespace {

using namespace graftal;

// The mesher's own vector arithmetic (a private header): these tests are about the mesh.

Vec3 d(const Vec3f& v) {
    return {v.x, v.y, v.z};
}
Vec3 d(const Vec3& v) {
    return Vec3(v);
}

Segment segment(Vec3 a, Vec3 b, float width, std::uint32_t previous = kNoSegment,
                std::uint16_t color = 0, Vec3 up = {0, 0, 1}) {
    Segment s;
    s.a = a;
    s.b = b;
    s.width = width;
    s.previous = previous;
    s.color = color;
    s.up = up;
    return s;
}

Scene sceneOf(std::vector<Segment> segments) {
    Scene s;
    s.segments = std::move(segments);
    s.is3D = true;
    return s;
}

MeshOptions sides(int n) {
    MeshOptions o;
    o.tubeSides = n;
    return o;
}

// Closed and consistently oriented: every directed edge appears exactly once and its
// reverse exactly once, so every edge is shared by exactly two triangles that agree on
// which side is out. A crack or a duplicated ring shows up as an edge used once.
::testing::AssertionResult isWatertight(const Mesh& m) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
            ++directed[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        if (count != 1)
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " used " << count
                   << " times in the same direction";
        auto back = directed.find({edge.second, edge.first});
        if (back == directed.end())
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " is on a crack";
    }
    return ::testing::AssertionSuccess();
}

// By the divergence theorem: positive for a closed mesh whose triangles face outwards.
double volume(const Mesh& m) {
    double v = 0;
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        v += dot(d(m.positions[m.indices[3 * t]]), cross(d(m.positions[m.indices[3 * t + 1]]),
                                                         d(m.positions[m.indices[3 * t + 2]]))) /
             6;
    return v;
}

// No triangle is folded over: each faces the way its vertex normals point on average.
// (A cap shares its rim with the tube's side, whose normals are perpendicular to the cap;
// its centre's normal is the cap's.)
::testing::AssertionResult facesAgreeWithNormals(const Mesh& m) {
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const std::uint32_t* i = &m.indices[3 * t];
        const Vec3 face = cross((d(m.positions[i[1]]) - d(m.positions[i[0]])),
                                (d(m.positions[i[2]]) - d(m.positions[i[0]])));
        if (length(face) < 1e-12) continue;
        Vec3 n;
        for (int k = 0; k < 3; ++k) {
            n = n + d(m.normals[i[k]]);
        }
        if (dot(face, n) <= 0.1 * length(face) * length(n))
            return ::testing::AssertionFailure() << "triangle " << t << " faces away from "
                                                 << "its vertex normals";
    }
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult normalsAreUnit(const Mesh& m) {
    if (m.normals.size() != m.positions.size())
        return ::testing::AssertionFailure()
               << m.normals.size() << " normals for " << m.positions.size() << " vertices";
    for (std::size_t v = 0; v < m.normals.size(); ++v)
        if (std::abs(length(d(m.normals[v])) - 1) > 1e-5)
            return ::testing::AssertionFailure()
                   << "normal " << v << " has length " << length(d(m.normals[v]));
    return ::testing::AssertionSuccess();
}

double distanceToLine(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    return length(cross((p - a), ab)) / length(ab);
}

// The distances of all vertices from the axis through a and b, rounded to 1e-5.
std::multiset<double> radii(const Mesh& m, const Vec3& a, const Vec3& b) {
    std::multiset<double> r;
    for (const Vec3f& p : m.positions) r.insert(std::round(distanceToLine(d(p), a, b) * 1e5) / 1e5);
    return r;
}

std::size_t distinctPositions(const Mesh& m) {
    std::set<std::tuple<float, float, float>> s;
    for (const Vec3f& p : m.positions) s.insert({p.x, p.y, p.z});
    return s.size();
}

TEST(TubeMesh, SingleSegmentIsAClosedTube) {
    const Scene scene = sceneOf({segment({0, 0, 0}, {0, 2, 0}, 0.5f)});
    const Mesh m = buildMesh(scene, sides(8));
    // Two rings of 8 and two cap centres; 16 side triangles and two fans of 8.
    EXPECT_EQ(m.positions.size(), 18u);
    EXPECT_EQ(m.triangleCount(), 32u);
    EXPECT_EQ(m.indices.size(), 3 * m.triangleCount());
    EXPECT_TRUE(isWatertight(m));
    EXPECT_TRUE(normalsAreUnit(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
    // The width is the diameter: every ring vertex is width / 2 from the axis.
    const auto r = radii(m, {0, 0, 0}, {0, 2, 0});
    EXPECT_EQ(r.count(0.25), 16u);
    EXPECT_EQ(r.count(0.0), 2u);
    // An octagon of circumradius r has area 2 sqrt(2) r^2.
    EXPECT_NEAR(volume(m), 2 * std::sqrt(2.0) * 0.25 * 0.25 * 2, 1e-6);
    const Bounds b = m.bounds();
    EXPECT_NEAR(b.min.y, 0, 1e-6);
    EXPECT_NEAR(b.max.y, 2, 1e-6);
    EXPECT_NEAR(b.max.x, 0.25, 1e-6);
    EXPECT_NEAR(b.max.z, 0.25, 1e-6);
    // Side normals point away from the axis.
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        const Vec3 p = d(m.positions[v]);
        if (distanceToLine(p, {0, 0, 0}, {0, 2, 0}) < 0.1) continue;
        EXPECT_GT(dot(d(m.normals[v]), {p.x, 0, p.z}), 0) << v;
    }
    EXPECT_EQ(m.triangleColor, std::vector<std::uint16_t>(32, 0));
    EXPECT_EQ(m.palette, scene.palette);
}

TEST(TubeMesh, SidesWidthScaleAndMinimumRadius) {
    const Scene scene = sceneOf({segment({1, 1, 1}, {1, 1, 3}, 0.5f)});
    const Mesh five = buildMesh(scene, sides(5));
    EXPECT_EQ(five.positions.size(), 12u);
    EXPECT_EQ(five.triangleCount(), 20u);
    EXPECT_TRUE(isWatertight(five));

    MeshOptions o = sides(6);
    o.widthScale = 2;
    EXPECT_EQ(radii(buildMesh(scene, o), {1, 1, 1}, {1, 1, 3}).count(0.5), 12u);

    // A stem of width 0 is widened to the minimum radius; thicker ones keep theirs.
    o = sides(6);
    o.minimumRadius = 0.1;
    const Scene thin = sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.0f)});
    EXPECT_EQ(radii(buildMesh(thin, o), {0, 0, 0}, {0, 1, 0}).count(0.1), 12u);
    EXPECT_EQ(radii(buildMesh(scene, o), {1, 1, 1}, {1, 1, 3}).count(0.25), 12u);
}

TEST(TubeMesh, ConsecutiveSegmentsShareTheirJointRing) {
    const Scene scene =
        sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.5f), segment({0, 1, 0}, {0, 2, 0}, 0.5f, 0)});
    const Mesh m = buildMesh(scene, sides(8));
    // Three rings, not four; two caps.
    EXPECT_EQ(m.positions.size(), 3u * 8 + 2);
    EXPECT_EQ(m.triangleCount(), 2u * 16 + 16);
    EXPECT_EQ(distinctPositions(m), m.positions.size());
    EXPECT_TRUE(isWatertight(m));
    EXPECT_NEAR(volume(m), 2 * std::sqrt(2.0) * 0.25 * 0.25 * 2, 1e-6);
}

// A curve bending 30 degrees at every joint, each time about a different axis.
Scene bentAxis(int count, double width) {
    std::vector<Segment> s;
    Vec3 p{0, 0, 0}, h{0, 1, 0};
    for (int i = 0; i < count; ++i) {
        const Vec3 q = p + h;
        s.push_back(segment(p, q, static_cast<float>(width),
                            i == 0 ? kNoSegment : static_cast<std::uint32_t>(i - 1), 0,
                            {0.3, 0.1, 1}));
        p = q;
        // Rotate h by 30 degrees about an axis perpendicular to it that turns with i.
        const Vec3 axis = i % 2 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
        const Vec3 k = normalizedOr(cross(h, axis), {});
        const double c = std::cos(std::numbers::pi / 6), sn = std::sin(std::numbers::pi / 6);
        h = c * h + sn * cross(k, h);
    }
    return sceneOf(std::move(s));
}

TEST(TubeMesh, BentAxisHasNoCracks) {
    const Scene scene = bentAxis(6, 0.3);
    const Mesh m = buildMesh(scene, sides(8));
    EXPECT_EQ(m.positions.size(), 7u * 8 + 2);
    EXPECT_EQ(m.triangleCount(), 6u * 16 + 16);
    EXPECT_TRUE(isWatertight(m));
    EXPECT_TRUE(normalsAreUnit(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
    EXPECT_GT(volume(m), 0);
    // The joint rings lie on both cylinders they join: the mitre is exact.
    for (std::size_t i = 0; i + 1 < scene.segments.size(); ++i) {
        const Segment& s0 = scene.segments[i];
        const Segment& s1 = scene.segments[i + 1];
        int onBoth = 0;
        for (const Vec3f& p : m.positions)
            if (std::abs(distanceToLine(d(p), d(s0.a), d(s0.b)) - 0.15) < 1e-5 &&
                std::abs(distanceToLine(d(p), d(s1.a), d(s1.b)) - 0.15) < 1e-5 &&
                length((d(p) - d(s0.b))) < 0.5)
                ++onBoth;
        EXPECT_EQ(onBoth, 8) << "joint " << i;
    }
}

TEST(TubeMesh, FrameIsCarriedWithoutTwisting) {
    // An arc in the z = 0 plane with the first up vector along z. Later segments' up
    // vectors roll around the heading; the tube must ignore that and not twist, so the
    // first vertex of every ring stays at the top (z = r).
    std::vector<Segment> s;
    Vec3 p{0, 0, 0};
    for (int i = 0; i < 10; ++i) {
        const double a = 0.2 * i;
        const Vec3 q{p.x + std::sin(a), p.y + std::cos(a), 0};
        const Vec3 up = i == 0 ? Vec3{0, 0, 1} : Vec3{std::cos(i), 0, std::sin(i)};
        s.push_back(segment(p, q, 0.2f, i == 0 ? kNoSegment : i - 1, 0, up));
        p = q;
    }
    const Mesh m = buildMesh(sceneOf(s), sides(8));
    EXPECT_TRUE(isWatertight(m));
    int top = 0;
    for (const Vec3f& v : m.positions) top += std::abs(v.z - 0.1) < 1e-6;
    EXPECT_EQ(top, 11);  // one per ring
}

TEST(TubeMesh, SharpBendIsCappedOnBothSides) {
    // 150 degrees: a shared ring would be stretched to nearly four times the radius.
    const double a = 150 * std::numbers::pi / 180;
    const Scene scene = sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.2f),
                                 segment({0, 1, 0}, {std::sin(a), 1 + std::cos(a), 0}, 0.2f, 0)});
    const Mesh m = buildMesh(scene, sides(8));
    EXPECT_EQ(m.positions.size(), 2u * 18);
    EXPECT_EQ(m.triangleCount(), 2u * 32);
    EXPECT_TRUE(isWatertight(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
}

TEST(TubeMesh, ShortSegmentsOfAThickStemAreNotMitred) {
    // 90 degrees on segments shorter than the stem is thick: a mitre would cut through the
    // neighbouring rings, so the joint is capped instead.
    const Scene scene = sceneOf(
        {segment({0, 0, 0}, {0, 0.2, 0}, 1.0f), segment({0, 0.2, 0}, {0.2, 0.2, 0}, 1.0f, 0)});
    const Mesh m = buildMesh(scene, sides(8));
    EXPECT_EQ(m.positions.size(), 2u * 18);
    EXPECT_TRUE(isWatertight(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
}

TEST(TubeMesh, WidthTapersAlongTheAxis) {
    const Scene scene =
        sceneOf({segment({0, 0, 0}, {0, 1, 0}, 1.0f), segment({0, 1, 0}, {0, 2, 0}, 0.5f, 0)});
    const Mesh m = buildMesh(scene, sides(8));
    const auto r = radii(m, {0, 0, 0}, {0, 1, 0});
    // The first segment is 1 wide throughout; the second narrows from 1 to 0.5.
    EXPECT_EQ(r.count(0.5), 16u);
    EXPECT_EQ(r.count(0.25), 8u);
    EXPECT_TRUE(isWatertight(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
    // Normals on the narrowing part lean towards the thin end.
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        const Vec3 p = d(m.positions[v]);
        if (std::abs(p.y - 2) < 1e-6 && distanceToLine(p, {0, 0, 0}, {0, 1, 0}) > 0.2) {
            EXPECT_GT(m.normals[v].y, 0.1) << v;
        }
    }
}

TEST(TubeMesh, ZeroWidthTipIsACone) {
    const Scene scene =
        sceneOf({segment({0, 0, 0}, {0, 1, 0}, 1.0f), segment({0, 1, 0}, {0, 2, 0}, 0.0f, 0)});
    const Mesh m = buildMesh(scene, sides(8));
    // Start ring and cap centre, joint ring, apex; start cap, sides, cone.
    EXPECT_EQ(m.positions.size(), 8u + 1 + 8 + 1);
    EXPECT_EQ(m.triangleCount(), 8u + 16 + 8);
    EXPECT_TRUE(isWatertight(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
    EXPECT_EQ(radii(m, {0, 0, 0}, {0, 1, 0}).count(0.0), 2u);
    EXPECT_NEAR(m.bounds().max.y, 2, 1e-6);
}

TEST(TubeMesh, BranchesAreTubesOfTheirOwn) {
    // Segment 2 branches off where segment 1 continues segment 0; even marked as a
    // continuation, the branch does not take the joint ring from the straighter segment.
    for (std::uint32_t branchPrevious : {kNoSegment, 0u}) {
        const Scene scene =
            sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.2f), segment({0, 1, 0}, {0, 2, 0}, 0.2f, 0),
                     segment({0, 1, 0}, {0.7, 1.7, 0}, 0.2f, branchPrevious)});
        const Mesh m = buildMesh(scene, sides(8));
        EXPECT_EQ(m.positions.size(), (3u * 8 + 2) + 18);
        EXPECT_TRUE(isWatertight(m));
        EXPECT_TRUE(facesAgreeWithNormals(m));
    }
}

TEST(TubeMesh, DegenerateSegmentsAreLookedThrough) {
    // A zero-length segment inside an axis (a turtle that drew F with step 0) neither
    // breaks the tube nor adds to it; a non-finite one is left out.
    const Scene scene =
        sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.2f), segment({0, 1, 0}, {0, 1, 0}, 0.2f, 0),
                 segment({0, 1, 0}, {0, 2, 0}, 0.2f, 1), segment({0, 0, 0}, {NAN, 1, 0}, 0.2f)});
    const Mesh m = buildMesh(scene, sides(8));
    EXPECT_EQ(m.positions.size(), 3u * 8 + 2);
    EXPECT_TRUE(isWatertight(m));
}

TEST(TubeMesh, ColoursComeFromSegments) {
    const Scene scene = sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.2f, kNoSegment, 5),
                                 segment({0, 1, 0}, {0, 2, 0}, 0.2f, 0, 1)});
    const Mesh m = buildMesh(scene, sides(4));
    std::map<std::uint16_t, int> count;
    for (std::uint16_t c : m.triangleColor) ++count[c];
    // Segment 0: its start cap and sides; segment 1: its sides and end cap.
    EXPECT_EQ(count[5], 4 + 8);
    EXPECT_EQ(count[1], 8 + 4);
}

TEST(TubeMesh, CylindersCanBeLeftOut) {
    MeshOptions o;
    o.cylinders = false;
    EXPECT_EQ(buildMesh(bentAxis(3, 0.1), o).triangleCount(), 0u);
}

TEST(TubeMesh, BigPlantIsAllocatedOnce) {
    // 500 axes of 100 segments: the counts are exact, so the arrays never grow.
    std::vector<Segment> s;
    for (int axis = 0; axis < 500; ++axis)
        for (int i = 0; i < 100; ++i)
            s.push_back(segment({axis * 1.0, i * 0.1, 0}, {axis * 1.0, (i + 1) * 0.1, 0.0}, 0.05f,
                                i == 0 ? kNoSegment : static_cast<std::uint32_t>(s.size() - 1)));
    const Mesh m = buildMesh(sceneOf(std::move(s)), sides(8));
    EXPECT_EQ(m.positions.size(), 500u * (101 * 8 + 2));
    EXPECT_EQ(m.triangleCount(), 500u * (100 * 16 + 16));
    EXPECT_EQ(m.positions.capacity(), m.positions.size());
    EXPECT_EQ(m.indices.capacity(), m.indices.size());
}

TEST(PolygonMesh, PolygonsAreFlatShadedTriangles) {
    Scene scene;
    const std::vector<Vec3> l = {{0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1, 1, 1}, {1, 3, 1}, {0, 3, 1}};
    scene.addPolygon(l, 3);
    std::vector<Vec3> clockwise(l.rbegin(), l.rend());
    for (Vec3& v : clockwise) v.x += 5;
    scene.addPolygon(clockwise, 4);
    const Mesh m = buildMesh(scene);
    EXPECT_EQ(m.positions.size(), 12u);
    EXPECT_EQ(m.triangleCount(), 8u);
    EXPECT_TRUE(facesAgreeWithNormals(m));
    // Single-sided: each faces the side its outline winds counter-clockwise around.
    for (std::size_t v = 0; v < 6; ++v) EXPECT_EQ(m.normals[v], (Vec3f{0, 0, 1}));
    for (std::size_t v = 6; v < 12; ++v) EXPECT_EQ(m.normals[v], (Vec3f{0, 0, -1}));
    EXPECT_EQ(m.triangleColor, (std::vector<std::uint16_t>{3, 3, 3, 3, 4, 4, 4, 4}));
    double area = 0;
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        area += length(cross(
                    (d(m.positions[m.indices[3 * t + 1]]) - d(m.positions[m.indices[3 * t]])),
                    (d(m.positions[m.indices[3 * t + 2]]) - d(m.positions[m.indices[3 * t]])))) /
                2;
    EXPECT_NEAR(area, 8, 1e-6);
}

TEST(PolygonMesh, DegeneratePolygonsAreSkipped) {
    Scene scene;
    scene.addPolygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}}, 1);
    scene.addPolygon(std::vector<Vec3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, 1);
    scene.addPolygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 2);
    const Mesh m = buildMesh(scene);
    EXPECT_EQ(m.triangleCount(), 1u);
    EXPECT_EQ(m.triangleColor, std::vector<std::uint16_t>{2});
}

// A flat unit square in the surface's own xy-plane: s along x, t along y.
Surface squareSurface() {
    Surface s;
    s.name = "square";
    BezierPatch p;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            p.points[static_cast<std::size_t>(row * 4 + col)] = {col / 3.0, row / 3.0, 0};
    s.patches = {p};
    s.contactPoint = {0.5, 0, 0};
    s.heading = {0, 1, 0};
    s.up = {0, 0, 1};
    s.size = 2;
    return s;
}

bool hasVertexAt(const Mesh& m, const Vec3& p) {
    for (const Vec3f& v : m.positions)
        if (length((d(v) - p)) < 1e-5) return true;
    return false;
}

TEST(SurfaceMesh, PlacedSurfaceIsTessellatedAtTheTurtle) {
    SurfaceLibrary library;
    library.add(squareSurface());
    Scene scene;
    scene.surfaceNames = {"square"};
    SurfaceInstance at;
    at.surface = 0;
    at.origin = {5, 0, 0};
    // The turtle heads along +x with its up along +z: H x L = U.
    at.heading = {1, 0, 0};
    at.left = {0, 1, 0};
    at.up = {0, 0, 1};
    at.scale = 4;  // over the surface's size 2: twice as big
    at.color = 2;
    scene.surfaces = {at};
    MeshOptions o;
    o.surfaceDivisions = 4;
    const Mesh m = buildMesh(scene, o, &library);
    EXPECT_EQ(m.positions.size(), 25u);
    EXPECT_EQ(m.triangleCount(), 32u);
    EXPECT_EQ(m.triangleColor, std::vector<std::uint16_t>(32, 2));
    EXPECT_TRUE(normalsAreUnit(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
    // The contact point lands on the turtle; the surface's heading (+y) along H (+x), its
    // left (-x) along L (+y), scaled by 2.
    EXPECT_TRUE(hasVertexAt(m, {5, 0, 0}));
    EXPECT_TRUE(hasVertexAt(m, {7, 0, 0}));
    EXPECT_TRUE(hasVertexAt(m, {7, 1, 0}));
    EXPECT_TRUE(hasVertexAt(m, {5, -1, 0}));
    const Bounds b = m.bounds();
    EXPECT_NEAR(b.min.x, 5, 1e-6);
    EXPECT_NEAR(b.max.x, 7, 1e-6);
    EXPECT_NEAR(b.min.y, -1, 1e-6);
    EXPECT_NEAR(b.max.y, 1, 1e-6);
    for (const Vec3f& n : m.normals) EXPECT_NEAR(std::abs(n.z), 1, 1e-6);

    // Turned upside down (U = -z, so L = -y), the surface mirrors across y and faces down.
    scene.surfaces[0].left = {0, -1, 0};
    scene.surfaces[0].up = {0, 0, -1};
    const Mesh flipped = buildMesh(scene, o, &library);
    EXPECT_TRUE(facesAgreeWithNormals(flipped));
    EXPECT_TRUE(hasVertexAt(flipped, {7, -1, 0}));
    for (std::size_t v = 0; v < m.normals.size(); ++v)
        EXPECT_NEAR(flipped.normals[v].z, -m.normals[v].z, 1e-6);
}

TEST(SurfaceMesh, BuiltinSurfacesTessellateCleanly) {
    const SurfaceLibrary library = SurfaceLibrary::builtin();
    Scene scene;
    scene.surfaceNames = library.names();
    ASSERT_FALSE(scene.surfaceNames.empty());
    for (std::uint32_t i = 0; i < scene.surfaceNames.size(); ++i) {
        SurfaceInstance at;
        at.surface = i;
        at.origin = {static_cast<double>(i), 0, 0};
        scene.surfaces.push_back(at);
    }
    const Mesh m = buildMesh(scene, {}, &library);
    EXPECT_GT(m.triangleCount(), 0u);
    EXPECT_TRUE(normalsAreUnit(m));
    EXPECT_TRUE(facesAgreeWithNormals(m));
}

TEST(SurfaceMesh, UnknownSurfacesAreErrors) {
    SurfaceLibrary library;
    library.add(squareSurface());
    Scene scene;
    scene.surfaceNames = {"leaf"};
    scene.surfaces = {SurfaceInstance{}};
    try {
        buildMesh(scene, {}, &library);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown surface 'leaf'"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("square"), std::string::npos) << e.what();
    }
    EXPECT_THROW(buildMesh(scene), Error);
}

TEST(MeshOptionsCheck, InvalidOptionsAreErrors) {
    const Scene scene = sceneOf({segment({0, 0, 0}, {0, 1, 0}, 1)});
    EXPECT_THROW(buildMesh(scene, sides(2)), Error);
    MeshOptions o;
    o.minimumRadius = -1;
    EXPECT_THROW(buildMesh(scene, o), Error);
    o = {};
    o.surfaceDivisions = 0;
    EXPECT_THROW(buildMesh(scene, o), Error);
}

TEST(MeshValue, PrintsCountsAndBounds) {
    const Mesh m = buildMesh(sceneOf({segment({0, 0, 0}, {0, 2, 0}, 0.5f)}));
    std::ostringstream os;
    os << m;
    EXPECT_EQ(os.str().rfind("mesh: 18 vertices, 32 triangles, 1 colour, bounds (", 0), 0u)
        << os.str();
    std::ostringstream empty;
    empty << Mesh{};
    EXPECT_EQ(empty.str(), "mesh: 0 vertices, 0 triangles, 0 colours, bounds empty");
}

TEST(MeshValue, AppendOffsetsIndices) {
    Mesh a = buildMesh(sceneOf({segment({0, 0, 0}, {0, 1, 0}, 0.5f)}));
    const Mesh b = buildMesh(sceneOf({segment({3, 0, 0}, {3, 1, 0}, 0.5f, kNoSegment, 2)}));
    a.append(b);
    EXPECT_EQ(a.positions.size(), 36u);
    EXPECT_EQ(a.triangleCount(), 64u);
    EXPECT_EQ(a.indices[3 * 32], b.indices[0] + 18);
    EXPECT_TRUE(isWatertight(a));
    Mesh other = b;
    other.palette = {Rgb{1, 0, 0}};
    EXPECT_THROW(a.append(other), Error);
}

}  // namespace
