// writeObj, writePly, writeGlb: every file is read back (OBJ and MTL as text, PLY's header
// and binary body, GLB through tinygltf) and every GLB is checked by the official Khronos
// validator (tests/tools/validate_gltf.mjs, which `make test-tools` sets up).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "gltf_validator.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/graftal.hpp"
#include "process.hpp"

namespace {

namespace fs = std::filesystem;
using graftal::Error;
using graftal::Mesh;
using graftal::Rgb;
using graftal::Scene;
using graftal::Segment;
using graftal::Vec3;
using graftal::Vec3f;
using graftal::testing::kToolsDir;
using graftal::testing::readFile;
using graftal::testing::TempDir;
using graftal::testing::validate;
using graftal::testing::Validation;
using graftal::testing::validatorInstalled;

// ---------------------------------------------------------------------------------------
// A small plant, built the way a 3D turtle would: bending axes with shared joints, side
// branches, leaves as polygons, predefined surfaces at the tips, several colours (one of
// them past the end of the palette, which wraps around).

// Rodrigues: v rotated about the unit axis k by `degrees`.
Vec3 rotate(const Vec3& v, const Vec3& k, double degrees) {
    const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    return c * v + s * cross(k, v) + (dot(k, v) * (1 - c)) * k;
}

struct Turtle {
    Vec3 p{0, 0, 0}, h{0, 1, 0}, l{-1, 0, 0}, u{0, 0, 1};
    void pitch(double deg) {
        h = rotate(h, l, deg);
        u = rotate(u, l, deg);
    }
    void roll(double deg) {
        l = rotate(l, h, deg);
        u = rotate(u, h, deg);
    }
};

void grow(Scene& scene, Turtle t, int depth, float width) {
    std::uint32_t previous = graftal::kNoSegment;
    for (int i = 0; i < 4; ++i) {
        const Vec3 q = t.p + (0.4 * (depth + 1)) * t.h;
        Segment s;
        s.a = t.p;
        s.b = q;
        s.width = width;
        s.previous = previous;
        s.color = depth >= 2 ? 5 : 0;
        s.up = t.u;
        scene.segments.push_back(s);
        previous = static_cast<std::uint32_t>(scene.segments.size() - 1);
        t.p = q;
        t.pitch(12);
        t.roll(35);
        width *= 0.85f;
        if (depth > 0 && i % 2 == 1) {
            Turtle branch = t;
            branch.pitch(50);
            grow(scene, branch, depth - 1, width * 0.6f);
        }
    }
    if (depth > 0) return;
    // A leaf in the plane of H and L, and a surface just beyond it.
    std::vector<Vec3> leaf;
    for (auto [a, b] : {std::pair{0.0, 0.0},
                        {0.3, 0.15},
                        {0.5, 0.05},
                        {0.8, 0.12},
                        {1.0, 0.0},
                        {0.8, -0.12},
                        {0.5, -0.05},
                        {0.3, -0.15}})
        leaf.push_back((t.p + (0.5 * a) * t.h + (0.5 * b) * t.l));
    scene.addPolygon(leaf, scene.polygonCount() % 2 ? 1 : 17);
    graftal::SurfaceInstance surface;
    surface.surface = 0;
    surface.origin = t.p;
    surface.heading = t.h;
    surface.left = t.l;
    surface.up = t.u;
    surface.scale = 0.3;
    surface.color = 3;
    scene.surfaces.push_back(surface);
}

const graftal::SurfaceLibrary& library() {
    static const graftal::SurfaceLibrary builtin = graftal::SurfaceLibrary::builtin();
    return builtin;
}

Scene samplePlant() {
    Scene scene;
    scene.is3D = true;
    scene.surfaceNames = {library().names().front()};
    grow(scene, Turtle{}, 3, 0.3f);
    return scene;
}

Mesh samplePlantMesh() {
    graftal::MeshOptions o;
    o.surfaceDivisions = 4;
    return graftal::buildMesh(samplePlant(), o, &library());
}

// ---------------------------------------------------------------------------------------
// What a reader of the files should find: triangles grouped by palette entry, in palette
// order, in mesh order within a colour.

std::uint16_t paletteIndex(const Mesh& m, std::uint16_t c) {
    return static_cast<std::uint16_t>(c % m.palette.size());
}

std::map<std::uint16_t, std::vector<std::size_t>> trianglesByColor(const Mesh& m) {
    std::map<std::uint16_t, std::vector<std::size_t>> groups;
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        groups[paletteIndex(m, m.triangleColor[t])].push_back(t);
    return groups;
}

// Vertices once per colour that uses them.
std::size_t verticesPerColor(const Mesh& m) {
    std::size_t n = 0;
    for (const auto& [color, triangles] : trianglesByColor(m)) {
        std::set<std::uint32_t> used;
        for (std::size_t t : triangles)
            for (int k = 0; k < 3; ++k) used.insert(m.indices[3 * t + k]);
        n += used.size();
    }
    return n;
}

// A triangle's corners rotated to start at the smallest, so that two listings of the same
// triangle with the same winding compare equal.
std::array<float, 9> canonicalTriangle(const std::array<Vec3f, 3>& c) {
    auto key = [](const Vec3f& v) { return std::tuple(v.x, v.y, v.z); };
    int first = 0;
    for (int k = 1; k < 3; ++k)
        if (key(c[k]) < key(c[first])) first = k;
    std::array<float, 9> out;
    for (int k = 0; k < 3; ++k) {
        const Vec3f& v = c[(first + k) % 3];
        out[3 * k] = v.x;
        out[3 * k + 1] = v.y;
        out[3 * k + 2] = v.z;
    }
    return out;
}

double linear(float srgb) {
    return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4);
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

bool startsWith(const std::string& s, const std::string& prefix) {
    return s.rfind(prefix, 0) == 0;
}

std::vector<fs::path> listing(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename());
    std::sort(out.begin(), out.end());
    return out;
}

// ---------------------------------------------------------------------------------------
// OBJ

TEST(ObjWriter, RoundTrip) {
    const Mesh m = samplePlantMesh();
    ASSERT_GT(m.triangleCount(), 1000u);
    TempDir dir;
    graftal::writeObj(m, dir.path() / "plant.obj");
    EXPECT_EQ(listing(dir.path()), (std::vector<fs::path>{"plant.mtl", "plant.obj"}));

    const auto groups = trianglesByColor(m);
    std::size_t v = 0, vn = 0, f = 0;
    std::vector<std::string> materials;
    std::map<std::string, std::size_t> facesPerMaterial;
    std::string mtllib;
    Vec3f first{};
    for (const std::string& line : lines(readFile(dir.path() / "plant.obj"))) {
        std::istringstream in(line);
        std::string tag;
        in >> tag;
        if (tag == "v") {
            if (v++ == 0) in >> first.x >> first.y >> first.z;
        } else if (tag == "vn") {
            ++vn;
        } else if (tag == "f") {
            ++f;
            ASSERT_FALSE(materials.empty()) << "a face before any usemtl";
            ++facesPerMaterial[materials.back()];
            for (int k = 0; k < 3; ++k) {
                std::string corner;
                in >> corner;
                const auto slashes = corner.find("//");
                ASSERT_NE(slashes, std::string::npos) << line;
                const long a = std::stol(corner.substr(0, slashes));
                const long b = std::stol(corner.substr(slashes + 2));
                EXPECT_EQ(a, b);
                EXPECT_GE(a, 1);
                EXPECT_LE(a, static_cast<long>(m.positions.size()));
            }
        } else if (tag == "usemtl") {
            std::string name;
            in >> name;
            materials.push_back(name);
        } else if (tag == "mtllib") {
            in >> mtllib;
        }
    }
    EXPECT_EQ(mtllib, "plant.mtl");
    EXPECT_EQ(v, m.positions.size());
    EXPECT_EQ(vn, m.normals.size());
    EXPECT_EQ(f, m.triangleCount());
    EXPECT_EQ(first, m.positions[0]);  // shortest round-trip text: exactly the same floats
    ASSERT_EQ(materials.size(), groups.size());
    std::size_t k = 0;
    for (const auto& [color, triangles] : groups) {
        EXPECT_EQ(materials[k], "color" + std::to_string(color));
        EXPECT_EQ(facesPerMaterial[materials[k]], triangles.size());
        ++k;
    }

    // The .mtl: one material per colour, with the palette's colour.
    std::map<std::string, Rgb> kd;
    std::string current;
    for (const std::string& line : lines(readFile(dir.path() / "plant.mtl"))) {
        std::istringstream in(line);
        std::string tag;
        in >> tag;
        if (tag == "newmtl") {
            in >> current;
            EXPECT_EQ(kd.count(current), 0u) << "material " << current << " defined twice";
            kd[current] = {};
        } else if (tag == "Kd") {
            in >> kd[current].r >> kd[current].g >> kd[current].b;
        }
    }
    EXPECT_EQ(kd.size(), groups.size());
    for (const auto& [color, triangles] : groups)
        EXPECT_EQ(kd["color" + std::to_string(color)], m.palette[color]) << color;
}

// ---------------------------------------------------------------------------------------
// PLY

struct PlyFile {
    std::vector<std::string> header;
    std::size_t vertices = 0, faces = 0;
    std::string body;
};

PlyFile readPly(const fs::path& path) {
    const std::string bytes = readFile(path);
    PlyFile ply;
    std::size_t at = 0;
    for (;;) {
        const std::size_t end = bytes.find('\n', at);
        if (end == std::string::npos) break;
        ply.header.push_back(bytes.substr(at, end - at));
        at = end + 1;
        if (ply.header.back() == "end_header") break;
    }
    for (const std::string& line : ply.header) {
        if (startsWith(line, "element vertex ")) ply.vertices = std::stoul(line.substr(15));
        if (startsWith(line, "element face ")) ply.faces = std::stoul(line.substr(13));
    }
    ply.body = bytes.substr(at);
    return ply;
}

template <class T>
T readLittle(const std::string& body, std::size_t at) {
    static_assert(std::endian::native == std::endian::little,
                  "the test reads on a little-endian host");
    T v;
    std::memcpy(&v, body.data() + at, sizeof v);
    return v;
}

TEST(PlyWriter, RoundTrip) {
    const Mesh m = samplePlantMesh();
    TempDir dir;
    graftal::writePly(m, dir.path() / "plant.ply");
    EXPECT_EQ(listing(dir.path()), std::vector<fs::path>{"plant.ply"});
    const PlyFile ply = readPly(dir.path() / "plant.ply");

    const std::vector<std::string> expectedHeader = {
        "ply",
        "format binary_little_endian 1.0",
        "comment graftal mesh",
        "element vertex " + std::to_string(ply.vertices),
        "property float x",
        "property float y",
        "property float z",
        "property float nx",
        "property float ny",
        "property float nz",
        "property uchar red",
        "property uchar green",
        "property uchar blue",
        "element face " + std::to_string(ply.faces),
        "property list uchar int vertex_indices",
        "end_header"};
    EXPECT_EQ(ply.header, expectedHeader);
    EXPECT_EQ(ply.vertices, verticesPerColor(m));
    EXPECT_EQ(ply.faces, m.triangleCount());
    constexpr std::size_t kVertexBytes = 6 * 4 + 3, kFaceBytes = 1 + 3 * 4;
    ASSERT_EQ(ply.body.size(), ply.vertices * kVertexBytes + ply.faces * kFaceBytes);

    // Face by face, in colour order, the same corners in the same order (so the same
    // winding), with the colour of the triangle on its vertices.
    std::size_t face = 0;
    for (const auto& [color, triangles] : trianglesByColor(m)) {
        const Rgb c = m.palette[color];
        for (std::size_t t : triangles) {
            const std::size_t at = ply.vertices * kVertexBytes + face * kFaceBytes;
            ASSERT_EQ(static_cast<unsigned char>(ply.body[at]), 3u);
            for (int k = 0; k < 3; ++k) {
                const auto v = readLittle<std::int32_t>(ply.body, at + 1 + 4 * k);
                ASSERT_GE(v, 0);
                ASSERT_LT(static_cast<std::size_t>(v), ply.vertices);
                const std::size_t vat = static_cast<std::size_t>(v) * kVertexBytes;
                const Vec3f p{readLittle<float>(ply.body, vat),
                              readLittle<float>(ply.body, vat + 4),
                              readLittle<float>(ply.body, vat + 8)};
                const Vec3f n{readLittle<float>(ply.body, vat + 12),
                              readLittle<float>(ply.body, vat + 16),
                              readLittle<float>(ply.body, vat + 20)};
                EXPECT_EQ(p, m.positions[m.indices[3 * t + k]]);
                EXPECT_EQ(n, m.normals[m.indices[3 * t + k]]);
                EXPECT_EQ(static_cast<unsigned char>(ply.body[vat + 24]), std::lround(c.r * 255));
                EXPECT_EQ(static_cast<unsigned char>(ply.body[vat + 25]), std::lround(c.g * 255));
                EXPECT_EQ(static_cast<unsigned char>(ply.body[vat + 26]), std::lround(c.b * 255));
            }
            ++face;
        }
        if (HasFailure()) break;
    }
    // The first vertex is the first corner of the first triangle of the first colour.
    const auto groups = trianglesByColor(m);
    EXPECT_EQ((Vec3f{readLittle<float>(ply.body, 0), readLittle<float>(ply.body, 4),
                     readLittle<float>(ply.body, 8)}),
              m.positions[m.indices[3 * groups.begin()->second.front()]]);
}

TEST(PlyWriter, VertexSharedByTwoColoursIsWrittenForEach) {
    // One axis, two colours: the joint ring belongs to both.
    Scene scene;
    Segment s;
    s.a = {0, 0, 0};
    s.b = {0, 1, 0};
    s.width = 0.2f;
    s.color = 1;
    scene.segments.push_back(s);
    s.a = s.b;
    s.b = {0, 2, 0};
    s.color = 3;
    s.previous = 0;
    scene.segments.push_back(s);
    const Mesh m = graftal::buildMesh(scene);
    ASSERT_EQ(m.positions.size(), 3u * 8 + 2);
    TempDir dir;
    graftal::writePly(m, dir.path() / "two.ply");
    const PlyFile ply = readPly(dir.path() / "two.ply");
    EXPECT_EQ(ply.vertices, m.positions.size() + 8);
    EXPECT_EQ(ply.faces, m.triangleCount());
}

// ---------------------------------------------------------------------------------------
// glTF

tinygltf::Model loadGlb(const fs::path& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = loader.LoadBinaryFromFile(&model, &err, &warn, path.string());
    EXPECT_TRUE(ok) << err;
    EXPECT_EQ(err, "");
    EXPECT_EQ(warn, "");
    return model;
}

TEST(GlbWriter, RoundTripAndValidator) {
    const Mesh m = samplePlantMesh();
    TempDir dir;
    const fs::path path = dir.path() / "plant.glb";
    graftal::writeGlb(m, path);
    EXPECT_EQ(listing(dir.path()), std::vector<fs::path>{"plant.glb"});
    EXPECT_EQ(readFile(path).substr(0, 4), "glTF");

    const tinygltf::Model model = loadGlb(path);
    const auto groups = trianglesByColor(m);
    ASSERT_EQ(model.meshes.size(), 1u);
    ASSERT_EQ(model.meshes[0].primitives.size(), groups.size());
    ASSERT_EQ(model.materials.size(), groups.size());
    ASSERT_EQ(model.scenes.size(), 1u);
    ASSERT_EQ(model.scenes[0].nodes, std::vector<int>{0});
    EXPECT_EQ(model.nodes[0].mesh, 0);
    std::size_t vertices = 0, indices = 0;
    auto group = groups.begin();
    for (const tinygltf::Primitive& p : model.meshes[0].primitives) {
        EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
        const tinygltf::Accessor& position = model.accessors.at(p.attributes.at("POSITION"));
        const tinygltf::Accessor& normal = model.accessors.at(p.attributes.at("NORMAL"));
        const tinygltf::Accessor& index = model.accessors.at(p.indices);
        EXPECT_EQ(position.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
        EXPECT_EQ(position.type, TINYGLTF_TYPE_VEC3);
        EXPECT_EQ(position.minValues.size(), 3u);
        EXPECT_EQ(position.maxValues.size(), 3u);
        EXPECT_EQ(normal.count, position.count);
        // 16-bit indices while they reach every vertex (65535 is the restart value).
        EXPECT_EQ(index.componentType, position.count < 65535
                                           ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                           : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
        EXPECT_EQ(index.count, 3 * group->second.size());
        vertices += position.count;
        indices += index.count;

        const tinygltf::Material& material = model.materials.at(p.material);
        const Rgb c = m.palette[group->first];
        EXPECT_EQ(material.name, "color" + std::to_string(group->first));
        const std::vector<double>& base = material.pbrMetallicRoughness.baseColorFactor;
        ASSERT_EQ(base.size(), 4u);
        EXPECT_NEAR(base[0], linear(c.r), 1e-6);
        EXPECT_NEAR(base[1], linear(c.g), 1e-6);
        EXPECT_NEAR(base[2], linear(c.b), 1e-6);
        EXPECT_EQ(base[3], 1);
        EXPECT_EQ(material.pbrMetallicRoughness.metallicFactor, 0);
        EXPECT_NEAR(material.pbrMetallicRoughness.roughnessFactor, 0.8, 1e-9);
        EXPECT_TRUE(material.doubleSided);
        ++group;
    }
    EXPECT_EQ(vertices, verticesPerColor(m));
    EXPECT_EQ(indices, 3 * m.triangleCount());

    // Each primitive holds its colour's triangles, reordered for the vertex cache: the same
    // corners in the same turn (so the same winding), in another order.
    group = groups.begin();
    for (const tinygltf::Primitive& p : model.meshes[0].primitives) {
        std::multiset<std::array<float, 9>> written, expected;
        const tinygltf::Accessor& ia = model.accessors[p.indices];
        const tinygltf::BufferView& iv = model.bufferViews[ia.bufferView];
        const tinygltf::Accessor& pa = model.accessors[p.attributes.at("POSITION")];
        const tinygltf::BufferView& pv = model.bufferViews[pa.bufferView];
        const unsigned char* bytes = model.buffers[0].data.data();
        const std::size_t indexSize =
            ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2 : 4;
        for (std::size_t t = 0; t < ia.count / 3; ++t) {
            std::array<Vec3f, 3> corner;
            for (std::size_t k = 0; k < 3; ++k) {
                std::uint32_t v = 0;
                std::memcpy(&v, bytes + iv.byteOffset + ia.byteOffset + indexSize * (3 * t + k),
                            indexSize);
                std::memcpy(&corner[k], bytes + pv.byteOffset + pa.byteOffset + 12 * v, 12);
            }
            written.insert(canonicalTriangle(corner));
        }
        for (std::size_t t : group->second)
            expected.insert(
                canonicalTriangle({m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
                                   m.positions[m.indices[3 * t + 2]]}));
        EXPECT_EQ(written, expected) << "colour " << group->first;
        ++group;
    }

    EXPECT_VALID_GLTF(path);
}

TEST(GlbWriter, ValidatorRejectsABrokenFile) {
    // The validator check is only worth something if it can fail.
    ASSERT_TRUE(validatorInstalled())
        << "the glTF validator is not installed in " << kToolsDir / "node_modules"
        << ": run `make test-tools` (`make test` installs it)";
    TempDir dir;
    const fs::path path = dir.path() / "plant.glb";
    graftal::writeGlb(samplePlantMesh(), path);
    std::string bytes = readFile(path);
    bytes[12 + 8 + 2] = '#';  // inside the JSON chunk
    dir.write("broken.glb", bytes);
    const Validation v = validate(dir.path() / "broken.glb");
    EXPECT_EQ(v.status, 1) << v.output;
    EXPECT_GT(v.report.value("numErrors", 0), 0) << v.output;
}

// ---------------------------------------------------------------------------------------
// All three

TEST(MeshWriters, EmptyMeshGivesValidEmptyFiles) {
    Mesh m;
    m.palette = Scene::defaultPalette();
    TempDir dir;
    graftal::writeObj(m, dir.path() / "empty.obj");
    graftal::writePly(m, dir.path() / "empty.ply");
    graftal::writeGlb(m, dir.path() / "empty.glb");
    EXPECT_EQ(readPly(dir.path() / "empty.ply").vertices, 0u);
    EXPECT_EQ(readPly(dir.path() / "empty.ply").body, "");
    EXPECT_EQ(loadGlb(dir.path() / "empty.glb").meshes.size(), 0u);
    EXPECT_VALID_GLTF(dir.path() / "empty.glb");
}

TEST(MeshWriters, SingleTubeGlbIsValid) {
    Scene scene;
    Segment s;
    s.a = {0, 0, 0};
    s.b = {0, 1, 0};
    s.width = 0.1f;
    scene.segments = {s};
    TempDir dir;
    graftal::writeGlb(graftal::buildMesh(scene), dir.path() / "tube.glb");
    EXPECT_VALID_GLTF(dir.path() / "tube.glb");
}

TEST(MeshWriters, MissingDirectoryThrowsAndWritesNothing) {
    const Mesh m = samplePlantMesh();
    TempDir dir;
    const fs::path missing = dir.path() / "missing";
    for (const char* name : {"plant.obj", "plant.ply", "plant.glb"}) {
        const fs::path path = missing / name;
        try {
            if (path.extension() == ".obj") graftal::writeObj(m, path);
            if (path.extension() == ".ply") graftal::writePly(m, path);
            if (path.extension() == ".glb") graftal::writeGlb(m, path);
            ADD_FAILURE() << "writing " << path << " should fail";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
            EXPECT_EQ(e.diagnostics().front().location.file, path.string());
        }
        EXPECT_FALSE(fs::exists(missing));
        EXPECT_TRUE(listing(dir.path()).empty());
    }
}

TEST(MeshWriters, FailedWriteLeavesNoFile) {
    const Mesh m = samplePlantMesh();
    TempDir dir;
    // The materials cannot be put in place (a directory has their name): the OBJ is not
    // written either, and no temporary stays behind.
    fs::create_directory(dir.path() / "plant.mtl");
    EXPECT_THROW(graftal::writeObj(m, dir.path() / "plant.obj"), Error);
    EXPECT_EQ(listing(dir.path()), std::vector<fs::path>{"plant.mtl"});
    // The target itself is a directory.
    fs::create_directory(dir.path() / "plant.glb");
    fs::create_directory(dir.path() / "plant.ply");
    EXPECT_THROW(graftal::writeGlb(m, dir.path() / "plant.glb"), Error);
    EXPECT_THROW(graftal::writePly(m, dir.path() / "plant.ply"), Error);
    EXPECT_EQ(listing(dir.path()), (std::vector<fs::path>{"plant.glb", "plant.mtl", "plant.ply"}));
}

TEST(MeshWriters, ReplacingAFileIsAtomic) {
    TempDir dir;
    const fs::path path = dir.path() / "plant.ply";
    dir.write("plant.ply", "old");
    Mesh broken = samplePlantMesh();
    broken.indices[5] = static_cast<std::uint32_t>(broken.positions.size());
    EXPECT_THROW(graftal::writePly(broken, path), Error);
    EXPECT_EQ(readFile(path), "old");
    graftal::writePly(samplePlantMesh(), path);
    EXPECT_EQ(readFile(path).substr(0, 4), "ply\n");
    EXPECT_EQ(listing(dir.path()), std::vector<fs::path>{"plant.ply"});
}

}  // namespace
