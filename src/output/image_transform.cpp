#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "graftal/output/output.hpp"

namespace graftal {

namespace {

// Below this a stroke disappears into antialiasing haze, whatever the density.
constexpr double kMinAutoLineWidth = 0.25;
// Fraction of the drawing area the lines may cover (estimated as total length x width)
// before the automatic width starts to shrink.
constexpr double kMaxInkCoverage = 0.35;

struct Area {
    double width, height;
};

// The part of the image the picture may use: the image minus the margin on every side,
// never less than a pixel so that a silly margin cannot produce a zero or negative scale.
Area drawingArea(const RenderOptions& o) {
    const double w = o.width, h = o.height;
    const double m = o.margin * std::min(w, h);
    return {std::max(w - 2 * m, 1.0), std::max(h - 2 * m, 1.0)};
}

}  // namespace

ImageTransform ImageTransform::fit(const Bounds& b, const RenderOptions& o) {
    ImageTransform t;
    const double cxImage = o.width / 2.0, cyImage = o.height / 2.0;
    if (b.empty()) {
        t.offsetX = cxImage;
        t.offsetY = cyImage;
        return t;
    }
    const Area area = drawingArea(o);
    const double dx = b.max.x - b.min.x, dy = b.max.y - b.min.y;
    // A zero extent imposes no limit on the scale in that direction; only when both are
    // zero (a single point) is there nothing to fit and the scale stays 1.
    double scale = 1;
    if (dx > 0 && dy > 0)
        scale = std::min(area.width / dx, area.height / dy);
    else if (dx > 0)
        scale = area.width / dx;
    else if (dy > 0)
        scale = area.height / dy;
    // Extents of 1e-320 or 1e308 would give an infinite or zero scale.
    if (!std::isfinite(scale) || scale <= 0) scale = 1;
    t.scale = scale;

    const double cx = b.min.x / 2 + b.max.x / 2, cy = b.min.y / 2 + b.max.y / 2;
    t.offsetX = cxImage - scale * cx;
    t.offsetY = cyImage + scale * cy;  // model y up, image y down
    if (!std::isfinite(t.offsetX) || !std::isfinite(t.offsetY)) {
        t.scale = 1;
        t.offsetX = cxImage;
        t.offsetY = cyImage;
    }
    return t;
}

// The base width grows with the image (1/600 of the smaller side, between 0.6 and 2 px)
// so that a poster-sized PNG does not look spidery and a thumbnail does not look blotched.
// Dense pictures (a high-order Hilbert curve, a bush of a million twigs) would turn into a
// solid blob at that width, so when total line length x width would ink more than
// kMaxInkCoverage of the drawing area the width shrinks in proportion, down to
// kMinAutoLineWidth. Sparse pictures, which are most of them, keep the base width.
double inkLength(const Segment& s, float baseWidth) {
    const double len = std::hypot(s.b.x - s.a.x, s.b.y - s.a.y);
    const double w = s.width > 0 && baseWidth > 0 ? s.width / baseWidth : 0;
    return std::isfinite(len) ? len * w : 0;
}

double clampedStrokeWidth(double pixels, const RenderOptions& o) {
    const double limit = 2.0 * (std::max(o.width, 1) + std::max(o.height, 1));
    return pixels < limit ? pixels : limit;
}

double defaultLineWidth(const Scene& scene, const RenderOptions& o) {
    double ink = 0;
    for (const Segment& s : scene.segments) ink += inkLength(s, scene.baseWidth);
    return defaultLineWidth(ink, !scene.segments.empty(), scene.bounds(), o);
}

double strokePixelsPerWidth(const Scene& scene, const RenderOptions& o, const ImageTransform& t) {
    if (scene.widthsInModelUnits && !(o.lineWidth > 0)) return t.scale;
    // Segment widths are relative to the scene's base width in 2D line art.
    return defaultLineWidth(scene, o) / (scene.baseWidth > 0 ? scene.baseWidth : 1);
}

double defaultLineWidth(double ink, bool anySegments, const Bounds& bounds,
                        const RenderOptions& o) {
    if (o.lineWidth > 0) return o.lineWidth;
    const double base = std::clamp(std::min(o.width, o.height) / 600.0, 0.6, 2.0);
    if (!anySegments) return base;
    const ImageTransform t = ImageTransform::fit(bounds, o);
    const double inkLength = ink * t.scale;  // sum of length x relative width, in pixels
    const Area area = drawingArea(o);
    const double coverage = inkLength * base / (area.width * area.height);
    if (!(coverage > kMaxInkCoverage)) return base;
    return std::max(base * kMaxInkCoverage / coverage, kMinAutoLineWidth);
}

std::optional<ImageFormat> imageFormatFor(const std::filesystem::path& path) {
    const std::optional<FileFormat> format = fileFormatFor(path);
    if (!format || fileFormatInfo(*format).kind != FormatKind::Picture) return std::nullopt;
    return format;
}

}  // namespace graftal
