// PNG and PDF output through Cairo. Both draw with drawScene so they look the same, and the
// same as the SVG writer: background, then polygons, then segments on top (the scene keeps
// polygons and segments apart, so turtle order between the two is not available).
#include <cairo-pdf.h>
#include <cairo.h>
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/output.hpp"
#include "png_encoder.hpp"
#include "stroke_order.hpp"

namespace graftal {

namespace {

// Cairo's image surfaces are limited to 32767 pixels a side.
constexpr int kMaxPixelSize = 32767;
// Cairo stores coordinates in 24.8 fixed point; farther out they wrap around. Such points
// are off the picture anyway, so they are skipped.
constexpr double kMaxCoordinate = 4e6;
// Segments per cairo_stroke. The stroker and rasteriser cost grows faster than linearly
// with path length (every edge is sorted against every other), so one huge stroke for a
// million-segment curve is slower than many short ones (a curve that crosses itself at every
// pixel strokes four times faster in runs of 50 than of 2000). Breaking a run is invisible: with
// round caps and round joins, two caps meeting at a point cover exactly what the join did.
constexpr int kSegmentsPerStroke = 50;

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// The pixels of a picture (a PNG, an animation's frame), mapped with their pages already in
// place. Cairo's own surface takes them from malloc, and painting the background then
// faults them in one page at a time: an 800 x 800 picture is 625 faults, a quarter of the
// time of `graftal render` on a small model on a virtual machine, where a fault costs tens
// of microseconds. One mmap with MAP_POPULATE maps them all in one call. Empty where that
// fails; the surface then has Cairo's own memory.
class PopulatedPixels {
  public:
    PopulatedPixels(int width, int height) {
#ifdef MAP_POPULATE
        stride_ = cairo_format_stride_for_width(CAIRO_FORMAT_ARGB32, width);
        if (stride_ <= 0) return;
        bytes_ = static_cast<std::size_t>(stride_) * static_cast<std::size_t>(height);
        void* p = ::mmap(nullptr, bytes_, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (p != MAP_FAILED) data_ = static_cast<unsigned char*>(p);
#endif
    }
    ~PopulatedPixels() {
        if (data_) ::munmap(data_, bytes_);
    }
    PopulatedPixels(const PopulatedPixels&) = delete;
    PopulatedPixels& operator=(const PopulatedPixels&) = delete;

    // An image surface on these pixels (or on Cairo's own); destroy it before this.
    cairo_surface_t* surface(int width, int height) const {
        return data_ ? cairo_image_surface_create_for_data(data_, CAIRO_FORMAT_ARGB32, width,
                                                           height, stride_)
                     : cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
    }

  private:
    unsigned char* data_ = nullptr;
    std::size_t bytes_ = 0;
    int stride_ = 0;
};

Error cairoError(const std::filesystem::path& path, const std::string& what,
                 cairo_status_t status) {
    return Error(SourceLocation{path.string(), 0, 0}, what + ": " + cairo_status_to_string(status));
}

void checkSize(const RenderOptions& o, const std::filesystem::path& path, int limit) {
    if (o.width <= 0 || o.height <= 0 || o.width > limit || o.height > limit)
        throw Error(SourceLocation{path.string(), 0, 0},
                    "image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                        " is out of range (1 to " + std::to_string(limit) + " per side)");
}

bool drawable(double x, double y) {
    return std::abs(x) < kMaxCoordinate && std::abs(y) < kMaxCoordinate;  // false for NaN
}

void setSource(cairo_t* cr, const Rgb& c) {
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

void fillPolygons(cairo_t* cr, const Scene& scene, const RenderOptions& o,
                  const ImageTransform& t) {
    for (std::size_t k = 0; k < scene.polygonCount(); ++k) {
        const auto vertices = scene.polygon(k);
        if (vertices.size() < 3) continue;  // nothing to fill
        bool ok = true;
        for (const Vec3& v : vertices) ok = ok && drawable(t.x(v), t.y(v));
        if (!ok) continue;
        // One fill per polygon: merging same-coloured polygons into one path would let
        // overlapping ones of opposite winding cancel out under the nonzero rule.
        cairo_new_path(cr);
        cairo_move_to(cr, t.x(vertices[0]), t.y(vertices[0]));
        for (std::size_t i = 1; i < vertices.size(); ++i)
            cairo_line_to(cr, t.x(vertices[i]), t.y(vertices[i]));
        cairo_close_path(cr);
        setSource(cr, o.fillColor ? *o.fillColor : scene.colorOf(scene.polygonColor[k]));
        cairo_fill(cr);
    }
}

// Segments are stroked in runs of equal colour and width, each run one path that only
// moves (move_to) where a segment does not start at the previous one's end: a connected
// curve then gets proper round joins and costs one stroke per kSegmentsPerStroke segments.
void strokeSegments(cairo_t* cr, const Scene& scene, const RenderOptions& o,
                    const ImageTransform& t) {
    const double lineWidth = strokePixelsPerWidth(scene, o, t);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_new_path(cr);

    int inPath = 0;  // segments in the current path; 0 means no path
    Rgb runColor;
    float runWidth = 0;
    double lastX = 0, lastY = 0;
    for (std::uint32_t index : strokeOrder(scene, o)) {
        const Segment& seg = scene.segments[index];
        if (!(seg.width > 0) || !std::isfinite(seg.width)) continue;  // invisible
        const double ax = t.x(seg.a), ay = t.y(seg.a), bx = t.x(seg.b), by = t.y(seg.b);
        if (!drawable(ax, ay) || !drawable(bx, by)) continue;
        const Rgb color = o.lineColor ? *o.lineColor : scene.colorOf(seg.color);

        if (inPath > 0 &&
            (color != runColor || seg.width != runWidth || inPath >= kSegmentsPerStroke)) {
            cairo_stroke(cr);
            inPath = 0;
        }
        if (inPath == 0) {
            runColor = color;
            runWidth = seg.width;
            setSource(cr, color);
            cairo_set_line_width(cr, clampedStrokeWidth(lineWidth * seg.width, o));
        }
        if (inPath == 0 || ax != lastX || ay != lastY) cairo_move_to(cr, ax, ay);
        cairo_line_to(cr, bx, by);
        lastX = bx;
        lastY = by;
        ++inPath;
    }
    if (inPath > 0) cairo_stroke(cr);
}

// Draws the whole picture in a width x height user space (pixels or points), with `frame`
// fitted into it.
void drawScene(cairo_t* cr, const Scene& scene, const RenderOptions& o, const Bounds& frame) {
    const ImageTransform t = ImageTransform::fit(frame, o);
    cairo_set_antialias(cr, o.antialias ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
    setSource(cr, o.background);
    cairo_paint(cr);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
    fillPolygons(cr, scene, o, t);
    strokeSegments(cr, scene, o, t);
}

}  // namespace

namespace {

// Cairo's write callback into a std::ostream.
cairo_status_t writeToStream(void* closure, const unsigned char* data, unsigned int length) {
    auto* out = static_cast<std::ostream*>(closure);
    out->write(reinterpret_cast<const char*>(data), length);
    return *out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

}  // namespace

void writePng(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path) {
    writeStreamAtomically(
        path, [&](std::ostream& out) { writePng(scene, o, out, path); }, "PNG");
}

void writePdf(const Scene& scene, const RenderOptions& o, const std::filesystem::path& path) {
    writeStreamAtomically(
        path, [&](std::ostream& out) { writePdf(scene, o, out, path); }, "PDF");
}

void writePng(const Scene& scene, const RenderOptions& o, std::ostream& out,
              const std::filesystem::path& path) {
    checkSize(o, path, kMaxPixelSize);
    const PopulatedPixels pixels(o.width, o.height);
    SurfacePtr surface(pixels.surface(o.width, o.height), &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(path,
                         "cannot create a " + std::to_string(o.width) + "x" +
                             std::to_string(o.height) + " image",
                         st);
    {
        ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        drawScene(cr.get(), scene, o, scene.bounds());
        if (auto st = cairo_status(cr.get()); st != CAIRO_STATUS_SUCCESS)
            throw cairoError(path, "cannot draw the picture", st);
    }
    cairo_surface_flush(surface.get());
    encodeArgbPng(cairo_image_surface_get_data(surface.get()), o.width, o.height,
                  cairo_image_surface_get_stride(surface.get()), out, path.c_str());
}

RgbaImage drawLineArt(const Scene& scene, const RenderOptions& o, const Bounds& frame) {
    const std::filesystem::path memory("image in memory");
    checkSize(o, memory, kMaxPixelSize);
    const PopulatedPixels pixels(o.width, o.height);
    SurfacePtr surface(pixels.surface(o.width, o.height), &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(memory,
                         "cannot create a " + std::to_string(o.width) + "x" +
                             std::to_string(o.height) + " image",
                         st);
    {
        ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        drawScene(cr.get(), scene, o, frame);
        if (auto st = cairo_status(cr.get()); st != CAIRO_STATUS_SUCCESS)
            throw cairoError(memory, "cannot draw the picture", st);
    }
    cairo_surface_flush(surface.get());
    RgbaImage image(o.width, o.height);
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < o.height; ++y) {
        // The background is opaque, so no pixel needs un-premultiplying.
        const auto* row = reinterpret_cast<const std::uint32_t*>(data + std::size_t(y) * stride);
        std::uint8_t* out = &image.pixels[std::size_t(y) * o.width * 4];
        for (int x = 0; x < o.width; ++x) {
            out[4 * x] = std::uint8_t(row[x] >> 16);
            out[4 * x + 1] = std::uint8_t(row[x] >> 8);
            out[4 * x + 2] = std::uint8_t(row[x]);
            out[4 * x + 3] = std::uint8_t(row[x] >> 24);
        }
    }
    return image;
}

void writePdf(const Scene& scene, const RenderOptions& o, std::ostream& out,
              const std::filesystem::path& path) {
    // PDF viewers refuse pages over 200 inches (14400 points) a side.
    checkSize(o, path, 14400);
    SurfacePtr surface(cairo_pdf_surface_create_for_stream(writeToStream, &out, o.width, o.height),
                       &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(path, "cannot create PDF", st);
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "graftal");
    {
        ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        drawScene(cr.get(), scene, o, scene.bounds());
        cairo_show_page(cr.get());
        if (auto st = cairo_status(cr.get()); st != CAIRO_STATUS_SUCCESS)
            throw cairoError(path, "cannot draw the picture", st);
    }
    // The file is only complete (and write errors only known) once the surface finishes.
    cairo_surface_finish(surface.get());
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(path, "cannot write PDF", st);
}

}  // namespace graftal
