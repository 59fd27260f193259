// Pictures of 3D scenes: a headless ray tracer (Embree) with a sun, shadows and sky light.
#pragma once

#include <filesystem>
#include <optional>

#include "graftal/mesh.hpp"
#include "graftal/mesh_scene.hpp"
#include "graftal/scene.hpp"

namespace graftal {

struct Camera {
    // Unset fields are chosen to frame the mesh: the camera looks at the centre of the
    // bounds from the front (+z, slightly raised), far enough that everything is in view.
    std::optional<Vec3> viewpoint;
    std::optional<Vec3> target;  // cpfg's "view reference point"
    Vec3 up{0, 1, 0};
    double fieldOfView = 40;  // vertical, degrees
    bool orthographic = false;
};

struct Lighting {
    Vec3 sunDirection{0.4, 1.0, 0.6};  // towards the sun (need not be unit length)
    double sunIntensity = 0.9;
    double skyIntensity = 0.35;  // ambient light from the sky hemisphere
    bool shadows = true;
};

struct RaytraceOptions {
    int width = 800, height = 800;
    int samplesPerPixel = 4;  // antialiasing (stratified)
    Rgb background{1, 1, 1};
    Camera camera;
    Lighting lighting;
    unsigned threads = 0;  // 0: all cores
};

// Renders the mesh to a PNG at `path` (atomically, like writeImage). Throws Error.
void renderRaytraced(const Mesh& mesh, const RaytraceOptions& options,
                     const std::filesystem::path& path);

// The same image into memory, RGB8 rows top to bottom (for tests and other front ends).
std::vector<unsigned char> renderRaytracedPixels(const Mesh& mesh, const RaytraceOptions& options);

// The same for an instanced scene: prototypes are placed as instances, curves drawn as
// round curves.
void renderRaytraced(const MeshScene& scene, const RaytraceOptions& options,
                     const std::filesystem::path& path);
std::vector<unsigned char> renderRaytracedPixels(const MeshScene& scene,
                                                 const RaytraceOptions& options);

}  // namespace graftal
