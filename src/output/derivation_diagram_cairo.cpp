// Painting a laid-out derivation diagram with Cairo, for PNG, PDF and an animation's frames:
// the same things in the same order as the SVG painter (derivation_diagram_writer.cpp).
#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <numbers>

#include "diagram_style.hpp"
#include "graftal/core/atomic_file.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/output/derivation_diagram.hpp"
#include "png_encoder.hpp"

namespace graftal {

using namespace diagram_style;

namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

Error cairoError(const std::filesystem::path& path, const std::string& what, cairo_status_t st) {
    return Error(SourceLocation{path.string(), 0, 0}, what + ": " + cairo_status_to_string(st));
}

void setSource(cairo_t* cr, const Rgb& c) {
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

// Writes `text` with its horizontal anchor at x: 0 left, 0.5 centre, 1 right.
void showText(cairo_t* cr, const std::string& text, double x, double baseline, double anchor) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, text.c_str(), &e);
    cairo_move_to(cr, x - anchor * e.x_advance, baseline);
    cairo_show_text(cr, text.c_str());
}

void roundedBox(cairo_t* cr, const DiagramCell& c) {
    const double r = std::min(kCornerRadius * c.height, c.width / 2);
    cairo_new_sub_path(cr);
    cairo_arc(cr, c.x + c.width - r, c.y + r, r, -std::numbers::pi / 2, 0);
    cairo_arc(cr, c.x + c.width - r, c.y + c.height - r, r, 0, std::numbers::pi / 2);
    cairo_arc(cr, c.x + r, c.y + c.height - r, r, std::numbers::pi / 2, std::numbers::pi);
    cairo_arc(cr, c.x + r, c.y + r, r, std::numbers::pi, 3 * std::numbers::pi / 2);
    cairo_close_path(cr);
}

void drawDiagram(cairo_t* cr, const DerivationDiagram& d) {
    setSource(cr, d.background);
    cairo_paint(cr);
    const double outline = std::max(1.0, d.labelSize / 14);
    for (const DiagramRow& row : d.rows) {
        cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, d.parameterSize * 1.2);
        setSource(cr, kStepInk);
        if (!row.gap)
            showText(cr, std::to_string(row.step), row.labelX, row.labelY + 0.4 * d.parameterSize,
                     1);
        for (const DiagramCell& c : row.cells) {
            roundedBox(cr, c);
            setSource(cr, c.fill);
            cairo_fill_preserve(cr);
            setSource(cr, kInk);
            cairo_set_line_width(cr, outline);
            if (c.ellipsis) {
                const double dash = 0.12 * c.height;
                cairo_set_dash(cr, &dash, 1, 0);
            }
            cairo_stroke(cr);
            cairo_set_dash(cr, nullptr, 0, 0);
            cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
            cairo_set_font_size(cr, d.labelSize);
            showText(cr, c.label, c.x + c.width / 2, labelBaseline(c, d.labelSize), 0.5);
            if (!c.parameters.empty()) {
                cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL,
                                       CAIRO_FONT_WEIGHT_NORMAL);
                cairo_set_font_size(cr, d.parameterSize);
                showText(cr, c.parameters, c.x + c.width / 2, parameterBaseline(c), 0.5);
            }
        }
    }
}

void checkSize(const DerivationDiagram& d, const std::filesystem::path& path, double limit) {
    if (!(d.width >= 1 && d.height >= 1 && d.width <= limit && d.height <= limit))
        throw Error(SourceLocation{path.string(), 0, 0},
                    "image size " + number(d.width) + "x" + number(d.height) +
                        " is out of range (1 to " + number(limit) + " per side)");
}

}  // namespace

void writeDerivationDiagramPng(const DerivationDiagram& d, const std::filesystem::path& path) {
    checkSize(d, path, 32767);
    SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(d.width),
                                                  static_cast<int>(d.height)),
                       &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(path, "cannot create the image", st);
    {
        ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        drawDiagram(cr.get(), d);
        if (auto st = cairo_status(cr.get()); st != CAIRO_STATUS_SUCCESS)
            throw cairoError(path, "cannot draw the derivation", st);
    }
    cairo_surface_flush(surface.get());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw fileError(path, "cannot open for writing");
    encodeArgbPng(cairo_image_surface_get_data(surface.get()), static_cast<int>(d.width),
                  static_cast<int>(d.height), cairo_image_surface_get_stride(surface.get()), out,
                  path.c_str());
    out.close();
    if (!out) throw fileError(path, "cannot write PNG: write failed");
}

RgbaImage drawDerivationDiagram(const DerivationDiagram& d) {
    checkSize(d, "derivation diagram", 16384);
    const int w = static_cast<int>(d.width), h = static_cast<int>(d.height);
    SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h),
                       &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError("derivation diagram", "cannot create the image", st);
    {
        ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        drawDiagram(cr.get(), d);
        if (auto st = cairo_status(cr.get()); st != CAIRO_STATUS_SUCCESS)
            throw cairoError("derivation diagram", "cannot draw the derivation", st);
    }
    cairo_surface_flush(surface.get());
    RgbaImage image(w, h);
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < h; ++y) {
        // ARGB32 is one native-endian word per pixel; the background is opaque, so the
        // premultiplied colours are the colours.
        const auto* row = reinterpret_cast<const std::uint32_t*>(data + std::size_t(y) * stride);
        for (int x = 0; x < w; ++x) {
            std::uint8_t* px = &image.pixels[(std::size_t(y) * w + x) * 4];
            px[0] = std::uint8_t(row[x] >> 16);
            px[1] = std::uint8_t(row[x] >> 8);
            px[2] = std::uint8_t(row[x]);
            px[3] = 255;
        }
    }
    return image;
}

void writeDerivationDiagramPdf(const DerivationDiagram& d, const std::filesystem::path& path) {
    checkSize(d, path, 14400);
    SurfacePtr surface(cairo_pdf_surface_create(path.c_str(), d.width, d.height),
                       &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(path, "cannot create PDF", st);
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "graftal");
    {
        ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
        drawDiagram(cr.get(), d);
        cairo_show_page(cr.get());
        if (auto st = cairo_status(cr.get()); st != CAIRO_STATUS_SUCCESS)
            throw cairoError(path, "cannot draw the derivation", st);
    }
    cairo_surface_finish(surface.get());
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw cairoError(path, "cannot write PDF", st);
}

}  // namespace graftal
