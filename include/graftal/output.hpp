// Writers: one file per format under src/output/. Each takes a Scene and options.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "graftal/scene.hpp"

namespace graftal {

struct RenderOptions {
    int width = 800;   // pixels (PNG) or points (PDF, SVG user units)
    int height = 800;
    double margin = 0.05;       // fraction of the smaller side left free around the picture
    double lineWidth = 0;       // pixels for a width-1 segment; 0 picks one from the picture
    Rgb background{1, 1, 1};
    std::optional<Rgb> lineColor;   // overrides the palette for lines when set
    std::optional<Rgb> fillColor;   // overrides the palette for polygons when set
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

void writeSvg(const Scene& scene, const RenderOptions& o, std::ostream& out);
void writePng(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path);
void writePdf(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path);

enum class ImageFormat { Svg, Png, Pdf };
// From the file name's extension (case-insensitive); nullopt for an unknown one.
std::optional<ImageFormat> imageFormatFor(const std::filesystem::path& path);

// Writes by extension, atomically: the picture goes to a temporary file beside `path`
// that is renamed into place only when complete, so a failure never leaves a partial
// file. Throws graftal::Error.
void writeImage(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path);

}  // namespace graftal
