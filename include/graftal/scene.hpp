// Plain geometry produced by the turtle: what every writer consumes.
#pragma once

#include <cstdint>
#include <limits>
#include <ostream>
#include <span>
#include <vector>

namespace graftal {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    friend bool operator==(const Vec3&, const Vec3&) = default;
};

std::ostream& operator<<(std::ostream& os, const Vec3& v);

struct Rgb {
    float r = 0, g = 0, b = 0;  // each in [0, 1]

    friend bool operator==(const Rgb&, const Rgb&) = default;
};

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

// A drawn line. Width is relative to the default line width (1 = default); colour is an
// index into Scene::palette.
struct Segment {
    Vec3 a, b;
    float width = 1;
    std::uint16_t color = 0;
};

class Scene {
public:
    std::vector<Segment> segments;
    // Filled polygons, stored flat: polygon k has vertices
    // polygonVertices[polygonStart[k] .. polygonStart[k+1]).
    std::vector<Vec3> polygonVertices;
    std::vector<std::uint32_t> polygonStart{0};
    std::vector<std::uint16_t> polygonColor;
    // Colour index -> colour. Indices past the end wrap around.
    std::vector<Rgb> palette = defaultPalette();

    std::size_t polygonCount() const { return polygonColor.size(); }
    std::span<const Vec3> polygon(std::size_t k) const {
        return {polygonVertices.data() + polygonStart[k], polygonStart[k + 1] - polygonStart[k]};
    }
    void addPolygon(std::span<const Vec3> vertices, std::uint16_t color);
    Rgb colorOf(std::uint16_t index) const;

    // Box of every segment end point and polygon vertex (empty for an empty scene).
    Bounds bounds() const;

    // A summary: counts and bounds (the geometry itself can be huge).
    void print(std::ostream& os) const;

    // Dark ink first, then the greens, yellows and reds plants need.
    static std::vector<Rgb> defaultPalette();
};

std::ostream& operator<<(std::ostream& os, const Scene& s);

}  // namespace graftal
