// Plain geometry produced by the turtle: what every writer consumes.
#pragma once

#include <cstdint>
#include <limits>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "graftal/core/rgb.hpp"
#include "graftal/core/vec3.hpp"

namespace graftal {

struct Bounds {
    Vec3 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity()};
    Vec3 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
             -std::numeric_limits<double>::infinity()};

    bool empty() const { return min.x > max.x; }
    void extend(const Vec3& p);
    void extend(const Bounds& b);
};

std::ostream& operator<<(std::ostream& os, const Bounds& b);

inline constexpr std::uint32_t kNoSegment = 0xFFFFFFFFu;

// A drawn segment of an axis. `width` is the turtle's width attribute: the diameter of the
// stem in model units when drawn as a cylinder, and relative to Scene::baseWidth for 2D
// line art. `color` indexes Scene::palette. `previous` is the segment this one continues
// along the same axis (kNoSegment at the start of an axis), so that a mesher can join
// consecutive cylinders without cracks; `up` is the turtle's up vector U at the segment,
// which fixes the orientation of a cylinder's cross-section.
struct Segment {
    Vec3 a, b;
    float width = 1;
    std::uint16_t color = 0;
    std::uint32_t previous = kNoSegment;
    Vec3 up{0, 0, 1};
};

// A predefined surface (a bicubic patch set from a .s file) placed at a turtle frame: the
// surface's contact point goes to `origin`, its heading to H and its up vector to U (as
// cpfg places surfaces), scaled by `scale`.
struct SurfaceInstance {
    std::uint32_t surface = 0;  // index into Scene::surfaceNames
    Vec3 origin;
    Vec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, 1};
    double scale = 1;
    std::uint16_t color = 0;
};

// A disc (cpfg's @o and @c): a filled circle of `radius` about `centre`, in the plane
// whose normal is `normal` (unit length).
struct Disc {
    Vec3 centre, normal{0, 0, 1};
    double radius = 0.5;
    std::uint16_t color = 0;
};

// A sphere (cpfg's @O).
struct Sphere {
    Vec3 centre;
    double radius = 0.5;
    std::uint16_t color = 0;
};

// A generalized cylinder between two control points (cpfg's @Gs, @Gc, @Ge): cross-sections
// (rings of `ringSize` points; ring k is points[k * ringSize .. (k + 1) * ringSize)) swept
// along a curved centre line whose direction at ring k is headings[k]. A closed
// cross-section repeats its first point last. Its centre line is also drawn as the
// segments [firstSegment, firstSegment + segmentCount) for pictures without surfaces (2D
// line art); a 3D mesh draws the swept surface instead of them.
struct SweptTube {
    std::vector<Vec3> points;
    std::vector<Vec3> headings;
    std::uint32_t ringSize = 0;
    bool closed = true;
    std::uint16_t color = 0;
    std::uint32_t firstSegment = 0, segmentCount = 0;
};

class Scene {
  public:
    std::vector<Segment> segments;
    // Filled polygons, stored flat: polygon k has vertices
    // polygonVertices[polygonStart[k] .. polygonStart[k+1]).
    std::vector<Vec3> polygonVertices;
    std::vector<std::uint32_t> polygonStart{0};
    std::vector<std::uint16_t> polygonColor;
    // Predefined surfaces placed by `~name`; the names are resolved by a SurfaceLibrary.
    std::vector<SurfaceInstance> surfaces;
    std::vector<std::string> surfaceNames;
    // Circles and balls the turtle places with @o, @c and @O.
    std::vector<Disc> discs;
    std::vector<Sphere> spheres;
    // Generalized cylinders, one per piece between two control points.
    std::vector<SweptTube> sweptTubes;
    // The width a segment has when the turtle never changed it: what 2D line art scales by.
    float baseWidth = 1;
    // 2D line art draws widths in model units, scaled with the picture (a cpfg view file's
    // world-unit line width, MaterialSettings::widthsInModelUnits), not relative to baseWidth.
    bool widthsInModelUnits = false;
    // True when anything left the z = 0 plane: 3D outputs and views make sense.
    bool is3D = false;
    // Colour index -> colour. Indices past the end wrap around.
    std::vector<Rgb> palette = defaultPalette();

    std::size_t polygonCount() const { return polygonColor.size(); }
    std::span<const Vec3> polygon(std::size_t k) const {
        return {polygonVertices.data() + polygonStart[k], polygonStart[k + 1] - polygonStart[k]};
    }
    void addPolygon(std::span<const Vec3> vertices, std::uint16_t color);
    Rgb colorOf(std::uint16_t index) const;

    // Box of every segment end point, polygon vertex, disc and sphere (empty for an empty
    // scene).
    Bounds bounds() const;

    // A summary: counts and bounds (the geometry itself can be huge).
    void print(std::ostream& os) const;

    // Dark ink first, then the greens, yellows and reds plants need.
    static std::vector<Rgb> defaultPalette();
};

std::ostream& operator<<(std::ostream& os, const Scene& s);

// The exact boxes of a disc and a sphere (empty when not finite).
Bounds discBounds(const Disc& d);
Bounds sphereBounds(const Sphere& s);

// `sides` points around a disc, counter-clockwise seen from the side its normal points to.
std::vector<Vec3> discOutline(const Disc& d, int sides);

}  // namespace graftal
