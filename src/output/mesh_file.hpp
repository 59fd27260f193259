// What the 3D writers (OBJ, PLY, glTF) share: checking the mesh they are given, and the
// mesh's triangles grouped into one material per colour. They write through
// writeStreamAtomically (atomic_file.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/output/output.hpp"

namespace graftal::mesh_file {

// Writers index arrays without further checks, so a malformed mesh is refused up front.
inline void checkMesh(const Mesh& mesh, const std::filesystem::path& path,
                      std::string_view format) {
    auto bad = [&](const std::string& what) {
        return fileError(path, "cannot write " + std::string(format) + ": invalid mesh: " + what);
    };
    if (mesh.normals.size() != mesh.positions.size())
        throw bad("it has " + std::to_string(mesh.normals.size()) + " normals for " +
                  std::to_string(mesh.positions.size()) + " vertices");
    if (mesh.indices.size() != 3 * mesh.triangleColor.size())
        throw bad("it has " + std::to_string(mesh.indices.size()) + " indices for " +
                  std::to_string(mesh.triangleColor.size()) + " triangles");
    for (std::uint32_t i : mesh.indices)
        if (i >= mesh.positions.size())
            throw bad("vertex index " + std::to_string(i) + " is out of range");
}

// Colour indices past the end of the palette wrap around, as Scene::colorOf does. A
// scene's prototypes index the palette of its mesh, so the palette is passed on its own.
inline std::uint16_t paletteIndex(const std::vector<Rgb>& palette, std::uint16_t color) {
    return palette.empty() ? color : static_cast<std::uint16_t>(color % palette.size());
}
inline std::uint16_t paletteIndex(const Mesh& mesh, std::uint16_t color) {
    return paletteIndex(mesh.palette, color);
}
inline Rgb paletteColor(const std::vector<Rgb>& palette, std::uint16_t color) {
    return palette.empty() ? Rgb{0.5f, 0.5f, 0.5f} : palette[paletteIndex(palette, color)];
}
inline Rgb paletteColor(const Mesh& mesh, std::uint16_t color) {
    return paletteColor(mesh.palette, color);
}
inline std::string materialName(std::uint16_t paletteIndex) {
    return "color" + std::to_string(paletteIndex);
}
inline std::array<std::uint8_t, 3> colorBytes(const Rgb& c) {
    auto byte = [](float v) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
    };
    return {byte(c.r), byte(c.g), byte(c.b)};
}

// The triangles of one palette entry: one material in OBJ and glTF.
struct ColorGroup {
    std::uint16_t color = 0;               // palette index
    std::vector<std::uint32_t> triangles;  // indices of the mesh's triangles, in mesh order
};

// In palette order; palette entries no triangle uses get no group.
inline std::vector<ColorGroup> groupByColor(const Mesh& mesh, const std::vector<Rgb>& palette) {
    std::vector<std::uint32_t> count(std::numeric_limits<std::uint16_t>::max() + 1, 0);
    for (std::uint16_t c : mesh.triangleColor) ++count[paletteIndex(palette, c)];
    std::vector<ColorGroup> groups;
    std::vector<std::uint32_t> groupOf(count.size(), 0);
    for (std::size_t c = 0; c < count.size(); ++c) {
        if (count[c] == 0) continue;
        groupOf[c] = static_cast<std::uint32_t>(groups.size());
        groups.push_back({static_cast<std::uint16_t>(c), {}});
        groups.back().triangles.reserve(count[c]);
    }
    for (std::uint32_t t = 0; t < mesh.triangleColor.size(); ++t)
        groups[groupOf[paletteIndex(palette, mesh.triangleColor[t])]].triangles.push_back(t);
    return groups;
}
inline std::vector<ColorGroup> groupByColor(const Mesh& mesh) {
    return groupByColor(mesh, mesh.palette);
}

// A colour group with vertices of its own, for formats whose vertices carry the colour
// (PLY) or whose primitives are indexed separately (glTF): a vertex shared by two colours
// becomes one vertex in each.
struct GroupVertices {
    std::vector<std::uint32_t> vertices;  // the mesh vertex of each group vertex
    std::vector<std::uint32_t> indices;   // into `vertices`, 3 per triangle
};

class VertexSplitter {
  public:
    explicit VertexSplitter(const Mesh& mesh) : mesh_(mesh), local_(mesh.positions.size(), kNone) {}

    GroupVertices split(const ColorGroup& group) {
        GroupVertices out;
        out.indices.reserve(3 * group.triangles.size());
        for (std::uint32_t t : group.triangles) {
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = mesh_.indices[3 * static_cast<std::size_t>(t) + k];
                if (local_[v] == kNone) {
                    local_[v] = static_cast<std::uint32_t>(out.vertices.size());
                    out.vertices.push_back(v);
                }
                out.indices.push_back(local_[v]);
            }
        }
        // Reset only what this group touched, so that splitting stays linear in the mesh.
        for (std::uint32_t v : out.vertices) local_[v] = kNone;
        return out;
    }

  private:
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    const Mesh& mesh_;
    std::vector<std::uint32_t> local_;
};

}  // namespace graftal::mesh_file
