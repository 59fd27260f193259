// Evaluation of a bicubic Bézier patch: the point from the Bernstein form, the normal from
// the cross product of the two partial derivatives, with care where a derivative vanishes.
#include <algorithm>
#include <cmath>

#include "graftal/geometry/surface.hpp"

namespace graftal {

namespace {

struct Partials {
    Vec3 point, ds, dt;
};

// Cubic Bernstein polynomials and their derivatives at u.
void bernstein(double u, double b[4], double db[4]) {
    double v = 1 - u;
    b[0] = v * v * v;
    b[1] = 3 * u * v * v;
    b[2] = 3 * u * u * v;
    b[3] = u * u * u;
    db[0] = -3 * v * v;
    db[1] = 3 * v * v - 6 * u * v;
    db[2] = 6 * u * v - 3 * u * u;
    db[3] = 3 * u * u;
}

Partials partials(const BezierPatch& p, double s, double t) {
    double bs[4], dbs[4], bt[4], dbt[4];
    bernstein(s, bs, dbs);
    bernstein(t, bt, dbt);
    Partials r;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            const Vec3& c = p.points[static_cast<std::size_t>(row * 4 + col)];
            double w = bt[row] * bs[col], ws = bt[row] * dbs[col], wt = dbt[row] * bs[col];
            r.point.x += w * c.x;
            r.point.y += w * c.y;
            r.point.z += w * c.z;
            r.ds.x += ws * c.x;
            r.ds.y += ws * c.y;
            r.ds.z += ws * c.z;
            r.dt.x += wt * c.x;
            r.dt.y += wt * c.y;
            r.dt.z += wt * c.z;
        }
    }
    return r;
}

// The largest distance of a control point from the first: the patch's scale, against which
// "a derivative vanishes" is judged.
double extent(const BezierPatch& p) {
    double e = 0;
    for (const Vec3& c : p.points) {
        Vec3 d{c.x - p.points[0].x, c.y - p.points[0].y, c.z - p.points[0].z};
        e = std::max(e, length(d));
    }
    return e;
}

// Any unit vector perpendicular to v (v not zero).
Vec3 perpendicularTo(const Vec3& v) {
    Vec3 axis = std::abs(v.x) <= std::abs(v.y) && std::abs(v.x) <= std::abs(v.z) ? Vec3{1, 0, 0}
                : std::abs(v.y) <= std::abs(v.z)                                 ? Vec3{0, 1, 0}
                                                                                 : Vec3{0, 0, 1};
    Vec3 n = cross(v, axis);
    double l = length(n);
    return {n.x / l, n.y / l, n.z / l};
}

}  // namespace

Vec3 evaluatePatch(const BezierPatch& p, double s, double t, Vec3* normal) {
    s = std::clamp(s, 0.0, 1.0);
    t = std::clamp(t, 0.0, 1.0);
    Partials at = partials(p, s, t);
    if (!normal) return at.point;

    double size = extent(p);
    // The cross product scales with size squared; below this it is rounding noise.
    double tiny = 1e-10 * size * size;
    Vec3 n = cross(at.ds, at.dt);
    double l = length(n);
    if (size > 0 && l <= tiny) {
        // A collapsed edge (a leaf tip where a whole row of control points coincides) or a
        // corner where the edges are parallel: the normal there is the limit of the normals
        // approaching it from inside, so step towards the patch centre until the partial
        // derivatives span a plane again. Stepping inward also gets the limit's sign right,
        // which a second derivative taken at the edge itself would not.
        for (double step : {1e-7, 1e-5, 1e-3, 1e-1, 0.5}) {
            Partials inside = partials(p, s + step * (0.5 - s), t + step * (0.5 - t));
            n = cross(inside.ds, inside.dt);
            l = length(n);
            if (l > tiny) break;
        }
    }
    if (l > tiny && l > 0) {
        *normal = {n.x / l, n.y / l, n.z / l};
    } else {
        // Nothing spans a plane (all control points on one line or one point): any normal
        // across the line is as good as another, and it must at least be finite.
        Vec3 d = length(at.ds) >= length(at.dt) ? at.ds : at.dt;
        if (!(length(d) > 0)) {
            for (const Vec3& c : p.points) {
                Vec3 e{c.x - p.points[0].x, c.y - p.points[0].y, c.z - p.points[0].z};
                if (length(e) > length(d)) d = e;
            }
        }
        *normal = length(d) > 0 ? perpendicularTo(d) : Vec3{0, 0, 1};
    }
    return at.point;
}

}  // namespace graftal
