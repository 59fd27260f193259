// Ear clipping with storage kept between calls: the mesher triangulates many small
// polygons and should not allocate for each.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "graftal/geometry/scene.hpp"

namespace graftal {

class PolygonTriangulator {
  public:
    // Appends triangles to `triangles` as indices into `outline`, 3 each, counter-clockwise
    // around the returned unit normal (the outline's Newell normal, so either winding of
    // the outline works). A simple outline of n distinct vertices gives n - 2 triangles.
    // Returns a zero vector and appends nothing for a degenerate outline: fewer than three
    // distinct vertices, all of them on one line, or a non-finite coordinate.
    Vec3 triangulate(std::span<const Vec3> outline, std::vector<std::uint32_t>& triangles);

  private:
    struct Corner {
        double x = 0, y = 0;      // in the outline's plane
        std::uint32_t index = 0;  // into the outline
        std::uint32_t prev = 0, next = 0;
    };

    double turn(const Corner& a, const Corner& b, const Corner& c) const;
    bool isEar(std::uint32_t i) const;
    void clip(std::uint32_t i, std::vector<std::uint32_t>& triangles);

    std::vector<std::uint32_t> kept_;
    std::vector<Corner> corners_;
    double flat_ = 0;  // turns smaller than this count as straight
};

}  // namespace graftal
