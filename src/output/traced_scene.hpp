// What the ray tracer traces: the parts of a MeshScene (or of a lone Mesh) seen in place,
// never copied, and the points of everything drawn, for framing the camera on them.
#pragma once

#include <cmath>
#include <span>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"

namespace graftal {

struct TracedScene {
    const Mesh* mesh = nullptr;  // never null
    std::span<const Mesh> prototypes;
    std::span<const MeshPlacement> placements;
    std::span<const CurveSegment> curves;

    static TracedScene of(const Mesh& mesh) { return {&mesh, {}, {}, {}}; }
    static TracedScene of(const MeshScene& s) {
        return {&s.mesh, s.prototypes, s.placements, s.curves};
    }

    const std::vector<Rgb>& palette() const { return mesh->palette; }
    bool empty() const {
        if (mesh->triangleCount() != 0 || !curves.empty()) return false;
        for (const MeshPlacement& p : placements)
            if (p.prototype < prototypes.size() && prototypes[p.prototype].triangleCount() != 0)
                return false;
        return true;
    }
};

inline bool isFinite(const Vec3f& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Calls visit(centre, radius) for every point that bounds what is drawn: each mesh vertex
// (radius 0), each vertex of each placed prototype where the placement puts it, and each
// end of each curve with its radius. Non-finite points are skipped (Embree drops what they
// belong to). The convex hull of these balls is the hull of the scene as drawn.
template <class Visit>
void forEachDrawnPoint(const TracedScene& scene, Visit&& visit) {
    for (const Vec3f& p : scene.mesh->positions)
        if (isFinite(p)) visit(toVec3(p), 0.0);
    for (const MeshPlacement& placement : scene.placements) {
        if (placement.prototype >= scene.prototypes.size()) continue;
        const Mesh& prototype = scene.prototypes[placement.prototype];
        if (prototype.triangleCount() == 0) continue;
        for (const Vec3f& p : prototype.positions) {
            const Vec3f q = placement.transform.point(p);
            if (isFinite(q)) visit(toVec3(q), 0.0);
        }
    }
    for (const CurveSegment& c : scene.curves) {
        if (isFinite(c.a) && std::isfinite(c.radiusA)) visit(toVec3(c.a), double(c.radiusA));
        if (isFinite(c.b) && std::isfinite(c.radiusB)) visit(toVec3(c.b), double(c.radiusB));
    }
}

}  // namespace graftal
