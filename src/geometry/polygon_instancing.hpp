// Repeated polygons (the same leaf drawn at every node) found by their shape, so that an
// instanced scene stores each shape once and places it by transform.
#pragma once

#include <cstdint>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal::meshing {

// The polygons of a scene grouped by shape: two polygons have the same shape when one is
// the other moved, turned and scaled uniformly (not mirrored), vertex by vertex, to within
// a millionth of its size, in the same colour. Polygons whose shape occurs once, and
// degenerate ones, are not grouped.
class PolygonShapes {
  public:
    explicit PolygonShapes(const Scene& scene);

    // Whether polygon k is placed from a shape (and so left out of the shared mesh).
    bool instanced(std::size_t k) const { return shapeOf_[k] != kNone; }
    bool any() const { return !shapes_.empty(); }

    // Adds one prototype per shape and one placement per grouped polygon to `out`
    // (whose mesh.palette is the scene's).
    void instance(MeshScene& out) const;

  private:
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

    struct Shape {
        std::size_t first = 0;  // the polygon whose outline becomes the prototype
        std::uint32_t count = 0;
    };

    const Scene& scene_;
    std::vector<std::uint32_t> shapeOf_;  // per polygon
    std::vector<Affine3f> placement_;     // per polygon: its own frame
    std::vector<Shape> shapes_;
};

}  // namespace graftal::meshing
