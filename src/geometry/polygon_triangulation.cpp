// Polygons to triangles: ear clipping in the plane that best fits the outline. Turtle
// polygons are small, roughly planar and often concave (leaves, petals); some repeat a
// vertex or run three vertices along a line, and they come in either winding.
#include "polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>

#include "graftal/core/vec3.hpp"
#include "graftal/geometry/mesh.hpp"

namespace graftal {

namespace {

// Relative to the outline's size: vertices closer than this are one vertex, and triangles
// whose doubled area is below this times the size squared are flat.
constexpr double kSameVertex = 1e-10;
constexpr double kFlatTurn = 1e-12;

}  // namespace

double PolygonTriangulator::turn(const Corner& a, const Corner& b, const Corner& c) const {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Corner i can be cut off when it turns left and no other corner lies in or on the
// triangle it makes with its neighbours. Only corners that do not turn left can lie there
// (a simple polygon's convex corners cannot), so only those are tested.
bool PolygonTriangulator::isEar(std::uint32_t i) const {
    const Corner& b = corners_[i];
    const Corner& a = corners_[b.prev];
    const Corner& c = corners_[b.next];
    if (turn(a, b, c) <= flat_) return false;
    auto same = [](const Corner& p, const Corner& q) { return p.x == q.x && p.y == q.y; };
    for (std::uint32_t j = c.next; j != b.prev; j = corners_[j].next) {
        const Corner& p = corners_[j];
        if (turn(corners_[p.prev], p, corners_[p.next]) > flat_) continue;
        // A corner repeated elsewhere in the outline (where it touches itself) is not in
        // the way of the ear it is a corner of.
        if (same(p, a) || same(p, b) || same(p, c)) continue;
        if (turn(a, b, p) >= -flat_ && turn(b, c, p) >= -flat_ && turn(c, a, p) >= -flat_)
            return false;
    }
    return true;
}

void PolygonTriangulator::clip(std::uint32_t i, std::vector<std::uint32_t>& triangles) {
    Corner& b = corners_[i];
    triangles.insert(triangles.end(), {corners_[b.prev].index, b.index, corners_[b.next].index});
    corners_[b.prev].next = b.next;
    corners_[b.next].prev = b.prev;
}

Vec3 PolygonTriangulator::triangulate(std::span<const Vec3> outline,
                                      std::vector<std::uint32_t>& triangles) {
    // Consecutive repeats (including the last vertex repeating the first) are one corner.
    Vec3 low{HUGE_VAL, HUGE_VAL, HUGE_VAL}, high = -low;
    for (const Vec3& v : outline) {
        if (!isFinite(Vec3(v))) return {};
        low = {std::min(low.x, v.x), std::min(low.y, v.y), std::min(low.z, v.z)};
        high = {std::max(high.x, v.x), std::max(high.y, v.y), std::max(high.z, v.z)};
    }
    if (outline.size() < 3) return {};
    const double size = length(high - low);
    auto distinct = [&](std::uint32_t p, std::uint32_t q) {
        return length(Vec3(outline[p]) - Vec3(outline[q])) > kSameVertex * size;
    };
    kept_.clear();
    for (std::uint32_t i = 0; i < outline.size(); ++i)
        if (kept_.empty() || distinct(kept_.back(), i)) kept_.push_back(i);
    while (kept_.size() > 1 && !distinct(kept_.back(), kept_.front())) kept_.pop_back();
    const std::size_t m = kept_.size();
    if (m < 3) return {};

    // Newell's normal is twice the vector area: its direction is the best-fit plane's
    // normal, oriented so that the outline runs counter-clockwise around it.
    const Vec3 centre = 0.5 * (low + high);
    Vec3 area;
    for (std::size_t k = 0; k < m; ++k)
        area = area +
               cross(Vec3(outline[kept_[k]]) - centre, Vec3(outline[kept_[(k + 1) % m]]) - centre);
    if (!(length(area) > kFlatTurn * size * size)) return {};
    const Vec3 normal = normalizedOr(area, {0, 0, 1});
    const Vec3 e1 = anyPerpendicular(normal);
    const Vec3 e2 = cross(normal, e1);

    corners_.resize(m);
    for (std::uint32_t k = 0; k < m; ++k) {
        const Vec3 p = Vec3(outline[kept_[k]]) - centre;
        corners_[k] = {dot(p, e1), dot(p, e2), kept_[k],
                       static_cast<std::uint32_t>((k + m - 1) % m),
                       static_cast<std::uint32_t>((k + 1) % m)};
    }
    flat_ = kFlatTurn * size * size;

    triangles.reserve(triangles.size() + 3 * (m - 2));
    std::uint32_t i = 0;
    std::size_t remaining = m, tried = 0;
    while (remaining > 3) {
        if (isEar(i)) {
            const std::uint32_t before = corners_[i].prev;
            clip(i, triangles);
            --remaining;
            tried = 0;
            // Cutting an ear changes only its neighbours, so look there first.
            i = before;
            continue;
        }
        i = corners_[i].next;
        if (++tried < remaining) continue;
        // No ear anywhere: the outline crosses itself or rounding hid one. Cutting the
        // sharpest left turn still covers the outline and always terminates.
        std::uint32_t best = i;
        double bestTurn = -HUGE_VAL;
        std::uint32_t j = i;
        do {
            const Corner& c = corners_[j];
            const double t = turn(corners_[c.prev], c, corners_[c.next]);
            if (t > bestTurn) {
                bestTurn = t;
                best = j;
            }
            j = c.next;
        } while (j != i);
        i = corners_[best].prev;
        clip(best, triangles);
        --remaining;
        tried = 0;
    }
    clip(corners_[i].next, triangles);
    return normal;
}

std::vector<std::uint32_t> triangulatePolygon(const std::vector<Vec3>& outline) {
    std::vector<std::uint32_t> triangles;
    PolygonTriangulator().triangulate(outline, triangles);
    return triangles;
}

}  // namespace graftal
