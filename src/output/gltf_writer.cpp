// glTF 2.0 binary (.glb). Each mesh gets one primitive per colour, each with its own
// vertices in meshoptimizer's vertex cache and fetch order, and a PBR material per colour.
// The materials are double-sided because polygons and surfaces are single sheets (see
// src/geometry/mesh.cpp).
//
// A MeshScene's prototypes are written once and placed with EXT_mesh_gpu_instancing: one
// node per prototype whose instances carry translation, rotation and scale. That extension
// has no fallback for viewers without it (they would draw each prototype once, at the
// origin), so, as its specification asks, it is listed as required; GlbOptions::instancing
// = false writes copies instead. Mirrored placements use a mirrored copy of their prototype
// (instanced renderers do not rewind a mirrored instance's triangles); placements that are
// not a rotation times a scale per axis (shear) are copied into the mesh.
#ifndef GRAFTAL_NO_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "glb_builder.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/output/output.hpp"
#include "instance_transform.hpp"
#include "mesh_file.hpp"

namespace graftal {

namespace {

using nlohmann::json;

constexpr double kRoughness = 0.8;
#ifndef GRAFTAL_NO_MESHOPTIMIZER
// Mantissa bits of compressed positions (see compressedPositions).
constexpr int kPositionBits = 16;
#endif
// The GLB header and chunk lengths are 32-bit; leave room for the JSON chunk.
constexpr std::size_t kMaxBinaryBytes = std::numeric_limits<std::uint32_t>::max() - (1u << 24);

// The palette is in sRGB, as pictures are; glTF colour factors are linear.
double linearFromSrgb(float c) {
    const double v = std::clamp(static_cast<double>(c), 0.0, 1.0);
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

template <class T>
std::span<const unsigned char> bytesOf(const std::vector<T>& v) {
    return {reinterpret_cast<const unsigned char*>(v.data()), v.size() * sizeof(T)};
}

class GltfDocument {
  public:
    GltfDocument(const std::vector<Rgb>& palette, const GlbOptions& options,
                 const std::filesystem::path& path)
        : palette_(palette), builder_(options.compression), path_(path) {
        json& d = builder_.document();
        d["asset"] = {{"version", "2.0"}, {"generator", "graftal"}};
        d["nodes"] = json::array({{{"name", "graftal"}}});
        d["scenes"] = json::array({{{"nodes", {0}}}});
        d["scene"] = 0;
    }

    void reserve(std::size_t bytes) { builder_.reserve(std::min(bytes, kMaxBinaryBytes)); }

    // A glTF mesh with one primitive per colour; -1 when the mesh has no triangles.
    int addMesh(const Mesh& mesh, const std::string& name) {
        if (mesh.triangleCount() == 0) return -1;
        json primitives = json::array();
        mesh_file::VertexSplitter splitter(mesh);
        for (const mesh_file::ColorGroup& g : mesh_file::groupByColor(mesh, palette_)) {
            primitives.push_back(primitive(mesh, splitter.split(g), material(g.color)));
            checkSize();
        }
        json& meshes = builder_.document()["meshes"];
        meshes.push_back({{"name", name}, {"primitives", std::move(primitives)}});
        return static_cast<int>(meshes.size() - 1);
    }

    // Shows `mesh` as it is (part of node 0).
    void show(int mesh, const std::string& name) {
        if (mesh < 0) return;
        json& root = builder_.document()["nodes"][0];
        if (!root.contains("mesh")) {
            root["mesh"] = mesh;
            return;
        }
        addChild({{"name", name}, {"mesh", mesh}});
    }

    // Shows `mesh` once per transform, through EXT_mesh_gpu_instancing.
    void showInstances(int mesh, const std::string& name,
                       const std::vector<instance_transform::Trs>& instances) {
        if (mesh < 0 || instances.empty()) return;
        std::vector<float> translation, rotation, scale;
        translation.reserve(3 * instances.size());
        rotation.reserve(4 * instances.size());
        scale.reserve(3 * instances.size());
        for (const instance_transform::Trs& t : instances) {
            translation.insert(translation.end(), t.translation.begin(), t.translation.end());
            rotation.insert(rotation.end(), t.rotation.begin(), t.rotation.end());
            scale.insert(scale.end(), t.scale.begin(), t.scale.end());
        }
        const std::size_t n = instances.size();
        json attributes = {
            {"TRANSLATION",
             builder_.addAccessor(builder_.addAttributeView(bytesOf(translation), n, 12, 0),
                                  glb::kFloat, "VEC3", n)},
            {"ROTATION",
             builder_.addAccessor(builder_.addAttributeView(bytesOf(rotation), n, 16, 0),
                                  glb::kFloat, "VEC4", n)},
            {"SCALE", builder_.addAccessor(builder_.addAttributeView(bytesOf(scale), n, 12, 0),
                                           glb::kFloat, "VEC3", n)}};
        checkSize();
        builder_.requireExtension(glb::kGpuInstancing);
        addChild({{"name", name},
                  {"mesh", mesh},
                  {"extensions", {{glb::kGpuInstancing, {{"attributes", attributes}}}}}});
    }

    void write(std::ostream& out) {
        if (!builder_.write(out)) throw tooLarge();
    }

  private:
    Error tooLarge() const {
        return fileError(path_, "cannot write " +
                                    std::string(fileFormatInfo(FileFormat::Glb).name) +
                                    ": the mesh is larger than the 4 GB a .glb file can hold");
    }
    void checkSize() const {
        if (builder_.binarySize() > kMaxBinaryBytes) throw tooLarge();
    }

    void addChild(json node) {
        json& nodes = builder_.document()["nodes"];
        nodes.push_back(std::move(node));
        nodes[0]["children"].push_back(nodes.size() - 1);
    }

    int material(std::uint16_t color) {
        const auto [it, added] = materials_.try_emplace(color, 0);
        if (!added) return it->second;
        const Rgb c = mesh_file::paletteColor(palette_, color);
        json& materials = builder_.document()["materials"];
        materials.push_back(
            {{"name", mesh_file::materialName(color)},
             {"pbrMetallicRoughness",
              {{"baseColorFactor",
                {linearFromSrgb(c.r), linearFromSrgb(c.g), linearFromSrgb(c.b), 1.0}},
               {"metallicFactor", 0.0},
               {"roughnessFactor", kRoughness}}},
             {"doubleSided", true}});
        it->second = static_cast<int>(materials.size() - 1);
        return it->second;
    }

    // One colour's triangles, reordered for the vertex cache and its vertices for fetching
    // in that order: faster to draw, and the order meshopt's codecs compress best.
    json primitive(const Mesh& mesh, const mesh_file::GroupVertices& group, int materialIndex) {
        const std::size_t vertexCount = group.vertices.size();
#ifdef GRAFTAL_NO_MESHOPTIMIZER
        // The web build: the triangles and vertices in the mesher's order.
        std::vector<std::uint32_t> indices(group.indices.begin(), group.indices.end());
        std::vector<std::uint32_t> order(group.vertices.begin(), group.vertices.end());
#else
        std::vector<std::uint32_t> indices(group.indices.size());
        meshopt_optimizeVertexCache(indices.data(), group.indices.data(), indices.size(),
                                    vertexCount);
        std::vector<std::uint32_t> remap(vertexCount);
        meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), vertexCount);
        meshopt_remapIndexBuffer(indices.data(), indices.data(), indices.size(), remap.data());
        std::vector<std::uint32_t> order(vertexCount);
        for (std::size_t v = 0; v < vertexCount; ++v) order[remap[v]] = group.vertices[v];
#endif

        std::vector<float> positions;
        positions.reserve(3 * vertexCount);
        for (std::uint32_t v : order) {
            const Vec3f& p = mesh.positions[v];
            positions.insert(positions.end(), {p.x, p.y, p.z});
        }
        const int position =
            builder_.compressing() ? compressedPositions(positions) : plainPositions(positions);
        const int normal =
            builder_.compressing() ? quantizedNormals(mesh, order) : plainNormals(mesh, order);
        // 16-bit indices where they reach every vertex (65535 is reserved for restarts).
        const bool shortIndices = vertexCount < std::numeric_limits<std::uint16_t>::max();
        const int index = builder_.addAccessor(
            builder_.addTriangleView(indices, shortIndices),
            shortIndices ? glb::kUnsignedShort : glb::kUnsignedInt, "SCALAR", indices.size());
        return {{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
                {"indices", index},
                {"material", materialIndex},
                {"mode", 4}};
    }

    // POSITION needs min and max, which must be exactly the stored floats.
    void setBounds(int accessor, const std::vector<float>& xyz) {
        std::vector<double> low(3, HUGE_VAL), high(3, -HUGE_VAL);
        for (std::size_t i = 0; i < xyz.size(); ++i) {
            low[i % 3] = std::min<double>(low[i % 3], xyz[i]);
            high[i % 3] = std::max<double>(high[i % 3], xyz[i]);
        }
        builder_.document()["accessors"][accessor]["min"] = low;
        builder_.document()["accessors"][accessor]["max"] = high;
    }

    int plainPositions(const std::vector<float>& positions) {
        const std::size_t n = positions.size() / 3;
        const int accessor = builder_.addAccessor(
            builder_.addAttributeView(bytesOf(positions), n, 12, glb::kArrayBuffer), glb::kFloat,
            "VEC3", n);
        setBounds(accessor, positions);
        return accessor;
    }

    // Floats kept to kPositionBits of mantissa (sign included), one exponent per vertex: the
    // codec then finds the low bits zero. A vertex moves by at most 2^-14 of its largest
    // coordinate, or of 1 if that is smaller (4 mm at 60 m from the origin).
    int compressedPositions(const std::vector<float>& positions) {
#ifdef GRAFTAL_NO_MESHOPTIMIZER
        return plainPositions(positions);  // never compressing (glb::Builder)
#else
        const std::size_t n = positions.size() / 3;
        std::vector<std::uint32_t> filtered(3 * n);
        meshopt_encodeFilterExp(filtered.data(), n, 12, kPositionBits, positions.data());
        std::vector<float> stored(3 * n);
        std::memcpy(stored.data(), filtered.data(), 12 * n);
        meshopt_decodeFilterExp(stored.data(), n, 12);
        const int accessor = builder_.addAccessor(
            builder_.addAttributeView(bytesOf(filtered), n, 12, glb::kArrayBuffer,
                                      glb::Filter::Exponential),
            glb::kFloat, "VEC3", n);
        setBounds(accessor, stored);
        return accessor;
#endif
    }

    int plainNormals(const Mesh& mesh, const std::vector<std::uint32_t>& order) {
        std::vector<float> normals;
        normals.reserve(3 * order.size());
        for (std::uint32_t v : order) {
            const Vec3f& n = mesh.normals[v];
            normals.insert(normals.end(), {n.x, n.y, n.z});
        }
        return builder_.addAccessor(
            builder_.addAttributeView(bytesOf(normals), order.size(), 12, glb::kArrayBuffer),
            glb::kFloat, "VEC3", order.size());
    }

    // Octahedral 8-bit normals (KHR_mesh_quantization's normalized bytes, padded to 4):
    // about a degree of error, invisible in shading, and a quarter of the floats' size
    // before the codec.
    int quantizedNormals(const Mesh& mesh, const std::vector<std::uint32_t>& order) {
#ifdef GRAFTAL_NO_MESHOPTIMIZER
        return plainNormals(mesh, order);  // never compressing (glb::Builder)
#else
        std::vector<float> xyzw;
        xyzw.reserve(4 * order.size());
        for (std::uint32_t v : order) {
            const Vec3f& n = mesh.normals[v];
            xyzw.insert(xyzw.end(), {n.x, n.y, n.z, 0.0f});
        }
        std::vector<std::int8_t> filtered(4 * order.size());
        meshopt_encodeFilterOct(filtered.data(), order.size(), 4, 8, xyzw.data());
        builder_.requireExtension(glb::kMeshQuantization);
        const int accessor = builder_.addAccessor(
            builder_.addAttributeView(bytesOf(filtered), order.size(), 4, glb::kArrayBuffer,
                                      glb::Filter::Octahedral, true),
            glb::kByte, "VEC3", order.size());
        builder_.document()["accessors"][accessor]["normalized"] = true;
        return accessor;
#endif
    }

    const std::vector<Rgb>& palette_;
    glb::Builder builder_;
    std::filesystem::path path_;
    std::map<std::uint16_t, int> materials_;
};

void checkScene(const MeshScene& scene, const std::filesystem::path& path,
                const std::string& format) {
    mesh_file::checkMesh(scene.mesh, path, format);
    for (const Mesh& p : scene.prototypes) mesh_file::checkMesh(p, path, format);
    for (const MeshPlacement& p : scene.placements)
        if (p.prototype >= scene.prototypes.size())
            throw fileError(path, "cannot write " + format +
                                      ": invalid mesh: placement of prototype " +
                                      std::to_string(p.prototype) + " of " +
                                      std::to_string(scene.prototypes.size()));
}

// The placements in `which` copied into one mesh, as MeshScene::flattened copies them.
Mesh copiesOf(const MeshScene& scene, const std::vector<const MeshPlacement*>& which) {
    Mesh out;
    out.palette = scene.palette();
    for (const MeshPlacement* p : which) scene.appendCopy(*p, out);
    return out;
}

void writeDocument(const Destination& destination, const std::function<void(GltfDocument&)>& build,
                   const std::vector<Rgb>& palette, const GlbOptions& options,
                   std::size_t estimate) {
    const std::string format(fileFormatInfo(FileFormat::Glb).name);
    // A file's directory is checked first, so that a missing one is reported before any work.
    destination.write(format, [&](std::ostream& file) {
        GltfDocument document(palette, options, destination.path());
        document.reserve(estimate);
        build(document);
        document.write(file);
    });
}

}  // namespace

void writeGlb(const Mesh& mesh, const std::filesystem::path& path) {
    mesh_file::checkMesh(mesh, path, std::string(fileFormatInfo(FileFormat::Glb).name));
    // Exact unless vertices are shared by colours (then they are written once per colour).
    writeDocument(
        Destination::file(path),
        [&](GltfDocument& d) { d.show(d.addMesh(mesh, "graftal"), "graftal"); }, mesh.palette,
        GlbOptions{}, 24 * mesh.positions.size() + 4 * mesh.indices.size());
}

void writeGlb(const MeshScene& scene, const std::filesystem::path& path,
              const GlbOptions& options) {
    writeGlb(scene, Destination::file(path), options);
}

void writeGlb(const MeshScene& scene, const Destination& destination, const GlbOptions& options) {
    const std::filesystem::path& path = destination.path();
    checkScene(scene, path, std::string(fileFormatInfo(FileFormat::Glb).name));
    // Which placements are instanced, per prototype and mirroring, and which are copied.
    std::map<std::pair<std::uint32_t, bool>, std::vector<instance_transform::Trs>> instances;
    std::vector<const MeshPlacement*> copied;
    for (const MeshPlacement& p : scene.placements) {
        if (!options.instancing) {
            copied.push_back(&p);
            continue;
        }
        const bool mirrored = p.transform.determinant() < 0;
        const auto trs = instance_transform::decompose(
            mirrored ? instance_transform::withMirroredPrototype(p.transform) : p.transform);
        if (trs)
            instances[{p.prototype, mirrored}].push_back(*trs);
        else
            copied.push_back(&p);
    }
    std::size_t estimate = 24 * scene.mesh.positions.size() + 4 * scene.mesh.indices.size();
    for (const MeshPlacement* p : copied) {
        const Mesh& proto = scene.prototypes[p->prototype];
        estimate += 24 * proto.positions.size() + 4 * proto.indices.size();
    }
    writeDocument(
        destination,
        [&](GltfDocument& d) {
            d.show(d.addMesh(scene.mesh, "graftal"), "graftal");
            d.show(d.addMesh(copiesOf(scene, copied), "copies"), "copies");
            for (const auto& [key, transforms] : instances) {
                const auto [prototype, mirrored] = key;
                const std::string name =
                    "prototype " + std::to_string(prototype) + (mirrored ? " mirrored" : "");
                const Mesh& proto = scene.prototypes[prototype];
                const int mesh = mirrored
                                     ? d.addMesh(instance_transform::mirroredPrototype(proto), name)
                                     : d.addMesh(proto, name);
                d.showInstances(mesh, name, transforms);
            }
        },
        scene.palette(), options, estimate);
}

}  // namespace graftal
