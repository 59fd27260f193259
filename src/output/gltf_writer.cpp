// glTF 2.0 binary (.glb) through tinygltf: one mesh with one primitive per colour, each
// with its own vertices, and a PBR material per colour. The materials are double-sided
// because polygons and surfaces are single sheets (see src/geometry/mesh.cpp).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "graftal/mesh.hpp"
#include "graftal/output.hpp"
#include "mesh_file.hpp"

namespace graftal {

namespace {

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian and are copied from memory as they are");

constexpr double kRoughness = 0.8;
// The GLB header and chunk lengths are 32-bit; leave room for the JSON chunk.
constexpr std::size_t kMaxBinaryBytes = std::numeric_limits<std::uint32_t>::max() - (1u << 24);

// The palette is in sRGB, as pictures are; glTF colour factors are linear.
double linearFromSrgb(float c) {
    const double v = std::clamp(static_cast<double>(c), 0.0, 1.0);
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

class ModelBuilder {
  public:
    ModelBuilder() {
        model_.asset.version = "2.0";
        model_.asset.generator = "graftal";
        model_.buffers.emplace_back();
    }

    // One primitive: the group's vertices (positions, normals) and triangles.
    void addPrimitive(const Mesh& mesh, const mesh_file::GroupVertices& group, int material,
                      tinygltf::Mesh& out) {
        tinygltf::Primitive primitive;
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        primitive.material = material;
        primitive.attributes["POSITION"] = addVectors(mesh.positions, group.vertices, true);
        primitive.attributes["NORMAL"] = addVectors(mesh.normals, group.vertices, false);
        primitive.indices = addIndices(group.indices);
        out.primitives.push_back(std::move(primitive));
    }

    int addMaterial(std::uint16_t color, const Rgb& c) {
        tinygltf::Material m;
        m.name = mesh_file::materialName(color);
        m.pbrMetallicRoughness.baseColorFactor = {linearFromSrgb(c.r), linearFromSrgb(c.g),
                                                  linearFromSrgb(c.b), 1.0};
        m.pbrMetallicRoughness.metallicFactor = 0;
        m.pbrMetallicRoughness.roughnessFactor = kRoughness;
        // tinygltf writes an empty emissiveFactor array (invalid) unless it is set.
        m.emissiveFactor = {0, 0, 0};
        m.doubleSided = true;
        model_.materials.push_back(std::move(m));
        return static_cast<int>(model_.materials.size() - 1);
    }

    std::size_t binarySize() const { return model_.buffers[0].data.size(); }
    void reserve(std::size_t bytes) { model_.buffers[0].data.reserve(bytes); }

    tinygltf::Model finish(tinygltf::Mesh mesh) {
        tinygltf::Node node;
        node.name = "graftal";
        if (!mesh.primitives.empty()) {
            model_.meshes.push_back(std::move(mesh));
            node.mesh = 0;
        }
        // glTF requires every buffer to hold at least one byte.
        if (model_.buffers[0].data.empty()) model_.buffers.clear();
        model_.nodes.push_back(std::move(node));
        tinygltf::Scene scene;
        scene.nodes = {0};
        model_.scenes.push_back(std::move(scene));
        model_.defaultScene = 0;
        return std::move(model_);
    }

  private:
    int addVectors(const std::vector<Vec3f>& source, const std::vector<std::uint32_t>& which,
                   bool bounds) {
        // Written straight into the buffer: a big plant's buffer is hundreds of megabytes.
        std::vector<unsigned char>& buffer = model_.buffers[0].data;
        const std::size_t offset = buffer.size();
        buffer.resize(offset + 12 * which.size());
        unsigned char* out = buffer.data() + offset;
        // POSITION needs min and max, which must be exactly the stored floats.
        float low[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF};
        float high[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
        for (std::uint32_t v : which) {
            const float xyz[3] = {source[v].x, source[v].y, source[v].z};
            std::memcpy(out, xyz, sizeof xyz);
            out += sizeof xyz;
            for (int k = 0; k < 3; ++k) {
                low[k] = std::min(low[k], xyz[k]);
                high[k] = std::max(high[k], xyz[k]);
            }
        }
        const int accessor =
            addAccessor(addView(offset, 12 * which.size(), TINYGLTF_TARGET_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, which.size());
        if (bounds) {
            model_.accessors[accessor].minValues.assign(low, low + 3);
            model_.accessors[accessor].maxValues.assign(high, high + 3);
        }
        return accessor;
    }

    // Every view starts on a 4-byte boundary, as float and uint32 accessors need; all
    // the data here is 4-byte values, so the buffer never needs padding.
    int addView(std::size_t offset, std::size_t bytes, int target) {
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = offset;
        view.byteLength = bytes;
        view.target = target;
        model_.bufferViews.push_back(view);
        return static_cast<int>(model_.bufferViews.size() - 1);
    }

    int addIndices(const std::vector<std::uint32_t>& indices) {
        std::vector<unsigned char>& buffer = model_.buffers[0].data;
        const std::size_t offset = buffer.size();
        const std::size_t bytes = 4 * indices.size();
        buffer.resize(offset + bytes);
        std::memcpy(buffer.data() + offset, indices.data(), bytes);
        return addAccessor(addView(offset, bytes, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                           indices.size());
    }

    int addAccessor(int view, int componentType, int type, std::size_t count) {
        tinygltf::Accessor a;
        a.bufferView = view;
        a.byteOffset = 0;
        a.componentType = componentType;
        a.type = type;
        a.count = count;
        model_.accessors.push_back(std::move(a));
        return static_cast<int>(model_.accessors.size() - 1);
    }

    tinygltf::Model model_;
};

}  // namespace

void writeGlb(const Mesh& mesh, const std::filesystem::path& path) {
    const std::string format(fileFormatInfo(FileFormat::Glb).name);
    mesh_file::checkMesh(mesh, path, format);
    // The directory is checked first, so that a missing one is reported before any work.
    writeStreamAtomically(
        path,
        [&](std::ostream& file) {
            const std::vector<mesh_file::ColorGroup> groups = mesh_file::groupByColor(mesh);
            mesh_file::VertexSplitter splitter(mesh);

            ModelBuilder builder;
            // Exact unless vertices are shared by colours (then they are written once per
            // colour).
            builder.reserve(
                std::min(kMaxBinaryBytes, 24 * mesh.positions.size() + 4 * mesh.indices.size()));
            tinygltf::Mesh gltfMesh;
            gltfMesh.name = "graftal";
            for (const mesh_file::ColorGroup& g : groups) {
                const int material =
                    builder.addMaterial(g.color, mesh_file::paletteColor(mesh, g.color));
                builder.addPrimitive(mesh, splitter.split(g), material, gltfMesh);
                if (builder.binarySize() > kMaxBinaryBytes)
                    throw fileError(path, "cannot write " + format +
                                              ": the mesh is larger than the 4 GB a .glb file "
                                              "can hold");
            }
            const tinygltf::Model model = builder.finish(std::move(gltfMesh));
            tinygltf::TinyGLTF gltf;
            if (!gltf.WriteGltfSceneToStream(&model, file, false, true))
                throw fileError(path, "cannot write " + format + ": the glTF library failed");
        },
        format);
}

}  // namespace graftal
