// Writers: one file per format under src/output/. Each takes a Scene and options.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/destination.hpp"
#include "graftal/core/file_format.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal {
struct Mesh;
struct MeshScene;
}  // namespace graftal

namespace graftal {

struct RenderOptions {
    int width = 800;  // pixels (PNG) or points (PDF, SVG user units)
    int height = 800;
    double margin = 0.05;  // fraction of the smaller side left free around the picture
    double lineWidth = 0;  // pixels for a width-1 segment; 0 picks one from the picture
    Rgb background{1, 1, 1};
    std::optional<Rgb> lineColor;  // overrides the palette for lines when set
    std::optional<Rgb> fillColor;  // overrides the palette for polygons when set
    bool antialias = true;
};

// The 2D projection used by every 2D writer: model (x, y) to image pixels with y down,
// uniformly scaled so the scene's bounds fit inside the margins, centred.
struct ImageTransform {
    double scale = 1, offsetX = 0, offsetY = 0;

    static ImageTransform fit(const Bounds& b, const RenderOptions& o);
    double x(const Vec3& p) const { return offsetX + scale * p.x; }
    double y(const Vec3& p) const { return offsetY - scale * p.y; }
};

// The line width in pixels a width-1 segment gets when RenderOptions::lineWidth is 0.
double defaultLineWidth(const Scene& scene, const RenderOptions& o);
// The same from totals a streamed first pass gathers: `ink` is the sum of inkLength().
double defaultLineWidth(double ink, bool anySegments, const Bounds& bounds, const RenderOptions& o);
// The stroke width in pixels of a width-1 segment of `scene` drawn with transform `t`: the
// transform's scale when the scene's widths are in model units (and no line width is
// requested), else defaultLineWidth() over the scene's base width.
double strokePixelsPerWidth(const Scene& scene, const RenderOptions& o, const ImageTransform& t);
// A segment's length times its width relative to `baseWidth`, in model units.
double inkLength(const Segment& s, float baseWidth);
// A stroke width in pixels as the 2D writers draw it: wider than the picture it only covers
// the picture, so it is capped at twice the picture's width plus height (a round cap of
// 1e12 pixels would otherwise take the rasteriser minutes and gigabytes).
double clampedStrokeWidth(double pixels, const RenderOptions& o);

// A 2D PNG drawn while the geometry streams in, never holding it: for strings too large
// to keep. The bounds, ink total and base width come from a first, measuring pass; the
// picture then matches writePng's for scenes whose segments share one colour and width
// and that have no polygons (writePng draws polygons first and groups strokes by width).
class StreamedPng {
  public:
    StreamedPng(const RenderOptions& o, const Bounds& bounds, double ink, bool anySegments,
                float baseWidth, std::vector<Rgb> palette, std::filesystem::path path);
    StreamedPng(const RenderOptions& o, const Bounds& bounds, double ink, bool anySegments,
                float baseWidth, std::vector<Rgb> palette, Destination destination);
    ~StreamedPng();
    StreamedPng(const StreamedPng&) = delete;
    StreamedPng& operator=(const StreamedPng&) = delete;

    void segment(const Segment& s);
    void polygon(std::span<const Vec3> vertices, std::uint16_t color);
    void finish();  // writes the file atomically; throws Error

    // The Cairo picture it draws into, made by the Cairo plugin in a shared build.
    struct Impl;

  private:
    std::unique_ptr<Impl> impl_;
};

void writeSvg(const Scene& scene, const RenderOptions& o, std::ostream& out);
void writePng(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path);
void writePdf(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path);
// The same into a stream; `name` names the output in errors.
void writePng(const Scene& scene, const RenderOptions& o, std::ostream& out,
              const std::filesystem::path& name);
void writePdf(const Scene& scene, const RenderOptions& o, std::ostream& out,
              const std::filesystem::path& name);

// 3D files of a mesh. Each writes atomically (temporary file, then rename) and throws Error.
void writeObj(const Mesh& mesh, const std::filesystem::path& path);  // + .mtl beside it
void writePly(const Mesh& mesh, const std::filesystem::path& path);  // binary, vertex colours
void writeGlb(const Mesh& mesh, const std::filesystem::path& path);  // glTF 2.0 binary

// How a GLB stores a scene's repeated organs and its buffers.
struct GlbOptions {
    // Prototypes placed with EXT_mesh_gpu_instancing; false copies every placement (for
    // viewers without the extension).
    bool instancing = true;
    // Vertex and index buffers compressed with EXT_meshopt_compression.
    bool compression = false;
};

// 3D files of an instanced scene (mesh_scene.hpp). OBJ and PLY have no instancing: they
// get every placement copied; curves are not written (build with curveRadius = 0).
void writeObj(const MeshScene& scene, const std::filesystem::path& path);
void writePly(const MeshScene& scene, const std::filesystem::path& path);
void writeGlb(const MeshScene& scene, const std::filesystem::path& path,
              const GlbOptions& options = {});
// The same to any destination. The OBJ names its materials by `mtl`'s file name (mtllib).
void writeObj(const Mesh& mesh, const Destination& obj, const Destination& mtl);
void writePly(const Mesh& mesh, const Destination& destination);
void writeObj(const MeshScene& scene, const Destination& obj, const Destination& mtl);
void writePly(const MeshScene& scene, const Destination& destination);
void writeGlb(const MeshScene& scene, const Destination& destination,
              const GlbOptions& options = {});

// The picture formats of the format table (file_format.hpp).
using ImageFormat = FileFormat;
// From the file name's extension (case-insensitive); nullopt for an unknown one and for a
// format that is not a picture.
std::optional<ImageFormat> imageFormatFor(const std::filesystem::path& path);

// Writes by extension, atomically: the picture goes to a temporary file beside `path`
// that is renamed into place only when complete, so a failure never leaves a partial
// file. Throws graftal::Error.
void writeImage(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path);
// The picture in `format` to any destination (a file is written atomically).
void writeImage(const Scene& scene, const RenderOptions& o, ImageFormat format,
                const Destination& destination);

}  // namespace graftal
