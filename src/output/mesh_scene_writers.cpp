// The 3D files and pictures of an instanced scene, for writers that do not (yet) keep its
// instancing: they are given the flattened mesh.
#include "graftal/mesh_scene.hpp"
#include "graftal/output.hpp"
#include "graftal/render3d.hpp"

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

void renderRaytraced(const MeshScene& scene, const RaytraceOptions& options,
                     const std::filesystem::path& path) {
    renderRaytraced(scene.flattened(), options, path);
}

std::vector<unsigned char> renderRaytracedPixels(const MeshScene& scene,
                                                 const RaytraceOptions& options) {
    return renderRaytracedPixels(scene.flattened(), options);
}

}  // namespace graftal
