// The geometry sinks of streamed passes: one measures what the turtle draws (counts,
// bounds, ink) without keeping it, the other hands it to a StreamedDrawing (a streamed
// PNG in src/output). The streamed turtle and the summarised walk (subtree_summaries.cpp)
// both use them.
#pragma once

#include <algorithm>
#include <limits>
#include <span>
#include <string>

#include "graftal/turtle/streamed_interpretation.hpp"
#include "planar_length.hpp"

namespace graftal {

class MeasureSink {
  public:
    explicit MeasureSink(StreamedMeasure& m) : m_(m) {}
    std::uint32_t segment(const Segment& s) {
        // A segment that goes on from the last one starts at a point already in the box:
        // extending by it again would change nothing (a bound moves only on a strict <).
        if (!(s.a == lastEnd_)) extend(s.a);
        extend(s.b);
        lastEnd_ = s.b;
        m_.ink += turtle::inkTerm(length_(s.b.x - s.a.x, s.b.y - s.a.y),
                                  turtle::inkWeight(s.width, m_.baseWidth));
        return static_cast<std::uint32_t>(m_.segments++);
    }
    void polygon(std::span<const Vec3> v, std::uint16_t) {
        for (const auto& p : v) extend(p);
        ++m_.polygons;
    }
    void surface(const std::string&, const SurfaceInstance&) {}
    void disc(const Disc& d) { extend(discBounds(d)); }
    void sphere(const Sphere& s) { extend(sphereBounds(s)); }
    void baseWidth(float w) { m_.baseWidth = w; }
    void finish(bool is3D) { m_.is3D = is3D; }

  private:
    void extend(const Bounds& b) {
        if (!b.empty()) m_.bounds.extend(b);
    }
    // Bounds::extend(), inline: it runs for every segment.
    void extend(const Vec3& p) {
        Bounds& b = m_.bounds;
        b.min = {std::min(b.min.x, p.x), std::min(b.min.y, p.y), std::min(b.min.z, p.z)};
        b.max = {std::max(b.max.x, p.x), std::max(b.max.y, p.y), std::max(b.max.z, p.z)};
    }

    StreamedMeasure& m_;
    Vec3 lastEnd_{kNaN, kNaN, kNaN};  // equal to no point
    turtle::PlanarLength length_;
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
};

class DrawingSink {
  public:
    explicit DrawingSink(StreamedDrawing& drawing) : drawing_(drawing) {}
    std::uint32_t segment(const Segment& s) {
        drawing_.segment(s);
        return kNoSegment;
    }
    void polygon(std::span<const Vec3> v, std::uint16_t c) { drawing_.polygon(v, c); }
    void surface(const std::string&, const SurfaceInstance&) {}
    // Seen from the front, as projectScene() draws them.
    void disc(const Disc& d) { drawing_.polygon(discOutline(d, kSides), d.color); }
    void sphere(const Sphere& s) {
        drawing_.polygon(discOutline(Disc{s.centre, {0, 0, 1}, s.radius, s.color}, kSides),
                         s.color);
    }
    void baseWidth(float) {}
    void finish(bool) {}

  private:
    static constexpr int kSides = 48;
    StreamedDrawing& drawing_;
};

}  // namespace graftal
