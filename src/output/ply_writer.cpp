// Stanford PLY, binary little-endian: positions, normals and colours per vertex, triangles
// as index lists. The colour lives on the vertices, so a vertex shared by triangles of two
// colours is written once for each.
#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <string>

#include "graftal/core/bit_cast.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/output/output.hpp"
#include "mesh_file.hpp"

namespace graftal {

namespace {

// Fixed-size records assembled in memory and written in large blocks.
class BinaryBuffer {
  public:
    explicit BinaryBuffer(std::ostream& out) : out_(out) { bytes_.reserve(kFlushAt + 64); }

    template <class T>
    void put(T v) {
        auto word = bitCast<std::array<char, sizeof(T)>>(v);
        if constexpr (std::endian::native == std::endian::big)
            std::reverse(word.begin(), word.end());
        bytes_.append(word.data(), word.size());
    }
    void endRecord() {
        if (bytes_.size() >= kFlushAt) flush();
    }
    void flush() {
        out_.write(bytes_.data(), static_cast<std::streamsize>(bytes_.size()));
        bytes_.clear();
    }

  private:
    static constexpr std::size_t kFlushAt = 1 << 20;

    std::ostream& out_;
    std::string bytes_;
};

// The header and the records, into the temporary file.
void writeMesh(const Mesh& mesh, const std::filesystem::path& path, std::ostream& file) {
    const std::vector<mesh_file::ColorGroup> groups = mesh_file::groupByColor(mesh);
    mesh_file::VertexSplitter splitter(mesh);
    std::vector<mesh_file::GroupVertices> split;
    split.reserve(groups.size());
    std::size_t vertexCount = 0;
    for (const mesh_file::ColorGroup& g : groups) {
        split.push_back(splitter.split(g));
        vertexCount += split.back().vertices.size();
    }
    // Face lists are declared as `int`.
    if (vertexCount > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        throw fileError(path, "cannot write PLY: " + std::to_string(vertexCount) +
                                  " vertices are more than PLY's int indices allow");

    file << "ply\n"
         << "format binary_little_endian 1.0\n"
         << "comment graftal mesh\n"
         << "element vertex " << vertexCount << "\n"
         << "property float x\nproperty float y\nproperty float z\n"
         << "property float nx\nproperty float ny\nproperty float nz\n"
         << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
         << "element face " << mesh.triangleCount() << "\n"
         << "property list uchar int vertex_indices\n"
         << "end_header\n";

    BinaryBuffer out(file);
    for (std::size_t k = 0; k < groups.size(); ++k) {
        const auto rgb = mesh_file::colorBytes(mesh_file::paletteColor(mesh, groups[k].color));
        for (std::uint32_t v : split[k].vertices) {
            const Vec3f& p = mesh.positions[v];
            const Vec3f& n = mesh.normals[v];
            for (float x : {p.x, p.y, p.z, n.x, n.y, n.z}) out.put(x);
            for (std::uint8_t c : rgb) out.put(c);
            out.endRecord();
        }
    }
    std::int32_t base = 0;
    for (const mesh_file::GroupVertices& g : split) {
        for (std::size_t i = 0; i < g.indices.size(); i += 3) {
            out.put(std::uint8_t{3});
            for (std::size_t k = 0; k < 3; ++k)
                out.put(base + static_cast<std::int32_t>(g.indices[i + k]));
            out.endRecord();
        }
        base += static_cast<std::int32_t>(g.vertices.size());
    }
    out.flush();
}

}  // namespace

void writePly(const Mesh& mesh, const std::filesystem::path& path) {
    writePly(mesh, Destination::file(path));
}

void writePly(const Mesh& mesh, const Destination& destination) {
    const std::string format(fileFormatInfo(FileFormat::Ply).name);
    mesh_file::checkMesh(mesh, destination.path(), format);
    // A file's directory is checked first, so that a missing one is reported before any work.
    destination.write(format,
                      [&](std::ostream& file) { writeMesh(mesh, destination.path(), file); });
}

}  // namespace graftal
