// GLB files of instanced scenes (MeshScene): prototypes placed with EXT_mesh_gpu_instancing
// or copied, buffers compressed with EXT_meshopt_compression or not. Every file is read back
// as a viewer draws it (tests/glb_reader.hpp: compressed views decoded with meshoptimizer,
// instance transforms applied) and checked by the Khronos validator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "glb_reader.hpp"
#include "gltf_validator.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/output/output.hpp"
#include "output/instance_transform.hpp"
#include "process.hpp"

namespace {

namespace fs = std::filesystem;
using graftal::Affine3f;
using graftal::Bounds;
using graftal::GlbOptions;
using graftal::Mesh;
using graftal::MeshPlacement;
using graftal::MeshScene;
using graftal::Vec3;
using graftal::Vec3f;
using graftal::testing::DrawnTriangle;
using graftal::testing::GlbFile;
using graftal::testing::TempDir;
namespace it = graftal::instance_transform;

// ---------------------------------------------------------------------------------------
// A scene as an instancing builder makes it: stems in the mesh, one leaf prototype (two
// colours, a curved blade) placed many times, rotated and scaled, some mirrored, one
// stretched along an axis and one sheared.

Vec3f rotated(const Vec3f& v, const Vec3f& axis, double degrees) {
    const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    const Vec3 k = toVec3(axis), w = toVec3(v);
    return graftal::toVec3f(c * w + s * cross(k, w) + (dot(k, w) * (1 - c)) * k);
}

Mesh leafPrototype() {
    Mesh leaf;
    // A blade along y, curved in z, 6 x 3 vertices; the tip triangles are a second colour.
    const int along = 6, across = 3;
    for (int i = 0; i < along; ++i)
        for (int j = 0; j < across; ++j) {
            const float y = i * 0.2f,
                        x = (j - 1) * 0.15f * (0.2f + std::sin(3.1f * i / (along - 1)));
            leaf.positions.push_back({x, y, 0.1f * y * y});
            leaf.normals.push_back({0, -0.2f * y, 1});
        }
    for (Vec3f& n : leaf.normals) {
        const float l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        n = {n.x / l, n.y / l, n.z / l};
    }
    for (int i = 0; i + 1 < along; ++i)
        for (int j = 0; j + 1 < across; ++j) {
            const auto v = static_cast<std::uint32_t>(i * across + j);
            const std::uint16_t color = i + 2 == along ? 2 : 1;
            leaf.indices.insert(leaf.indices.end(), {v, v + 1, v + across});
            leaf.indices.insert(leaf.indices.end(), {v + 1, v + across + 1, v + across});
            leaf.triangleColor.insert(leaf.triangleColor.end(), {color, color});
        }
    return leaf;
}

Affine3f frame(const Vec3f& at, double yaw, double pitch, float size) {
    Affine3f a;
    const Vec3f up{0, 1, 0}, side{1, 0, 0};
    for (int k = 0; k < 3; ++k) {
        Vec3f c = rotated(rotated(a.columns[k], side, pitch), up, yaw);
        a.columns[k] = {c.x * size, c.y * size, c.z * size};
    }
    a.columns[3] = at;
    return a;
}

MeshScene leafyScene(int leaves) {
    MeshScene scene;
    graftal::Scene stems;
    graftal::Segment s;
    s.a = {0, 0, 0};
    s.b = {0, 4, 0};
    s.width = 0.2f;
    stems.segments.push_back(s);
    s.a = s.b;
    s.b = {1, 6, 0.5};
    s.previous = 0;
    stems.segments.push_back(s);
    scene.mesh = graftal::buildMesh(stems);
    scene.mesh.palette = graftal::Scene::defaultPalette();
    scene.prototypes.push_back(leafPrototype());
    for (int i = 0; i < leaves; ++i) {
        const float h = 6.0f * i / leaves;
        Affine3f a = frame({0.1f * std::sin(i * 1.0f), h, 0.1f * std::cos(i * 1.0f)}, 137.5 * i,
                           30 + i % 40, 0.5f + 0.01f * (i % 50));
        if (i % 7 == 3) a.columns[0] = {-a.columns[0].x, -a.columns[0].y, -a.columns[0].z};
        scene.placements.push_back({0, a});
    }
    // Stretched along its own length (a scale per axis: still instanced).
    Affine3f stretched = frame({2, 1, 0}, 20, 10, 1);
    stretched.columns[1] = {2 * stretched.columns[1].x, 2 * stretched.columns[1].y,
                            2 * stretched.columns[1].z};
    scene.placements.push_back({0, stretched});
    // Sheared: no TRS form, so copied.
    Affine3f sheared = frame({-2, 1, 0}, 0, 0, 1);
    sheared.columns[1] = {0.5f, 1, 0};
    scene.placements.push_back({0, sheared});
    return scene;
}

// ---------------------------------------------------------------------------------------
// What to compare: triangles per material, bounds, the sum of their corners and of their
// area vectors (which flips sign with the winding).

struct Summary {
    std::map<std::string, std::size_t> trianglesPerMaterial;
    Bounds bounds;
    Vec3 cornerSum{0, 0, 0}, areaSum{0, 0, 0};
};

Summary summarise(const std::vector<DrawnTriangle>& triangles) {
    Summary s;
    for (const DrawnTriangle& t : triangles) {
        ++s.trianglesPerMaterial[t.material];
        for (const Vec3& c : t.corners) {
            s.bounds.extend(c);
            s.cornerSum = s.cornerSum + c;
        }
        s.areaSum = s.areaSum + cross(t.corners[1] - t.corners[0], t.corners[2] - t.corners[0]);
    }
    return s;
}

Summary summarise(const Mesh& m) {
    std::vector<DrawnTriangle> triangles;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        DrawnTriangle d;
        d.material = "color" + std::to_string(m.triangleColor[t] % m.palette.size());
        for (int k = 0; k < 3; ++k) d.corners[k] = toVec3(m.positions[m.indices[3 * t + k]]);
        triangles.push_back(d);
    }
    return summarise(triangles);
}

void expectNear(const Vec3& a, const Vec3& b, double tolerance, const char* what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
    EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

// The file draws what the scene draws: the same triangles per colour, within float
// rounding of the instance transforms, facing the same way.
void expectDrawsScene(const GlbFile& file, const MeshScene& scene, double tolerance = 1e-4) {
    const Summary got = summarise(graftal::testing::drawnTriangles(file));
    const Summary want = summarise(scene.flattened());
    EXPECT_EQ(got.trianglesPerMaterial, want.trianglesPerMaterial);
    std::size_t drawn = 0;
    for (const auto& [name, n] : got.trianglesPerMaterial) drawn += n;
    EXPECT_EQ(drawn, scene.triangleCount());
    const Bounds b = scene.bounds();
    expectNear(got.bounds.min, b.min, tolerance, "bounds min");
    expectNear(got.bounds.max, b.max, tolerance, "bounds max");
    const double n = 3.0 * static_cast<double>(scene.triangleCount());
    expectNear((1 / n) * got.cornerSum, (1 / n) * want.cornerSum, tolerance, "mean corner");
    expectNear(got.areaSum, want.areaSum, 1e-3 * std::max(1.0, length(want.areaSum)),
               "area vector");
}

// Each POSITION accessor's min and max are those of its values, as decoded.
void expectPositionBounds(const GlbFile& file) {
    for (const auto& mesh : file.json["meshes"])
        for (const auto& p : mesh["primitives"]) {
            const int accessor = p["attributes"]["POSITION"];
            const std::vector<double> v = file.values(accessor);
            ASSERT_FALSE(v.empty());
            for (int k = 0; k < 3; ++k) {
                double low = HUGE_VAL, high = -HUGE_VAL;
                for (std::size_t i = k; i < v.size(); i += 3) {
                    low = std::min(low, v[i]);
                    high = std::max(high, v[i]);
                }
                EXPECT_EQ(file.json["accessors"][accessor]["min"][k].get<double>(), low);
                EXPECT_EQ(file.json["accessors"][accessor]["max"][k].get<double>(), high);
            }
        }
}

std::vector<std::string> extensionList(const GlbFile& f, const char* key) {
    return f.json.contains(key) ? f.json[key].get<std::vector<std::string>>()
                                : std::vector<std::string>{};
}

std::size_t instancedNodes(const GlbFile& f) {
    std::size_t n = 0;
    for (const auto& node : f.json["nodes"])
        if (node.contains("extensions") && node["extensions"].contains("EXT_mesh_gpu_instancing"))
            ++n;
    return n;
}

// ---------------------------------------------------------------------------------------
// The transforms

TEST(InstanceTransform, RotationTimesAxisScaleRoundTrips) {
    for (int i = 0; i < 200; ++i) {
        Affine3f a = frame({float(i), -2.0f * i, 0.5f}, 37.0 * i, 11.0 * i - 90, 0.1f + 0.05f * i);
        a.columns[2] = {3 * a.columns[2].x, 3 * a.columns[2].y, 3 * a.columns[2].z};
        const auto trs = it::decompose(a);
        ASSERT_TRUE(trs) << i;
        EXPECT_GE(trs->rotation[3], 0);
        const Affine3f b = it::compose(*trs);
        for (int c = 0; c < 4; ++c) {
            const double size = length(toVec3(a.columns[std::min(c, 2)])) + (c == 3 ? 2.0 * i : 0);
            expectNear(toVec3(b.columns[c]), toVec3(a.columns[c]), 1e-6 * size + 1e-7, "column");
        }
    }
}

TEST(InstanceTransform, ShearMirrorAndZeroHaveNoTrsForm) {
    Affine3f sheared;
    sheared.columns[1] = {0.3f, 1, 0};
    EXPECT_FALSE(it::decompose(sheared));
    Affine3f mirrored;
    mirrored.columns[0] = {-1, 0, 0};
    EXPECT_FALSE(it::decompose(mirrored));
    Affine3f flat;
    flat.columns[2] = {0, 0, 0};
    EXPECT_FALSE(it::decompose(flat));
    EXPECT_TRUE(it::decompose(Affine3f{}));
}

TEST(InstanceTransform, MirroredPrototypeDrawsTheMirroredPlacement) {
    const Mesh leaf = leafPrototype();
    Affine3f a = frame({1, 2, 3}, 40, 25, 0.7f);
    a.columns[1] = {-a.columns[1].x, -a.columns[1].y, -a.columns[1].z};
    ASSERT_LT(a.determinant(), 0);
    const Affine3f b = it::withMirroredPrototype(a);
    EXPECT_GT(b.determinant(), 0);
    const Mesh mirrored = it::mirroredPrototype(leaf);
    for (std::size_t v = 0; v < leaf.positions.size(); ++v) {
        expectNear(toVec3(b.point(mirrored.positions[v])), toVec3(a.point(leaf.positions[v])), 1e-6,
                   "point");
        expectNear(toVec3(b.normal(mirrored.normals[v])), toVec3(a.normal(leaf.normals[v])), 1e-6,
                   "normal");
    }
    // Rewound, so that the geometric normal still agrees with the vertex normals.
    for (std::size_t t = 0; t < mirrored.indices.size(); t += 3) {
        const Vec3 p0 = toVec3(b.point(mirrored.positions[mirrored.indices[t]]));
        const Vec3 p1 = toVec3(b.point(mirrored.positions[mirrored.indices[t + 1]]));
        const Vec3 p2 = toVec3(b.point(mirrored.positions[mirrored.indices[t + 2]]));
        EXPECT_GT(
            dot(cross(p1 - p0, p2 - p0), toVec3(b.normal(mirrored.normals[mirrored.indices[t]]))),
            0);
    }
}

// ---------------------------------------------------------------------------------------
// Files

TEST(GlbWriterInstancing, InstancedAndFlattenedDrawTheSameAndAreValid) {
    const MeshScene scene = leafyScene(300);
    TempDir dir;
    const fs::path instanced = dir.path() / "instanced.glb", flat = dir.path() / "flat.glb";
    graftal::writeGlb(scene, instanced);
    graftal::writeGlb(scene, flat, GlbOptions{.instancing = false});

    const GlbFile i = GlbFile::read(instanced);
    EXPECT_EQ(extensionList(i, "extensionsUsed"),
              std::vector<std::string>{"EXT_mesh_gpu_instancing"});
    EXPECT_EQ(extensionList(i, "extensionsRequired"),
              std::vector<std::string>{"EXT_mesh_gpu_instancing"});
    // The leaf, the mirrored leaf; the sheared placement is a copy in a mesh of its own.
    EXPECT_EQ(instancedNodes(i), 2u);
    EXPECT_EQ(i.json["meshes"].size(), 4u);
    for (const auto& node : i.json["nodes"]) {
        if (!node.contains("extensions")) continue;
        for (const graftal::testing::InstanceMap& m : graftal::testing::instancesOf(i, node))
            EXPECT_GT(m.determinant(), 0) << "an instance mirrors: its triangles would face in";
    }
    expectDrawsScene(i, scene);
    expectPositionBounds(i);

    const GlbFile f = GlbFile::read(flat);
    EXPECT_FALSE(f.json.contains("extensionsUsed"));
    EXPECT_EQ(instancedNodes(f), 0u);
    expectDrawsScene(f, scene);
    expectPositionBounds(f);

    EXPECT_VALID_GLTF(instanced);
    EXPECT_VALID_GLTF(flat);
}

TEST(GlbWriterInstancing, CompressedFilesDecodeToTheSamePositions) {
    const MeshScene scene = leafyScene(300);
    TempDir dir;
    for (bool instancing : {true, false}) {
        SCOPED_TRACE(instancing ? "instanced" : "flattened");
        const fs::path plainPath = dir.path() / "plain.glb", packedPath = dir.path() / "packed.glb";
        graftal::writeGlb(scene, plainPath, {.instancing = instancing, .compression = false});
        graftal::writeGlb(scene, packedPath, {.instancing = instancing, .compression = true});
        const GlbFile plain = GlbFile::read(plainPath), packed = GlbFile::read(packedPath);
        const auto required = extensionList(packed, "extensionsRequired");
        for (const char* e : {"EXT_meshopt_compression", "KHR_mesh_quantization"})
            EXPECT_NE(std::find(required.begin(), required.end(), e), required.end()) << e;
        EXPECT_EQ(extensionList(packed, "extensionsUsed"), required);
        // The placeholder buffer holds no data: the file carries only the encoded bytes.
        ASSERT_EQ(packed.json["buffers"].size(), 2u);
        EXPECT_FALSE(packed.json["buffers"][1].contains("uri"));
        EXPECT_TRUE(packed.json["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"]);
        // Copies compress well. A few hundred random rotations do not, and are kept as they
        // are (without the extension) rather than grow; in a file this small the extension's
        // JSON outweighs what the codec saves, so the binary chunks are compared.
        EXPECT_LT(packed.binary.size(), instancing ? plain.binary.size() : plain.binary.size() / 2);
        std::size_t compressedViews = 0;
        for (const auto& view : packed.json["bufferViews"]) {
            const bool compressed = view.contains("extensions");
            compressedViews += compressed;
            EXPECT_EQ(view["buffer"], compressed ? 1 : 0);
        }
        EXPECT_GT(compressedViews, packed.json["bufferViews"].size() / 2);

        // Accessor by accessor (both files list them in the same order): indices and
        // instance transforms decode exactly, positions within their 16-bit mantissa (15 bits
        // and a sign, scaled to the largest coordinate, or to 1 when a coordinate is 0: the
        // exponent meshoptimizer 0.18 takes for a zero),
        // normals within 8-bit octahedral precision.
        ASSERT_EQ(packed.json["accessors"].size(), plain.json["accessors"].size());
        std::set<int> positions, normals, indices;
        for (const auto& mesh : plain.json["meshes"])
            for (const auto& p : mesh["primitives"]) {
                positions.insert(p["attributes"]["POSITION"].get<int>());
                normals.insert(p["attributes"]["NORMAL"].get<int>());
                indices.insert(p["indices"].get<int>());
            }
        for (int a = 0; a < static_cast<int>(plain.json["accessors"].size()); ++a) {
            const std::vector<double> want = plain.values(a), got = packed.values(a);
            ASSERT_EQ(got.size(), want.size()) << "accessor " << a;
            if (normals.count(a)) {
                for (std::size_t i = 0; i < want.size(); ++i)
                    ASSERT_NEAR(got[i], want[i], 0.02) << "normal accessor " << a << " value " << i;
            } else if (positions.count(a)) {
                for (std::size_t v = 0; v < want.size(); v += 3) {
                    const double largest = std::max(
                        {1.0, std::abs(want[v]), std::abs(want[v + 1]), std::abs(want[v + 2])});
                    for (int k = 0; k < 3; ++k)
                        ASSERT_NEAR(got[v + k], want[v + k], largest * std::ldexp(1.0, -14))
                            << "position accessor " << a << " vertex " << v / 3;
                }
            } else if (indices.count(a)) {
                // The triangle codec may start a triangle at another corner (same winding).
                for (std::size_t t = 0; t < want.size(); t += 3) {
                    const bool same =
                        std::equal(want.begin() + t, want.begin() + t + 3, got.begin() + t) ||
                        (got[t] == want[t + 1] && got[t + 1] == want[t + 2] &&
                         got[t + 2] == want[t]) ||
                        (got[t] == want[t + 2] && got[t + 1] == want[t] &&
                         got[t + 2] == want[t + 1]);
                    ASSERT_TRUE(same) << "index accessor " << a << " triangle " << t / 3;
                }
            } else {
                EXPECT_EQ(got, want) << "accessor " << a;
            }
        }
        expectDrawsScene(packed, scene, 1e-3);
        expectPositionBounds(packed);
        EXPECT_VALID_GLTF(packedPath);
    }
}

TEST(GlbWriterInstancing, InstancedFileIsSmallerByTheNumberOfCopies) {
    // 2,000 leaves of 20 triangles: copies store 2,000 leaves' vertices, instancing one leaf
    // and 40 bytes of transform per leaf.
    const MeshScene scene = leafyScene(2000);
    TempDir dir;
    const fs::path instanced = dir.path() / "instanced.glb", flat = dir.path() / "flat.glb",
                   packed = dir.path() / "packed.glb";
    graftal::writeGlb(scene, instanced);
    graftal::writeGlb(scene, flat, GlbOptions{.instancing = false});
    graftal::writeGlb(scene, packed, GlbOptions{.instancing = true, .compression = true});
    const auto iSize = fs::file_size(instanced), fSize = fs::file_size(flat),
               pSize = fs::file_size(packed);
    std::cout << "flattened " << fSize << " bytes, instanced " << iSize << ", compressed " << pSize
              << '\n';
    EXPECT_GT(fSize, 5 * iSize);
    EXPECT_LT(pSize, iSize);
    EXPECT_VALID_GLTF(instanced);
    EXPECT_VALID_GLTF(packed);
}

TEST(GlbWriterInstancing, SceneWithoutPlacementsIsThePlainMesh) {
    MeshScene scene = leafyScene(0);
    scene.placements.clear();
    TempDir dir;
    graftal::writeGlb(scene, dir.path() / "scene.glb");
    graftal::writeGlb(scene.mesh, dir.path() / "mesh.glb");
    EXPECT_EQ(graftal::testing::readFile(dir.path() / "scene.glb"),
              graftal::testing::readFile(dir.path() / "mesh.glb"));
    const GlbFile f = GlbFile::read(dir.path() / "scene.glb");
    EXPECT_FALSE(f.json.contains("extensionsUsed"));
    expectDrawsScene(f, scene);
}

TEST(GlbWriterInstancing, EmptyCompressedSceneIsValid) {
    MeshScene scene;
    scene.mesh.palette = graftal::Scene::defaultPalette();
    TempDir dir;
    graftal::writeGlb(scene, dir.path() / "empty.glb", {.instancing = true, .compression = true});
    const GlbFile f = GlbFile::read(dir.path() / "empty.glb");
    EXPECT_FALSE(f.json.contains("buffers"));
    EXPECT_FALSE(f.json.contains("extensionsRequired"));
    EXPECT_VALID_GLTF(dir.path() / "empty.glb");
}

TEST(GlbWriterInstancing, PlacementOfAMissingPrototypeIsRefused) {
    MeshScene scene = leafyScene(3);
    scene.placements.push_back({7, Affine3f{}});
    TempDir dir;
    EXPECT_THROW(graftal::writeGlb(scene, dir.path() / "bad.glb"), graftal::Error);
    EXPECT_FALSE(fs::exists(dir.path() / "bad.glb"));
}

}  // namespace

namespace {

// ---------------------------------------------------------------------------------------
// graftal render

TEST(GlbWriterInstancing, RenderCommandCompressesAndCopiesOnRequest) {
    TempDir dir;
    const std::string model = std::string(GRAFTAL_EXAMPLES_DIR) + "/fig3.9-lychnis-3d.l";
    const fs::path plain = dir.path() / "plain.glb", packed = dir.path() / "packed.glb",
                   copies = dir.path() / "copies.glb";
    for (const auto& [path, flags] :
         {std::pair{plain, std::string()}, std::pair{packed, std::string(" --compress")},
          std::pair{copies, std::string(" --no-instancing")}}) {
        const auto r = graftal::testing::runGraftal("render '" + model + "' -o '" + path.string() +
                                                    "'" + flags);
        ASSERT_EQ(r.status, 0) << r.err;
    }
    const GlbFile p = GlbFile::read(plain), c = GlbFile::read(packed), n = GlbFile::read(copies);
    EXPECT_FALSE(p.uses("EXT_meshopt_compression"));
    EXPECT_TRUE(c.uses("EXT_meshopt_compression"));
    EXPECT_EQ(instancedNodes(n), 0u);
    EXPECT_LT(c.fileSize, p.fileSize / 2);
    EXPECT_EQ(graftal::testing::drawnTriangles(c).size(),
              graftal::testing::drawnTriangles(p).size());
    EXPECT_EQ(graftal::testing::drawnTriangles(n).size(),
              graftal::testing::drawnTriangles(p).size());
    EXPECT_VALID_GLTF(plain);
    EXPECT_VALID_GLTF(packed);
    EXPECT_VALID_GLTF(copies);
}

}  // namespace
