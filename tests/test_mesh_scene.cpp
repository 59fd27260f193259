// buildMeshScene: repeated organs stored once and placed by transforms. Flattening an
// instanced scene must give buildMesh's triangles (same count, same places, same facing)
// and bounds; thin stems become curves when asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "graftal/core/vec3.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/graftal.hpp"
#include "test_helpers.hpp"

namespace {

using namespace graftal;
namespace fs = std::filesystem;

Scene exampleScene(const std::string& name) {
    const Model m = graftal::testing::loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / name);
    return interpret(m, applyHomomorphism(m.lsystem, derive(m)));
}

Vec3 d(const Vec3f& v) {
    return {v.x, v.y, v.z};
}

// One triangle as a user would compare it: where it is, which way it faces (its winding)
// and which way its vertex normals point.
struct TriangleView {
    Vec3 centroid, facing, shading;
    std::uint16_t color;
};

std::vector<TriangleView> triangles(const Mesh& m) {
    std::vector<TriangleView> out;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const std::uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1],
                            c = m.indices[3 * t + 2];
        const Vec3 pa = d(m.positions[a]), pb = d(m.positions[b]), pc = d(m.positions[c]);
        out.push_back({(1.0 / 3) * (pa + pb + pc), normalizedOr(cross(pb - pa, pc - pa), {}),
                       normalizedOr(d(m.normals[a]) + d(m.normals[b]) + d(m.normals[c]), {}),
                       m.triangleColor[t]});
    }
    return out;
}

// Every triangle of `got` has one of `want` within `tolerance` of its centroid, in the
// same colour, facing the same way with the same shading normal (degenerate triangles
// compare by place only). Returns how many did not.
std::size_t unmatchedTriangles(const Mesh& got, const Mesh& want, double tolerance) {
    const std::vector<TriangleView> g = triangles(got), w = triangles(want);
    auto cell = [&](const Vec3& p) {
        return std::array<long long, 3>{std::llround(p.x / tolerance),
                                        std::llround(p.y / tolerance),
                                        std::llround(p.z / tolerance)};
    };
    struct CellHash {
        std::size_t operator()(const std::array<long long, 3>& c) const {
            return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^
                                            c[2] * 83492791LL);
        }
    };
    std::unordered_map<std::array<long long, 3>, std::vector<std::size_t>, CellHash> grid;
    for (std::size_t i = 0; i < w.size(); ++i) grid[cell(w[i].centroid)].push_back(i);
    std::size_t unmatched = 0;
    for (const TriangleView& t : g) {
        const auto c = cell(t.centroid);
        bool found = false;
        for (long long dx = -1; dx <= 1 && !found; ++dx)
            for (long long dy = -1; dy <= 1 && !found; ++dy)
                for (long long dz = -1; dz <= 1 && !found; ++dz) {
                    auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == grid.end()) continue;
                    for (std::size_t i : it->second) {
                        const TriangleView& u = w[i];
                        if (u.color != t.color || length(u.centroid - t.centroid) > tolerance)
                            continue;
                        const bool flat = length(t.facing) == 0 || length(u.facing) == 0;
                        if (flat ||
                            (dot(u.facing, t.facing) > 0.9 && dot(u.shading, t.shading) > 0.9)) {
                            found = true;
                            break;
                        }
                    }
                }
        if (!found) ++unmatched;
    }
    return unmatched;
}

double extent(const Bounds& b) {
    const Vec3 e = b.max - b.min;
    return std::max({e.x, e.y, e.z});
}

// The comparison every instanced scene must pass against buildMesh.
void expectSameDrawing(const Scene& scene, const MeshOptions& options,
                       const SurfaceLibrary* library) {
    MeshOptions copies = options;
    copies.instancing = false;
    const Mesh want = buildMesh(scene, copies, library);
    MeshOptions instanced = options;
    instanced.instancing = true;
    const MeshScene s = buildMeshScene(scene, instanced, library);
    const Mesh got = s.flattened();
    ASSERT_EQ(got.triangleCount(), want.triangleCount());
    EXPECT_EQ(s.triangleCount(), want.triangleCount());
    const double tolerance = 1e-4 * std::max(1.0, extent(want.bounds()));
    EXPECT_EQ(unmatchedTriangles(got, want, tolerance), 0u);
    EXPECT_EQ(unmatchedTriangles(want, got, tolerance), 0u);
    const Bounds a = s.bounds(), b = want.bounds();
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR((&a.min.x)[k], (&b.min.x)[k], tolerance);
        EXPECT_NEAR((&a.max.x)[k], (&b.max.x)[k], tolerance);
    }
    for (const Vec3f& n : got.normals) EXPECT_NEAR(length(d(n)), 1, 1e-4);
}

Surface squareSurface() {
    Surface s;
    s.name = "square";
    BezierPatch p;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            p.points[static_cast<std::size_t>(row * 4 + col)] = {col / 3.0, row / 3.0,
                                                                 0.1 * col * row};
    s.patches = {p};
    s.contactPoint = {0.5, 0, 0};
    s.size = 2;
    return s;
}

// Surfaces in two colours, one in a mirrored turtle frame, one scaled to nothing (drawn by
// neither), discs facing three ways and spheres of two sizes.
Scene handMadeScene() {
    Scene scene;
    scene.surfaceNames = {"square"};
    SurfaceInstance at;
    at.origin = {5, 0, 0};
    at.heading = {1, 0, 0};
    at.left = {0, 1, 0};
    at.up = {0, 0, 1};
    at.scale = 4;
    at.color = 2;
    scene.surfaces.push_back(at);
    SurfaceInstance mirrored = at;
    mirrored.origin = {0, 3, 1};
    mirrored.up = {0, 0, -1};  // H x L = +z, but the frame says -z: mirrored
    scene.surfaces.push_back(mirrored);
    SurfaceInstance turned = at;
    turned.origin = {-2, 1, 4};
    turned.heading = normalized(Vec3{0, 1, 1});
    turned.left = {-1, 0, 0};
    turned.up = cross(turned.heading, turned.left);
    turned.color = 3;
    turned.scale = 0.5;
    scene.surfaces.push_back(turned);
    SurfaceInstance nothing = at;
    nothing.scale = 0;
    scene.surfaces.push_back(nothing);
    scene.discs.push_back({{1, 1, 1}, {0, 0, 1}, 0.5, 1});
    scene.discs.push_back({{2, 1, 1}, normalized(Vec3{1, 1, 0}), 0.25, 1});
    scene.discs.push_back({{3, 1, 1}, {0, 0, -1}, 1, 4});
    scene.spheres.push_back({{0, 0, 0}, 0.5, 2});
    scene.spheres.push_back({{4, -2, 1}, 2, 2});
    // A stem, which stays in the shared mesh.
    scene.segments.push_back({{0, 0, 0}, {0, 1, 0}, 0.2f, 0, kNoSegment, {0, 0, 1}});
    scene.is3D = true;
    return scene;
}

TEST(MeshScene, FlattenedHandMadeSceneIsTheCopiedMesh) {
    SurfaceLibrary library;
    library.add(squareSurface());
    const Scene scene = handMadeScene();
    MeshOptions o;
    o.surfaceDivisions = 5;
    expectSameDrawing(scene, o, &library);

    const MeshScene s = buildMeshScene(scene, o, &library);
    // Square in colours 2 and 3, a disc in colours 1 and 4, a sphere in colour 2.
    EXPECT_EQ(s.prototypes.size(), 5u);
    // Every organ but the surface scaled to nothing.
    EXPECT_EQ(s.placements.size(), 3u + 3u + 2u);
    // The shared mesh holds the stem alone: a closed tube of 8 sides, 16 + 2 * 8 triangles.
    EXPECT_EQ(s.mesh.triangleCount(), 32u);
    for (const Mesh& p : s.prototypes) EXPECT_EQ(p.palette, scene.palette);
    // The mirrored frame's placement mirrors.
    EXPECT_GT(s.placements[0].transform.determinant(), 0);
    EXPECT_LT(s.placements[1].transform.determinant(), 0);
}

TEST(MeshScene, WithoutInstancingEverythingIsInTheMesh) {
    SurfaceLibrary library;
    library.add(squareSurface());
    const Scene scene = handMadeScene();
    MeshOptions o;
    o.instancing = false;
    const MeshScene s = buildMeshScene(scene, o, &library);
    const Mesh m = buildMesh(scene, o, &library);
    EXPECT_TRUE(s.prototypes.empty());
    EXPECT_TRUE(s.placements.empty());
    EXPECT_EQ(s.mesh.positions, m.positions);
    EXPECT_EQ(s.mesh.normals, m.normals);
    EXPECT_EQ(s.mesh.indices, m.indices);
    EXPECT_EQ(s.mesh.triangleColor, m.triangleColor);
}

TEST(MeshScene, LychnisLeavesAndPetalsAreStoredOnce) {
    const SurfaceLibrary library = SurfaceLibrary::builtin();
    const Scene scene = exampleScene("fig3.9-lychnis-3d.l");
    ASSERT_GT(scene.surfaces.size(), 50u);
    expectSameDrawing(scene, {}, &library);
    const MeshScene s = buildMeshScene(scene, {}, &library);
    // One prototype per surface and colour the plant uses, one placement per organ.
    std::set<std::pair<std::uint32_t, std::uint16_t>> kinds;
    for (const SurfaceInstance& i : scene.surfaces) kinds.insert({i.surface, i.color});
    EXPECT_EQ(s.prototypes.size(), kinds.size());
    EXPECT_EQ(s.placements.size(), scene.surfaces.size());
    EXPECT_LE(s.prototypes.size(), 8u);
}

TEST(MeshScene, MirroredNormalsPointOutOfTheMirroredSurface) {
    Affine3f mirror;
    mirror.columns[0] = {2, 0, 0};
    mirror.columns[1] = {0, 2, 0};
    mirror.columns[2] = {0, 0, -2};
    mirror.columns[3] = {1, 2, 3};
    EXPECT_FLOAT_EQ(mirror.determinant(), -8);
    const Vec3f up = mirror.normal({0, 0, 1});
    EXPECT_FLOAT_EQ(up.z, -1);
    EXPECT_FLOAT_EQ(up.x, 0);
    // A shear keeps normals perpendicular to the sheared surface, not along the sheared
    // normal: the plane z = 0 stays z = 0 under x += z.
    Affine3f shear;
    shear.columns[2] = {1, 0, 1};
    const Vec3f n = shear.normal({0, 0, 1});
    EXPECT_NEAR(n.x, 0, 1e-6);
    EXPECT_NEAR(n.z, 1, 1e-6);
    // The plane x = z (normal (1, 0, -1)/sqrt 2) goes to x = 2z under x += z.
    const Vec3f m =
        shear.normal({static_cast<float>(std::sqrt(0.5)), 0, static_cast<float>(-std::sqrt(0.5))});
    EXPECT_NEAR(m.x / -m.z, 0.5, 1e-5);
}

}  // namespace

namespace {

TEST(MeshScene, FlowerFieldLeavesAndPetalsArePlaced) {
    const Scene scene = exampleScene("fig3.17-flower-field-3d.l");
    ASSERT_GT(scene.polygonCount(), 1000u);
    expectSameDrawing(scene, {}, nullptr);
    const MeshScene s = buildMeshScene(scene, {}, nullptr);
    // The leaf and the petal wedge, in their colours, perhaps mirrored: a few shapes.
    EXPECT_LE(s.prototypes.size(), 10u);
    EXPECT_GT(s.placements.size(), 1000u);
    // What is left in the shared mesh is the stems.
    std::size_t stemTriangles = buildMeshScene(scene, {}, nullptr).mesh.triangleCount();
    Scene stemsOnly = scene;
    stemsOnly.polygonVertices.clear();
    stemsOnly.polygonStart = {0};
    stemsOnly.polygonColor.clear();
    EXPECT_EQ(stemTriangles, buildMesh(stemsOnly).triangleCount());
}

}  // namespace

namespace {

Segment stem(Vec3 a, Vec3 b, float width, std::uint32_t previous) {
    return {a, b, width, 0, previous, {0, 0, 1}};
}

// An axis thick, thin, thin, thick: the thin middle becomes two joined curves, the thick
// ends two capped tubes.
Scene thickThinThick() {
    Scene scene;
    scene.segments.push_back(stem({0, 0, 0}, {0, 1, 0}, 1.0f, kNoSegment));
    scene.segments.push_back(stem({0, 1, 0}, {0, 2, 0}, 0.1f, 0));
    scene.segments.push_back(stem({0, 2, 0}, {0.5, 3, 0}, 0.1f, 1));
    scene.segments.push_back(stem({0.5, 3, 0}, {0.5, 4, 0}, 1.0f, 2));
    scene.is3D = true;
    return scene;
}

TEST(MeshScene, ThinStemsBecomeCurvesWithTheirJoints) {
    const Scene scene = thickThinThick();
    MeshOptions o;
    o.curveRadius = 0.2;
    const MeshScene s = buildMeshScene(scene, o);
    ASSERT_EQ(s.curves.size(), 2u);
    const CurveSegment& first = s.curves[0];
    const CurveSegment& second = s.curves[1];
    EXPECT_EQ(d(first.a), Vec3(0, 1, 0));
    EXPECT_EQ(d(first.b), Vec3(0, 2, 0));
    // The stem narrows from the tube's radius to its own, as a tube would.
    EXPECT_FLOAT_EQ(first.radiusA, 0.5f);
    EXPECT_FLOAT_EQ(first.radiusB, 0.05f);
    EXPECT_EQ(first.previous, kNoSegment);
    // The second continues the first: the same joint, the same radius there.
    EXPECT_EQ(second.previous, 0u);
    EXPECT_EQ(second.a, first.b);
    EXPECT_FLOAT_EQ(second.radiusA, 0.05f);
    EXPECT_EQ(d(second.b), Vec3(0.5, 3, 0));
    // Two capped tubes of one segment each, 8 sides: 2 * (16 sides + 2 * 8 cap) triangles
    // (one tube through all four would have 4 * 16 + 2 * 8).
    EXPECT_EQ(s.mesh.triangleCount(), 64u);
    EXPECT_EQ(buildMeshScene(scene).mesh.triangleCount(), 80u);
    // buildMesh knows no curves: every segment a tube.
    EXPECT_EQ(buildMesh(scene, o).triangleCount(), 80u);
}

TEST(MeshScene, CurvesCountTheRadiusAfterTheMinimum) {
    const Scene scene = thickThinThick();
    MeshOptions o;
    o.curveRadius = 0.2;
    o.minimumRadius = 0.25;  // the thin stems are drawn 0.25 thick: tubes
    EXPECT_TRUE(buildMeshScene(scene, o).curves.empty());
    o.minimumRadius = 0;
    o.widthScale = 10;  // radius 0.5 for the thin ones: tubes
    EXPECT_TRUE(buildMeshScene(scene, o).curves.empty());
    o.widthScale = 1;
    o.curveRadius = 1;  // everything is thinner
    const MeshScene all = buildMeshScene(scene, o);
    EXPECT_EQ(all.curves.size(), 4u);
    EXPECT_EQ(all.mesh.triangleCount(), 0u);
    EXPECT_EQ(all.curves[3].previous, 2u);
    // The bounds are the curves', widened by their radii: the last ends at y = 4, 0.5 thick.
    const Bounds b = all.bounds();
    EXPECT_NEAR(b.max.y, 4.5, 1e-6);
    EXPECT_NEAR(b.min.x, -0.5, 1e-6);
}

TEST(MeshScene, ATreeSplitsIntoTubesAndCurves) {
    const Model m =
        graftal::testing::loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / "honda-monopodial-tree.l");
    DerivationOptions d;
    const Scene scene = interpret(m, applyHomomorphism(m.lsystem, derive(m.lsystem, 12, d)));
    ASSERT_GT(scene.segments.size(), 4000u);
    MeshOptions o;
    o.curveRadius = 0.01;
    const MeshScene s = buildMeshScene(scene, o);
    std::size_t thin = 0;
    for (const Segment& g : scene.segments) thin += g.width / 2 < o.curveRadius;
    EXPECT_EQ(s.curves.size(), thin);
    EXPECT_GT(thin, 0u);
    EXPECT_LT(thin, scene.segments.size());
    for (std::size_t k = 0; k < s.curves.size(); ++k) {
        EXPECT_LT(s.curves[k].radiusB, 0.01f);
        if (s.curves[k].previous != kNoSegment) {
            ASSERT_LT(s.curves[k].previous, k);
            EXPECT_EQ(s.curves[s.curves[k].previous].b, s.curves[k].a);
        }
    }
}

// The tubes are built by several threads into their final places: the mesh must not
// depend on how many.
TEST(MeshScene, TubesAreTheSameForAnyThreadCount) {
    const Model m =
        graftal::testing::loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / "honda-monopodial-tree.l");
    const Scene scene = interpret(m, applyHomomorphism(m.lsystem, derive(m.lsystem, 14)));
    ASSERT_GT(scene.segments.size(), 16000u);
    MeshOptions o;
    o.threads = 1;
    const Mesh one = buildMeshScene(scene, o).mesh;
    for (unsigned threads : {2u, 7u}) {
        o.threads = threads;
        const Mesh many = buildMeshScene(scene, o).mesh;
        EXPECT_EQ(many.positions, one.positions) << threads << " threads";
        EXPECT_EQ(many.normals, one.normals) << threads << " threads";
        EXPECT_EQ(many.indices, one.indices) << threads << " threads";
        EXPECT_EQ(many.triangleColor, one.triangleColor) << threads << " threads";
    }
    // Every index is a vertex, every vertex is used (nothing left unwritten).
    std::vector<bool> used(one.positions.size(), false);
    for (std::uint32_t i : one.indices) {
        ASSERT_LT(i, one.positions.size());
        used[i] = true;
    }
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
    for (const Vec3f& n : one.normals) ASSERT_NEAR(length(d(n)), 1, 1e-4);
}

}  // namespace

namespace {

TEST(MeshScene, BuildingIntoAUsedSceneForgetsTheOldOne) {
    SurfaceLibrary library;
    library.add(squareSurface());
    MeshScene reused = buildMeshScene(handMadeScene(), {}, &library);
    MeshOptions o;
    o.curveRadius = 0.2;
    buildMeshScene(thickThinThick(), o, &library, reused);
    const MeshScene fresh = buildMeshScene(thickThinThick(), o, &library);
    EXPECT_TRUE(reused.prototypes.empty());
    EXPECT_TRUE(reused.placements.empty());
    EXPECT_EQ(reused.curves.size(), 2u);
    EXPECT_EQ(reused.mesh.positions, fresh.mesh.positions);
    EXPECT_EQ(reused.mesh.indices, fresh.mesh.indices);
    EXPECT_EQ(reused.mesh.triangleColor, fresh.mesh.triangleColor);
}

}  // namespace

namespace {

TEST(MeshQuality, NamesAndNumbersGiveTubeSidesAndSurfaceDivisions) {
    const std::optional<MeshResolution> medium = meshResolutionFor("medium");
    ASSERT_TRUE(medium);
    // Medium is what a request holds by default: today's pictures.
    EXPECT_EQ(medium->tubeSides, RenderRequest{}.tubeSides);
    EXPECT_EQ(medium->surfaceDivisions, RenderRequest{}.surfaceDivisions);
    EXPECT_EQ(medium->tubeSides, MeshOptions{}.tubeSides);
    ASSERT_TRUE(meshResolutionFor("low"));
    EXPECT_LT(meshResolutionFor("low")->tubeSides, 8);
    ASSERT_TRUE(meshResolutionFor("high"));
    EXPECT_EQ(meshResolutionFor("high")->tubeSides, 16);
    EXPECT_EQ(meshResolutionFor("high")->surfaceDivisions, 16);
    ASSERT_TRUE(meshResolutionFor("12"));
    EXPECT_EQ(meshResolutionFor("12")->tubeSides, 12);
    EXPECT_EQ(meshResolutionFor("12")->surfaceDivisions, 12);
    for (const char* bad : {"", "ultra", "2", "65", "8x", "-8", "1e1"})
        EXPECT_FALSE(meshResolutionFor(bad)) << bad;
}

}  // namespace
