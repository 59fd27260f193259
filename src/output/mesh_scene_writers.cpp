// OBJ and PLY files of an instanced scene: neither format can place one mesh several
// times, so they are given the flattened mesh (every placement copied). The GLB writer
// keeps the instancing (gltf_writer.cpp).
#include "graftal/mesh_scene.hpp"
#include "graftal/output.hpp"

namespace graftal {

void writeObj(const MeshScene& scene, const std::filesystem::path& path) {
    writeObj(scene.flattened(), path);
}

void writePly(const MeshScene& scene, const std::filesystem::path& path) {
    writePly(scene.flattened(), path);
}

}  // namespace graftal
