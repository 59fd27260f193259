// SVG output. Polygons are drawn first and segments on top: the scene keeps them in two
// separate arrays, so their interleaving in turtle order is not available, and lines on top
// of leaves is what plant pictures want (a leaf must not hide the stem it hangs from).
//
// Coordinates are rounded to 1/100 pixel and kept as integers, which makes the output
// compact, locale-independent and free of accumulated error when written as relative moves.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/output/output.hpp"
#include "stroke_order.hpp"

namespace graftal {

namespace {

// Beyond this (in pixels) a point is off any sane picture; skipping it keeps the integer
// conversion below defined.
constexpr double kMaxCoordinate = 1e9;
// Points per line of path data: keeps files diffable and friendly to line-based tools.
constexpr int kPointsPerLine = 10;
// Segments per <path> element. libxml2 (behind xmllint, older rsvg and Inkscape) gives up
// on documents over 10 MB unless it gets to discard parsed input between elements, which it
// rarely manages next to attribute values of a megabyte; paths of tens of kilobytes keep it
// happy. A cut is invisible: round caps meeting at a point cover what the round join did.
// Curves up to a Koch curve of level 6 (4096 segments) still come out as one path.
constexpr int kSegmentsPerPath = 5000;
// Flush the text buffer to the stream in blocks of about this size.
constexpr std::size_t kFlushSize = 1 << 16;

struct Fixed {  // a point in 1/100 pixel
    std::int64_t x, y;
    friend bool operator==(const Fixed&, const Fixed&) = default;
};

bool toFixed(const ImageTransform& t, const Vec3& p, Fixed& out) {
    const double x = t.x(p), y = t.y(p);
    if (!(std::abs(x) < kMaxCoordinate) || !(std::abs(y) < kMaxCoordinate)) return false;
    out = {std::llround(x * 100), std::llround(y * 100)};
    return true;
}

void appendInt(std::string& s, std::uint64_t v) {
    char buf[24];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    s.append(buf, r.ptr);
}

// Writes v / 10^decimals with trailing zeros (and a bare point) dropped.
void appendScaled(std::string& s, std::int64_t v, int decimals) {
    std::uint64_t unit = 1;
    for (int i = 0; i < decimals; ++i) unit *= 10;
    // The magnitude in unsigned arithmetic: -INT64_MIN does not fit an int64_t.
    std::uint64_t m = static_cast<std::uint64_t>(v);
    if (v < 0) {
        s += '-';
        m = 0 - m;
    }
    appendInt(s, m / unit);
    std::uint64_t frac = m % unit;
    if (frac == 0) return;
    s += '.';
    for (std::uint64_t d = unit / 10; d > 0 && frac > 0; d /= 10) {
        s += static_cast<char>('0' + frac / d);
        frac %= d;
    }
}

void appendCenti(std::string& s, std::int64_t v) {
    appendScaled(s, v, 2);
}

void appendPair(std::string& s, std::int64_t x, std::int64_t y) {
    appendCenti(s, x);
    s += ' ';
    appendCenti(s, y);
}

class SvgText {
  public:
    explicit SvgText(std::ostream& out) : out_(out) { text_.reserve(kFlushSize * 2); }

    std::string& text() { return text_; }
    void maybeFlush() {
        if (text_.size() >= kFlushSize) flush();
    }
    void flush() {
        out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
        text_.clear();
    }

  private:
    std::ostream& out_;
    std::string text_;
};

void writePolygons(const Scene& scene, const RenderOptions& o, const ImageTransform& t,
                   SvgText& svg) {
    std::string& s = svg.text();
    bool groupOpen = false;
    std::vector<Fixed> points;
    for (std::size_t k = 0; k < scene.polygonCount(); ++k) {
        points.clear();
        bool ok = true;
        for (const Vec3& v : scene.polygon(k)) {
            Fixed f;
            if (!toFixed(t, v, f)) {
                ok = false;
                break;
            }
            points.push_back(f);
        }
        if (!ok || points.size() < 3) continue;  // nothing to fill
        if (!groupOpen) {
            s += "<g stroke=\"none\">\n";
            groupOpen = true;
        }
        s += "<path fill=\"";
        s += hexColor(o.fillColor ? *o.fillColor : scene.colorOf(scene.polygonColor[k]));
        s += "\" d=\"M";
        appendPair(s, points[0].x, points[0].y);
        s += 'l';
        for (std::size_t i = 1; i < points.size(); ++i) {
            if (i > 1) s += (i - 1) % kPointsPerLine == 0 ? '\n' : ' ';
            appendPair(s, points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
        }
        s += "z\"/>\n";
        svg.maybeFlush();
    }
    if (groupOpen) s += "</g>\n";
}

// One <path> per run of segments with the same colour and width; inside it a new subpath
// (M) only where a segment does not start at the previous one's end, so a connected curve
// of any length is a single M followed by relative moves.
void writeSegments(const Scene& scene, const RenderOptions& o, const ImageTransform& t,
                   SvgText& svg) {
    std::string& s = svg.text();
    const double lineWidth = strokePixelsPerWidth(scene, o, t);
    bool groupOpen = false;
    bool pathOpen = false;     // a <path> element has been started and not closed
    bool subpathOpen = false;  // that path has a subpath ending at `last`
    std::string pathColor;
    float pathWidth = 0;
    int inPath = 0;  // segments written to the open <path>
    Fixed last{0, 0};
    int pointsOnLine = 0;

    for (std::uint32_t index : strokeOrder(scene, o)) {
        const Segment& seg = scene.segments[index];
        if (!(seg.width > 0) || !std::isfinite(seg.width)) continue;  // invisible
        Fixed a, b;
        if (!toFixed(t, seg.a, a) || !toFixed(t, seg.b, b)) continue;
        std::string color = hexColor(o.lineColor ? *o.lineColor : scene.colorOf(seg.color));

        if (!pathOpen || color != pathColor || seg.width != pathWidth ||
            inPath >= kSegmentsPerPath) {
            if (pathOpen) s += "\"/>\n";
            if (!groupOpen) {
                s += "<g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
                groupOpen = true;
            }
            pathColor = std::move(color);
            pathWidth = seg.width;
            s += "<path stroke=\"";
            s += pathColor;
            s += "\" stroke-width=\"";
            appendScaled(s, std::llround(clampedStrokeWidth(lineWidth * seg.width, o) * 1000), 3);
            s += "\" d=\"";
            pathOpen = true;
            subpathOpen = false;
            inPath = 0;
        }

        if (subpathOpen && a == last) {
            if (b == a) continue;  // a dot on the line being drawn adds nothing
            s += ++pointsOnLine % kPointsPerLine == 0 ? '\n' : ' ';
        } else {
            // "M x y l" starts a subpath; the pairs after it are implicit relative line-tos.
            // A zero-length first segment is kept: with round caps it draws a dot.
            if (subpathOpen) s += '\n';
            s += 'M';
            appendPair(s, a.x, a.y);
            s += 'l';
            subpathOpen = true;
            pointsOnLine = 0;
        }
        appendPair(s, b.x - a.x, b.y - a.y);
        last = b;
        ++inPath;
        svg.maybeFlush();
    }
    if (pathOpen) s += "\"/>\n";
    if (groupOpen) s += "</g>\n";
}

}  // namespace

void writeSvg(const Scene& scene, const RenderOptions& o, std::ostream& out) {
    if (o.width <= 0 || o.height <= 0)
        throw Error(SourceLocation{}, "image size must be positive, not " +
                                          std::to_string(o.width) + "x" + std::to_string(o.height));
    const ImageTransform t = ImageTransform::fit(scene.bounds(), o);
    SvgText svg(out);
    std::string& s = svg.text();
    const std::string w = std::to_string(o.width), h = std::to_string(o.height);
    s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + w + "\" height=\"" +
         h + "\" viewBox=\"0 0 " + w + " " + h + "\">\n";
    s += "<rect x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h + "\" fill=\"" +
         hexColor(o.background) + "\"/>\n";
    writePolygons(scene, o, t, svg);
    writeSegments(scene, o, t, svg);
    s += "</svg>\n";
    svg.flush();
    out.flush();
    if (!out) throw Error(SourceLocation{}, "cannot write SVG: output stream failed");
}

}  // namespace graftal
