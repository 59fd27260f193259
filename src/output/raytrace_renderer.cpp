// The headless 3D renderer's entry points: the options are checked, the camera framed on
// the scene (raytrace_camera), the scene handed to Embree without copying it
// (raytrace_scene) and the pixels shaded (raytrace_shading). The PNG goes through the
// atomic PNG writer, as the 2D pictures do.
#include <cmath>
#include <string>
#include <system_error>

#include "graftal/core/diagnostics.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/output/output.hpp"
#include "graftal/output/render3d.hpp"
#include "raytrace_camera.hpp"
#include "raytrace_scene.hpp"
#include "raytrace_shading.hpp"
#include "traced_scene.hpp"

namespace graftal {

namespace {

namespace fs = std::filesystem;

// Cairo's image surfaces are limited to 32767 pixels a side; the in-memory image keeps the
// same limit so that the two entry points accept the same options.
constexpr int kMaxPixelSize = 32767;
constexpr int kMaxSamplesPerPixel = 1024;
constexpr int kMaxSkyRays = 256;

Error renderError(const std::string& message) {
    return Error(SourceLocation{}, message);
}

void checkOptions(const RaytraceOptions& o) {
    if (o.width <= 0 || o.height <= 0 || o.width > kMaxPixelSize || o.height > kMaxPixelSize)
        throw renderError("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                          " is out of range (1 to " + std::to_string(kMaxPixelSize) + " per side)");
    if (o.samplesPerPixel < 1 || o.samplesPerPixel > kMaxSamplesPerPixel)
        throw renderError("samples per pixel " + std::to_string(o.samplesPerPixel) +
                          " is out of range (1 to " + std::to_string(kMaxSamplesPerPixel) + ")");
    const Camera& c = o.camera;
    if (!(c.fieldOfView > 0 && c.fieldOfView < 180))
        throw renderError("field of view must be between 0 and 180 degrees (exclusive)");
    if (!isFinite(c.up) || length(c.up) == 0)
        throw renderError("the camera's up vector must be a finite, non-zero vector");
    if ((c.viewpoint && !isFinite(*c.viewpoint)) || (c.target && !isFinite(*c.target)))
        throw renderError("the camera's viewpoint and target must be finite points");
    const Lighting& l = o.lighting;
    if (!isFinite(l.sunDirection) || !std::isfinite(l.sunIntensity) ||
        !std::isfinite(l.skyIntensity) || l.sunIntensity < 0 || l.skyIntensity < 0)
        throw renderError("light direction and intensities must be finite, intensities >= 0");
    if (!(l.sunDiameterDegrees >= 0 && l.sunDiameterDegrees < 180))
        throw renderError("the sun's diameter must be at least 0 and under 180 degrees");
    if (l.skyRays < 0 || l.skyRays > kMaxSkyRays)
        throw renderError("sky rays " + std::to_string(l.skyRays) + " is out of range (0 to " +
                          std::to_string(kMaxSkyRays) + ")");
    if (!(o.minimumCurvePixels >= 0) || !std::isfinite(o.minimumCurvePixels))
        throw renderError("the curves' minimum width must be a finite number of pixels >= 0");
}

std::vector<unsigned char> renderPixels(const TracedScene& scene, const RaytraceOptions& options) {
    checkOptions(options);
    std::vector<unsigned char> pixels(static_cast<std::size_t>(options.width) * options.height * 3);
    if (scene.empty()) {
        // Nothing to see is a picture too (a plant that has not sprouted yet), but a broken
        // scene is an error whether it draws or not.
        checkScene(scene);
        fillBackground(pixels, options.background);
        return pixels;
    }

    const TracedScene one[] = {scene};
    const PointSource points = drawnPoints(one);
    Bounds bounds;
    points([&](const Vec3& p, double r) {
        bounds.extend(p - Vec3{r, r, r});
        bounds.extend(p + Vec3{r, r, r});
    });
    const Camera camera = frameCamera(options.camera, points, options.width, options.height);
    const View view = makeView(camera, points, options.width, options.height);
    const EmbreeScene embree(scene, view, options.minimumCurvePixels);
    renderPixels(embree, scene.palette(), view, bounds, options, pixels.data());
    embree.check("while tracing");
    return pixels;
}

void writePicture(const TracedScene& scene, const RaytraceOptions& options, const fs::path& path) {
    // Checked before the render: a wrong directory should not cost a minute of tracing.
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw fileError(path,
                        "cannot write image: '" + dir.string() +
                            (fs::exists(dir, ec) ? "' is not a directory" : "' does not exist"));

    std::vector<unsigned char> pixels;
    try {
        pixels = renderPixels(scene, options);
    } catch (const Error& e) {
        throw fileError(path, e.messages());
    }
    writeRgbaPng(RgbaImage::fromRgb(pixels, options.width, options.height), path);
}

}  // namespace

std::vector<unsigned char> renderRaytracedPixels(const Mesh& mesh, const RaytraceOptions& options) {
    return renderPixels(TracedScene::of(mesh), options);
}

void renderRaytraced(const Mesh& mesh, const RaytraceOptions& options, const fs::path& path) {
    writePicture(TracedScene::of(mesh), options, path);
}

std::vector<unsigned char> renderRaytracedPixels(const MeshScene& scene,
                                                 const RaytraceOptions& options) {
    return renderPixels(TracedScene::of(scene), options);
}

void renderRaytraced(const MeshScene& scene, const RaytraceOptions& options, const fs::path& path) {
    writePicture(TracedScene::of(scene), options, path);
}

}  // namespace graftal
