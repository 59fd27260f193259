// The ray tracer's light: what colour each pixel gets once Embree says what its rays hit
// (a soft sun with shadows, sky light with ambient occlusion, an optional ground), and the
// tiles the picture is cut into for the threads.
#pragma once

#include <vector>

#include "raytrace_camera.hpp"
#include "raytrace_scene.hpp"

namespace graftal {

// The floor under a scene: the plane through its lowest point (along the camera's up),
// drawn out to about the scene's size around it, then fading into the background.
struct Ground {
    double height = 0;     // dot(point, up) of the plane
    Vec3 centre;           // of the scene, on the plane
    double fadeStart = 0;  // distances from the centre where the floor starts fading
    double fadeEnd = 0;    // ... and is gone
};

// The ground under the scene's box, for `up` (unit).
Ground groundUnder(const Bounds& bounds, const Vec3& up);

// Renders the RGB8 picture (rows top to bottom) of the scene into `out`. Threads take
// tiles from a shared counter; what a tile contains does not depend on which takes it.
void renderPixels(const EmbreeScene& scene, const std::vector<Rgb>& palette, const View& view,
                  const Bounds& bounds, const RaytraceOptions& options, unsigned char* out);

// The background colour as the picture's bytes.
void fillBackground(std::vector<unsigned char>& pixels, const Rgb& background);

}  // namespace graftal
