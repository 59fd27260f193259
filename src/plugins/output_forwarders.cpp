// The output layer's writers that need Cairo, Embree, giflib, libwebp or FFmpeg, as
// libgraftal_output has them in a shared build: each loads its plugin on first use and calls
// the plugin's own definition (output_plugins.hpp). What they write is the plugin's; these
// only choose the plugin and name the format for its error.
#include "output_plugins.hpp"

namespace graftal {

namespace {

namespace fs = std::filesystem;
using plugins::plugin;

const plugins::CairoPlugin& cairo(std::string_view what) {
    return plugin<plugins::CairoPlugin>("cairo", what);
}
const plugins::RaytracePlugin& raytrace() {
    return plugin<plugins::RaytracePlugin>("raytrace", "a ray-traced picture (Embree)");
}

}  // namespace

// Cairo.
void writePng(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    cairo("a PNG picture (Cairo)").writePngFile(scene, o, path);
}
void writePdf(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    cairo("a PDF picture (Cairo)").writePdfFile(scene, o, path);
}
void writePng(const Scene& scene, const RenderOptions& o, std::ostream& out, const fs::path& name) {
    cairo("a PNG picture (Cairo)").writePngStream(scene, o, out, name);
}
void writePdf(const Scene& scene, const RenderOptions& o, std::ostream& out, const fs::path& name) {
    cairo("a PDF picture (Cairo)").writePdfStream(scene, o, out, name);
}
RgbaImage drawLineArt(const Scene& scene, const RenderOptions& o, const Bounds& frame) {
    return cairo("a picture in pixels (Cairo)").drawLineArt(scene, o, frame);
}
std::unique_ptr<StreamedPng::Impl> openStreamedPng(const RenderOptions& o, const Bounds& bounds,
                                                   double ink, bool anySegments, float baseWidth,
                                                   std::vector<Rgb> palette,
                                                   Destination destination) {
    return cairo("a PNG picture (Cairo)")
        .openStreamedPng(o, bounds, ink, anySegments, baseWidth, std::move(palette),
                         std::move(destination));
}
RgbaImage drawDerivationDiagram(const DerivationDiagram& d) {
    return cairo("a derivation diagram in pixels (Cairo)").drawDerivationDiagram(d);
}
void writeDerivationDiagramPng(const DerivationDiagram& d, const fs::path& path) {
    cairo("a PNG derivation diagram (Cairo)").writeDerivationDiagramPng(d, path);
}
void writeDerivationDiagramPdf(const DerivationDiagram& d, const fs::path& path) {
    cairo("a PDF derivation diagram (Cairo)").writeDerivationDiagramPdf(d, path);
}
std::unique_ptr<AnimationEncoder> openPngFramesEncoder(const fs::path& folder,
                                                       const AnimationEncoding& encoding) {
    return cairo("a folder of PNG frames (Cairo)").openPngFramesEncoder(folder, encoding);
}
void writeRgbaPng(const RgbaImage& image, const fs::path& path) {
    writeRgbaPng(image, Destination::file(path));
}
void writeRgbaPng(const RgbaImage& image, const Destination& destination) {
    cairo("a PNG picture (Cairo)").writeRgbaPng(image, destination);
}

// Embree.
void renderRaytraced(const Mesh& mesh, const RaytraceOptions& options, const fs::path& path) {
    raytrace().renderMesh(mesh, options, path);
}
std::vector<unsigned char> renderRaytracedPixels(const Mesh& mesh, const RaytraceOptions& options) {
    return raytrace().meshPixels(mesh, options);
}
void renderRaytraced(const MeshScene& scene, const RaytraceOptions& options, const fs::path& path) {
    raytrace().renderScene(scene, options, path);
}
std::vector<unsigned char> renderRaytracedPixels(const MeshScene& scene,
                                                 const RaytraceOptions& options) {
    return raytrace().scenePixels(scene, options);
}

// giflib, libwebp, FFmpeg.
std::unique_ptr<AnimationEncoder> openGifEncoder(const fs::path& file,
                                                 const AnimationEncoding& encoding) {
    return plugin<plugins::AnimationPlugin>("animation", "an animated GIF (giflib)")
        .openGifEncoder(file, encoding);
}
std::unique_ptr<AnimationEncoder> openWebPEncoder(const fs::path& file,
                                                  const AnimationEncoding& encoding) {
    return plugin<plugins::AnimationPlugin>("animation", "an animated WebP (libwebp)")
        .openWebPEncoder(file, encoding);
}
std::unique_ptr<AnimationEncoder> openMp4Encoder(const fs::path& file,
                                                 const AnimationEncoding& encoding) {
    return plugin<plugins::VideoPlugin>("video", "an MP4 video (FFmpeg)")
        .openMp4Encoder(file, encoding);
}

}  // namespace graftal
