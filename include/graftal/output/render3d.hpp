// Pictures of 3D scenes: a headless ray tracer (Embree) with a soft sun, shadows, sky light
// with ambient occlusion and an optional ground. Every pixel is a pure function of the
// scene, the options and its position: the picture is the same for any thread count.
#pragma once

#include <filesystem>
#include <optional>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal {

struct Camera {
    // Unset fields are chosen to frame the scene (framedCamera): the camera looks at it from
    // the front (+z, slightly raised), so that its outline fills the picture.
    std::optional<Vec3> viewpoint;
    std::optional<Vec3> target;  // cpfg's "view reference point"
    Vec3 up{0, 1, 0};
    double fieldOfView = 40;  // vertical, degrees
    bool orthographic = false;
    // Orthographic with a viewpoint and a target: only the direction between them counts,
    // and the window is fitted to the scene, as cpfg fits its parallel view volume to the
    // model (a cpfg view file's `viewpoint:` is often just outside the origin, which would
    // otherwise show a window a few units across).
    bool fitWindow = false;
};

struct Lighting {
    Vec3 sunDirection{0.4, 1.0, 0.6};  // towards the sun (need not be unit length)
    double sunIntensity = 0.9;
    // The sun's apparent size: shadows are soft over this angle (0: a point, sharp shadows).
    double sunDiameterDegrees = 2;
    double skyIntensity = 0.35;  // light from the sky hemisphere (and the ground below it)
    // Ambient occlusion: rays per hit that look for the sky, so that leaves shade each other
    // and the inside of a crown is darker than its outside. 0: the sky is never hidden.
    int skyRays = 2;
    bool shadows = true;  // of the sun
};

struct RaytraceOptions {
    int width = 800, height = 800;
    int samplesPerPixel = 4;  // antialiasing (stratified), soft shadows and sky share them
    Rgb background{1, 1, 1};
    Camera camera;
    Lighting lighting;
    // A floor under the scene (at its lowest point) that takes its shadow and fades into
    // the background away from it.
    bool ground = false;
    // Curves (thin stems) are drawn at least this many pixels wide, so that none vanishes
    // between the rays.
    double minimumCurvePixels = 1;
    unsigned threads = 0;  // 0: all cores
};

// Renders the mesh to a PNG at `path` (atomically, like writeImage). Throws Error.
void renderRaytraced(const Mesh& mesh, const RaytraceOptions& options,
                     const std::filesystem::path& path);

// The same image into memory, RGB8 rows top to bottom (for tests and other front ends).
std::vector<unsigned char> renderRaytracedPixels(const Mesh& mesh, const RaytraceOptions& options);

// The same for an instanced scene: each prototype is stored once and placed by Embree
// instances, curves are drawn as round curves (at least minimumCurvePixels wide).
void renderRaytraced(const MeshScene& scene, const RaytraceOptions& options,
                     const std::filesystem::path& path);
std::vector<unsigned char> renderRaytracedPixels(const MeshScene& scene,
                                                 const RaytraceOptions& options);

}  // namespace graftal
