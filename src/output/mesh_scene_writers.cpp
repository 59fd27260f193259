// OBJ and PLY files of an instanced scene: neither format can place one mesh several
// times, so they are given the flattened mesh (every placement copied). The GLB writer
// keeps the instancing (gltf_writer.cpp).
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/output/output.hpp"

namespace graftal {

void writeObj(const MeshScene& scene, const std::filesystem::path& path) {
    writeObj(scene.flattened(), path);
}

void writePly(const MeshScene& scene, const std::filesystem::path& path) {
    writePly(scene.flattened(), path);
}

void writeObj(const MeshScene& scene, const Destination& obj, const Destination& mtl) {
    writeObj(scene.flattened(), obj, mtl);
}

void writePly(const MeshScene& scene, const Destination& destination) {
    writePly(scene.flattened(), destination);
}

}  // namespace graftal
