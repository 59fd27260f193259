// A PNG drawn as the geometry streams in (see output.hpp). Segments are stroked in runs of
// one colour and width, connected runs as one path, as writePng does, so the two agree.
#include <cairo.h>

#include <cmath>

#include "graftal/core/diagnostics.hpp"
#include "graftal/output/output.hpp"
#include "png_encoder.hpp"
#include "streamed_png.hpp"

namespace graftal {

namespace {
constexpr int kSegmentsPerStroke = 50;  // as in cairo_writer.cpp: long paths stroke slowly
constexpr double kMaxCoordinate = 4e6;  // Cairo's fixed point wraps beyond this

class CairoStreamedPng final : public StreamedPng::Impl {
  public:
    CairoStreamedPng(const RenderOptions& o, const Bounds& bounds, double ink, bool anySegments,
                     float base, std::vector<Rgb> colors, Destination out);
    ~CairoStreamedPng() override;
    void segment(const Segment& s) override;
    void polygon(std::span<const Vec3> vertices, std::uint16_t color) override;
    void finish() override;

  private:
    RenderOptions options;
    ImageTransform transform;
    double lineWidth = 1;
    float baseWidth = 1;
    std::vector<Rgb> palette;
    Destination destination = Destination::file({});
    std::filesystem::path path;  // the destination's name, for messages
    cairo_surface_t* surface = nullptr;
    cairo_t* cr = nullptr;
    int inPath = 0;
    Rgb runColor;
    float runWidth = 0;
    double lastX = 0, lastY = 0;

    Rgb colorOf(std::uint16_t c) const {
        if (palette.empty()) return {0, 0, 0};
        return palette[c % palette.size()];
    }
    void stroke() {
        if (inPath > 0) cairo_stroke(cr);
        inPath = 0;
    }
};

CairoStreamedPng::CairoStreamedPng(const RenderOptions& o, const Bounds& bounds, double ink,
                                   bool anySegments, float base, std::vector<Rgb> colors,
                                   Destination out) {
    CairoStreamedPng& m = *this;
    m.options = o;
    m.transform = ImageTransform::fit(bounds, o);
    m.baseWidth = base > 0 ? base : 1;
    m.lineWidth = defaultLineWidth(ink, anySegments, bounds, o) / m.baseWidth;
    m.palette = std::move(colors);
    m.path = out.path();
    m.destination = std::move(out);
    if (o.width < 1 || o.height < 1 || o.width > 32767 || o.height > 32767)
        throw Error(SourceLocation{m.path.string(), 0, 0},
                    "image size out of range (1 to 32767 per side)");
    m.surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, o.width, o.height);
    m.cr = cairo_create(m.surface);
    cairo_set_antialias(m.cr, o.antialias ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
    cairo_set_source_rgb(m.cr, o.background.r, o.background.g, o.background.b);
    cairo_paint(m.cr);
    cairo_set_fill_rule(m.cr, CAIRO_FILL_RULE_WINDING);
    cairo_set_line_cap(m.cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(m.cr, CAIRO_LINE_JOIN_ROUND);
}

CairoStreamedPng::~CairoStreamedPng() {
    if (cr) cairo_destroy(cr);
    if (surface) cairo_surface_destroy(surface);
}

void CairoStreamedPng::segment(const Segment& s) {
    CairoStreamedPng& m = *this;
    if (!(s.width > 0)) return;
    double ax = m.transform.x(s.a), ay = m.transform.y(s.a);
    double bx = m.transform.x(s.b), by = m.transform.y(s.b);
    if (!(std::abs(ax) < kMaxCoordinate && std::abs(ay) < kMaxCoordinate &&
          std::abs(bx) < kMaxCoordinate && std::abs(by) < kMaxCoordinate))
        return;
    Rgb color = m.options.lineColor ? *m.options.lineColor : m.colorOf(s.color);
    if (m.inPath > 0 &&
        (!(color == m.runColor) || s.width != m.runWidth || m.inPath >= kSegmentsPerStroke))
        m.stroke();
    if (m.inPath == 0) {
        m.runColor = color;
        m.runWidth = s.width;
        cairo_set_source_rgb(m.cr, color.r, color.g, color.b);
        cairo_set_line_width(m.cr, clampedStrokeWidth(m.lineWidth * s.width, m.options));
    }
    if (m.inPath == 0 || ax != m.lastX || ay != m.lastY) cairo_move_to(m.cr, ax, ay);
    cairo_line_to(m.cr, bx, by);
    m.lastX = bx;
    m.lastY = by;
    ++m.inPath;
}

void CairoStreamedPng::polygon(std::span<const Vec3> vertices, std::uint16_t color) {
    CairoStreamedPng& m = *this;
    m.stroke();
    Rgb c = m.options.fillColor ? *m.options.fillColor : m.colorOf(color);
    cairo_set_source_rgb(m.cr, c.r, c.g, c.b);
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        double x = m.transform.x(vertices[i]), y = m.transform.y(vertices[i]);
        if (i == 0)
            cairo_move_to(m.cr, x, y);
        else
            cairo_line_to(m.cr, x, y);
    }
    cairo_close_path(m.cr);
    cairo_fill(m.cr);
}

void CairoStreamedPng::finish() {
    CairoStreamedPng& m = *this;
    m.stroke();
    if (auto st = cairo_status(m.cr); st != CAIRO_STATUS_SUCCESS)
        throw Error(SourceLocation{m.path.string(), 0, 0},
                    std::string("cannot draw the picture: ") + cairo_status_to_string(st));
    cairo_surface_flush(m.surface);
    m.destination.write("PNG", [&](std::ostream& out) {
        encodeArgbPng(cairo_image_surface_get_data(m.surface),
                      cairo_image_surface_get_width(m.surface),
                      cairo_image_surface_get_height(m.surface),
                      cairo_image_surface_get_stride(m.surface), out, m.path.c_str());
    });
}

}  // namespace

std::unique_ptr<StreamedPng::Impl> openStreamedPng(const RenderOptions& o, const Bounds& bounds,
                                                   double ink, bool anySegments, float baseWidth,
                                                   std::vector<Rgb> palette,
                                                   Destination destination) {
    return std::make_unique<CairoStreamedPng>(o, bounds, ink, anySegments, baseWidth,
                                              std::move(palette), std::move(destination));
}

}  // namespace graftal
