// Repeated polygons by shape (see polygon_instancing.hpp).
//
// Each polygon gets its own frame: the first vertex is the origin, the first edge of
// non-zero length gives the x axis and the unit of length, the outline's Newell normal the
// z axis. Its vertices in that frame, rounded to a millionth, are its shape; polygons whose
// shapes are equal share a prototype (the first one's outline in its frame), placed by
// each polygon's frame.
#include "polygon_instancing.hpp"

#include <cmath>
#include <map>
#include <tuple>

#include "graftal/core/vec3.hpp"
#include "polygon_triangulation.hpp"

namespace graftal::meshing {

namespace {

// Vertices in the polygon's frame are rounded to this fraction of its first edge.
constexpr double kShapeResolution = 1e-6;
// Coordinates farther than this many first edges from the first vertex make no shape
// (the rounded values would not fit 32 bits).
constexpr double kMaxShapeExtent = 1e3;

struct Frame {
    Vec3 origin, x, y, z;
    double unit = 0;
};

// The frame of an outline with Newell normal `n` (unit length); unit == 0 when none.
Frame frameOf(std::span<const Vec3> outline, const Vec3& n) {
    Frame f;
    f.origin = outline[0];
    double scale = 0;
    for (const Vec3& v : outline) scale = std::max(scale, length(v - f.origin));
    for (std::size_t i = 1; i < outline.size(); ++i) {
        const Vec3 e = outline[i] - f.origin;
        const double l = length(e);
        if (!(l > 1e-6 * scale)) continue;
        const Vec3 x = e - dot(e, n) * n;
        if (!(length(x) > 1e-3 * l)) continue;
        f.x = normalized(x);
        f.z = n;
        f.y = cross(f.z, f.x);
        f.unit = l;
        return f;
    }
    return f;
}

}  // namespace

PolygonShapes::PolygonShapes(const Scene& scene)
    : scene_(scene), shapeOf_(scene.polygonCount(), kNone), placement_(scene.polygonCount()) {
    PolygonTriangulator triangulator;
    std::vector<std::uint32_t> triangles;
    std::map<std::tuple<std::uint16_t, std::vector<std::int32_t>>, std::uint32_t> byShape;
    std::vector<std::int32_t> key;
    std::vector<std::uint32_t> candidate(scene.polygonCount(), kNone);
    for (std::size_t k = 0; k < scene.polygonCount(); ++k) {
        const std::span<const Vec3> outline = scene.polygon(k);
        if (outline.size() < 3) continue;
        triangles.clear();
        const Vec3 n = triangulator.triangulate(outline, triangles);
        if (triangles.empty()) continue;
        const Frame f = frameOf(outline, n);
        if (!(f.unit > 0) || !std::isfinite(f.unit)) continue;
        key.clear();
        bool fits = true;
        for (const Vec3& v : outline) {
            const Vec3 e = (1 / f.unit) * (v - f.origin);
            for (double c : {dot(e, f.x), dot(e, f.y), dot(e, f.z)}) {
                if (!(std::fabs(c) < kMaxShapeExtent)) fits = false;
                key.push_back(fits ? static_cast<std::int32_t>(std::lround(c / kShapeResolution))
                                   : 0);
            }
        }
        if (!fits) continue;
        Affine3f& a = placement_[k];
        a.columns[0] = toVec3f(f.unit * f.x);
        a.columns[1] = toVec3f(f.unit * f.y);
        a.columns[2] = toVec3f(f.unit * f.z);
        a.columns[3] = toVec3f(f.origin);
        auto [it, fresh] = byShape.try_emplace({scene.polygonColor[k], key},
                                               static_cast<std::uint32_t>(shapes_.size()));
        if (fresh) shapes_.push_back({k, 0});
        ++shapes_[it->second].count;
        candidate[k] = it->second;
    }
    // A shape drawn once stays in the mesh; the others are renumbered in order.
    std::vector<std::uint32_t> renumbered(shapes_.size(), kNone);
    std::vector<Shape> kept;
    for (std::size_t s = 0; s < shapes_.size(); ++s) {
        if (shapes_[s].count < 2) continue;
        renumbered[s] = static_cast<std::uint32_t>(kept.size());
        kept.push_back(shapes_[s]);
    }
    shapes_ = std::move(kept);
    for (std::size_t k = 0; k < candidate.size(); ++k)
        if (candidate[k] != kNone) shapeOf_[k] = renumbered[candidate[k]];
}

void PolygonShapes::instance(MeshScene& out) const {
    const auto firstPrototype = static_cast<std::uint32_t>(out.prototypes.size());
    PolygonTriangulator triangulator;
    std::vector<std::uint32_t> triangles;
    std::vector<Vec3> local;
    for (const Shape& shape : shapes_) {
        // The prototype: the first polygon of the shape, in its own frame, flat-shaded.
        const std::span<const Vec3> outline = scene_.polygon(shape.first);
        triangles.clear();
        const Frame f = frameOf(outline, triangulator.triangulate(outline, triangles));
        local.clear();
        for (const Vec3& v : outline) {
            const Vec3 e = (1 / f.unit) * (v - f.origin);
            local.push_back({dot(e, f.x), dot(e, f.y), dot(e, f.z)});
        }
        triangles.clear();
        const Vec3 normal = triangulator.triangulate(local, triangles);
        Mesh m;
        m.palette = out.mesh.palette;
        for (const Vec3& v : local) {
            m.positions.push_back(toVec3f(v));
            m.normals.push_back(toVec3f(normal));
        }
        m.indices = triangles;
        m.triangleColor.assign(triangles.size() / 3, scene_.polygonColor[shape.first]);
        out.prototypes.push_back(std::move(m));
    }
    for (std::size_t k = 0; k < shapeOf_.size(); ++k)
        if (shapeOf_[k] != kNone)
            out.placements.push_back({firstPrototype + shapeOf_[k], placement_[k]});
}

}  // namespace graftal::meshing
