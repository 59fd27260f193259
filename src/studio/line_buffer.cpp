// The line buffer, from a Scene or straight from the turtle's polylines: both fill the
// same quantized polylines, and one writer lays out the bytes.
#include "graftal/studio/line_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/output/output.hpp"

namespace graftal::studio {

namespace {

template <typename T>
void appendRaw(std::string& out, const T* data, std::size_t count) {
    out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

// R, G, B, A bytes in memory order (a little-endian uint32).
std::uint32_t rgbaBytes(const Rgb& c) {
    auto byte = [](double v) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
    };
    return byte(c.r) | byte(c.g) << 8 | byte(c.b) << 16 | 0xFF000000u;
}

// The segments as polylines: each point once, as 16-bit fractions of the bounding box
// (a 65536th of the picture is far below a pixel until zoomed 80 times), and runs of
// links sharing a width and a colour. A turtle's path is mostly joined, so a flat segment
// costs 4 bytes and a few per run instead of two end points each; bytes are what it costs
// to move a picture into the page.
class QuantizedPolylines {
  public:
    QuantizedPolylines(const Bounds& b, bool is3D, float maxWidth, std::size_t paletteSize,
                       std::size_t pointsAbout)
        : dims_(is3D ? 3 : 2), paletteSize_(paletteSize) {
        const bool empty = b.empty();
        origin_ = empty ? Vec3{} : b.min;
        size_ = empty ? Vec3{} : b.max - b.min;
        auto quantizer = [](double extent) { return extent > 0 ? 65535.0 / extent : 0.0; };
        qx_ = quantizer(size_.x), qy_ = quantizer(size_.y), qz_ = quantizer(size_.z);
        widthScale_ = maxWidth > 0 ? 65535.0 / maxWidth : 0.0;
        maxWidth_ = maxWidth;
        points_.reserve(dims_ * pointsAbout);
    }

    // The first point, or the start of a segment: a jump unless it is where the pen is.
    void moveTo(const Vec3& p) {
        std::uint16_t from[3];
        quantize(p, from);
        if (!points_.empty() && std::equal(from, from + dims_, last_)) return;
        if (!points_.empty()) link(1, 0, kJump);
        put(from);
    }
    // `links` segments drawn with `width` and `color` through the next points.
    void drawTo(const Vec3* points, std::size_t links, float width, std::uint16_t color) {
        link(static_cast<std::uint32_t>(links), q(width, widthScale_),
             static_cast<std::uint16_t>(color % paletteSize_));
        for (std::size_t k = 0; k < links; ++k) {
            std::uint16_t to[3];
            quantize(points[k], to);
            put(to);
        }
    }

    std::string write(const Scene& rest, std::size_t segments, const Bounds& b, double ink) const;

  private:
    struct Run {
        std::uint32_t links;
        std::uint16_t width, color;  // color kJump: the pen moves, nothing is drawn
    };
    static constexpr std::uint16_t kJump = 0xFFFF;

    static std::uint16_t q(double v, double scale) {
        return static_cast<std::uint16_t>(std::clamp(std::lround(v * scale), 0L, 65535L));
    }
    void quantize(const Vec3& p, std::uint16_t out[3]) const {
        const Vec3 a = p - origin_;
        out[0] = q(a.x, qx_), out[1] = q(a.y, qy_), out[2] = q(a.z, qz_);
    }
    void put(const std::uint16_t p[3]) {
        points_.insert(points_.end(), p, p + dims_);
        std::copy(p, p + 3, last_);
    }
    void link(std::uint32_t links, std::uint16_t width, std::uint16_t color) {
        if (!runs_.empty() && runs_.back().width == width && runs_.back().color == color)
            runs_.back().links += links;
        else
            runs_.push_back({links, width, color});
    }

    std::size_t dims_, paletteSize_;
    Vec3 origin_, size_;
    double qx_ = 0, qy_ = 0, qz_ = 0, widthScale_ = 0;
    float maxWidth_ = 0;
    std::vector<std::uint16_t> points_;
    std::vector<Run> runs_;
    std::uint16_t last_[3] = {0, 0, 0};
};

std::string QuantizedPolylines::write(const Scene& scene, std::size_t n, const Bounds& b,
                                      double ink) const {
    std::vector<std::uint32_t> palette;
    for (std::size_t k = 0; k < paletteSize_; ++k)
        palette.push_back(rgbaBytes(scene.colorOf(static_cast<std::uint16_t>(k))));

    std::vector<float> triangles;
    std::vector<std::uint32_t> triangleColors;
    auto addOutline = [&](const std::vector<Vec3>& outline, const Rgb& color) {
        const std::vector<std::uint32_t> index = triangulatePolygon(outline);
        for (std::size_t i = 0; i + 2 < index.size(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = outline[index[i + k]];
                triangles.insert(triangles.end(), {float(p.x), float(p.y), float(p.z)});
            }
            triangleColors.push_back(rgbaBytes(color));
        }
    };
    for (std::size_t k = 0; k < scene.polygonCount(); ++k) {
        const auto poly = scene.polygon(k);
        addOutline(std::vector<Vec3>(poly.begin(), poly.end()),
                   scene.colorOf(scene.polygonColor[k]));
    }
    for (const Disc& d : scene.discs) addOutline(discOutline(d, 24), scene.colorOf(d.color));
    for (const Sphere& s : scene.spheres)
        addOutline(discOutline(Disc{s.centre, {0, 0, 1}, s.radius, s.color}, 24),
                   scene.colorOf(s.color));

    const std::uint32_t header[6] = {0x334C4647u,
                                     static_cast<std::uint32_t>(n),
                                     static_cast<std::uint32_t>(triangleColors.size()),
                                     dims_ == 3 ? 1u : 0u,
                                     static_cast<std::uint32_t>(points_.size() / dims_),
                                     static_cast<std::uint32_t>(runs_.size())};
    const float lineWidth = float(defaultLineWidth(ink, n > 0, b, RenderOptions{}));
    const float extent[9] = {float(origin_.x),
                             float(origin_.y),
                             float(origin_.z),
                             float(origin_.x + size_.x),
                             float(origin_.y + size_.y),
                             float(origin_.z + size_.z),
                             lineWidth,
                             scene.baseWidth,
                             maxWidth_};
    const std::uint32_t paletteCount = static_cast<std::uint32_t>(palette.size());
    std::string out;
    out.reserve(64 + 4 * palette.size() + 2 * points_.size() + 4 + 8 * runs_.size() +
                4 * (triangles.size() + triangleColors.size()));
    appendRaw(out, header, 6);
    appendRaw(out, extent, 9);
    appendRaw(out, &paletteCount, 1);
    appendRaw(out, palette.data(), palette.size());
    appendRaw(out, points_.data(), points_.size());
    out.append((4 - out.size() % 4) % 4, '\0');
    for (const Run& r : runs_) {
        appendRaw(out, &r.links, 1);
        appendRaw(out, &r.width, 1);
        appendRaw(out, &r.color, 1);
    }
    appendRaw(out, triangles.data(), triangles.size());
    appendRaw(out, triangleColors.data(), triangleColors.size());
    return out;
}

std::size_t paletteSizeOf(const Scene& scene) {
    return std::clamp<std::size_t>(scene.palette.size(), 1, 65535);
}

}  // namespace

std::string encodeLines(const Scene& scene) {
    const std::size_t n = scene.segments.size();
    const Bounds b = scene.bounds();
    float maxWidth = 0;
    for (const Segment& s : scene.segments) maxWidth = std::max(maxWidth, s.width);
    QuantizedPolylines lines(b, scene.is3D, maxWidth, paletteSizeOf(scene), n + n / 8 + 1);
    double ink = 0;
    for (const Segment& s : scene.segments) {
        lines.moveTo(s.a);
        lines.drawTo(&s.b, 1, s.width, s.color);
        ink += inkLength(s, scene.baseWidth);
    }
    return lines.write(scene, n, b, ink);
}

std::string encodeLines(const PolylineScene& polylines) {
    const Scene& rest = polylines.rest;
    const Bounds b = polylines.bounds();
    float maxWidth = 0;
    for (const PolylineScene::Run& r : polylines.runs)
        if (!r.jump) maxWidth = std::max(maxWidth, r.width);
    QuantizedPolylines lines(b, rest.is3D, maxWidth, paletteSizeOf(rest), polylines.points.size());
    const Vec3* point = polylines.points.data();
    if (!polylines.points.empty()) lines.moveTo(*point++);
    for (const PolylineScene::Run& r : polylines.runs) {
        if (r.jump) {
            lines.moveTo(*point++);
        } else {
            lines.drawTo(point, r.links, r.width, r.color);
            point += r.links;
        }
    }
    return lines.write(rest, polylines.segments, b, polylines.ink);
}

}  // namespace graftal::studio
