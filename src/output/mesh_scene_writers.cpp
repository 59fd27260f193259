// The 3D files of an instanced scene, for writers that do not (yet) keep its instancing:
// they are given the flattened mesh.
#include "graftal/mesh_scene.hpp"
#include "graftal/output.hpp"

namespace graftal {

void writeObj(const MeshScene& scene, const std::filesystem::path& path) {
    writeObj(scene.flattened(), path);
}

void writePly(const MeshScene& scene, const std::filesystem::path& path) {
    writePly(scene.flattened(), path);
}

void writeGlb(const MeshScene& scene, const std::filesystem::path& path, const GlbOptions&) {
    writeGlb(scene.flattened(), path);
}

}  // namespace graftal
