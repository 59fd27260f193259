// Generalized cylinders (see graftal/generalized_cylinder.hpp). The curves follow cpfg's
// definitions (its generalized-cylinder code interpolates position, and radius against a
// curve parameter, by cubic Hermite polynomials), so that the centre line passes through
// the points cpfg draws.
#include "graftal/geometry/generalized_cylinder.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace graftal {

namespace {

// The cubic Hermite polynomial from p0 (tangent m0) at s = 0 to p1 (tangent m1) at s = 1.
template <class T>
T hermite(const T& p0, const T& m0, const T& p1, const T& m1, double s) {
    const double s2 = s * s, s3 = s2 * s;
    return p0 * (2 * s3 - 3 * s2 + 1) + m0 * (s3 - 2 * s2 + s) + p1 * (3 * s2 - 2 * s3) +
           m1 * (s3 - s2);
}

template <class T>
T hermiteSlope(const T& p0, const T& m0, const T& p1, const T& m1, double s) {
    const double s2 = s * s;
    return p0 * (6 * s2 - 6 * s) + m0 * (3 * s2 - 4 * s + 1) + p1 * (6 * s - 6 * s2) +
           m1 * (3 * s2 - 2 * s);
}

struct CentreTangents {
    Vec3 leaving, arriving;
};

// cpfg scales both headings by the distance between the points and by the tangent
// parameters: the one a leaves with and the one b arrives with.
CentreTangents centreTangents(const CylinderControlPoint& a, const CylinderControlPoint& b) {
    const double d = length(b.position - a.position);
    return {a.heading * (d * a.tangentLeaving), b.heading * (d * b.tangentArriving)};
}

// The B-spline span as a cubic in t: ((c3 t + c2) t + c1) t + c0.
struct BsplineCubic {
    Vec3 c0, c1, c2, c3;
};

BsplineCubic bsplineCubic(const std::array<Vec3, 4>& p) {
    const double sixth = 1.0 / 6.0;
    return {(p[0] + p[1] * 4.0 + p[2]) * sixth, (p[2] - p[0]) * 0.5,
            (p[0] - p[1] * 2.0 + p[2]) * 0.5, (p[3] - p[0] + (p[1] - p[2]) * 3.0) * sixth};
}

}  // namespace

Vec3 bsplinePoint(const std::array<Vec3, 4>& p, double t) {
    const BsplineCubic c = bsplineCubic(p);
    return ((c.c3 * t + c.c2) * t + c.c1) * t + c.c0;
}

Vec3 bsplineSlope(const std::array<Vec3, 4>& p, double t) {
    const BsplineCubic c = bsplineCubic(p);
    return (c.c3 * (3 * t) + c.c2 * 2.0) * t + c.c1;
}

namespace {

// Where the centre line is at curve parameter t, and which way it runs there.
struct CentreLine {
    const CylinderControlPoint& a;
    const CylinderControlPoint& b;
    const std::array<Vec3, 4>* bspline;
    Vec3 leaving, arriving;  // the Hermite tangents

    Vec3 at(double t) const {
        return bspline ? bsplinePoint(*bspline, t)
                       : hermite(a.position, leaving, b.position, arriving, t);
    }
    Vec3 slope(double t) const {
        return bspline ? bsplineSlope(*bspline, t)
                       : hermiteSlope(a.position, leaving, b.position, arriving, t);
    }
};

}  // namespace

Vec3 hermiteCentre(const CylinderControlPoint& a, const CylinderControlPoint& b, double t) {
    const CentreTangents m = centreTangents(a, b);
    return hermite(a.position, m.leaving, b.position, m.arriving, t);
}

Vec3 carryUp(const Vec3& up, const Vec3& from, const Vec3& to) {
    Vec3 axis = cross(from, to);
    const double s = length(axis), c = dot(from, to);
    Vec3 carried = up;
    if (s > 1e-12) {
        axis = axis * (1 / s);
        const double angle = std::atan2(s, c);
        carried = up * std::cos(angle) + cross(axis, up) * std::sin(angle) +
                  axis * (dot(axis, up) * (1 - std::cos(angle)));
    }
    Vec3 across = carried - to * dot(carried, to);
    return length(across) > 1e-12 ? normalized(across) : up;
}

std::vector<CylinderRing> cylinderRings(const CylinderControlPoint& a,
                                        const CylinderControlPoint& b, int steps,
                                        const std::array<Vec3, 4>* bspline) {
    std::vector<CylinderRing> rings;
    const double d = length(b.position - a.position);
    if (d < 1e-5) return rings;  // cpfg draws nothing between coinciding points
    steps = std::max(steps, 1);
    const CentreTangents m = centreTangents(a, b);
    const CentreLine centre{a, b, bspline, m.leaving, m.arriving};
    // The radius is a Hermite curve too, of pairs (curve parameter t, radius) over the
    // ring parameter r; zero tangents mean a straight change (t = r).
    using Pair = std::array<double, 2>;
    const double r0 = a.width / 2, r1 = b.width / 2;
    auto tangent = [&](std::array<double, 2> v) {
        if (b.scaleRadiusTangents) v[1] *= d;
        if (v[0] == 0 && v[1] == 0) v = {1, r1 - r0};
        return v;
    };
    const Pair m0 = tangent(a.radiusLeaving), m1 = tangent(b.radiusArriving);
    auto at = [&](double r, std::size_t k) {
        return hermite(k ? r0 : 0.0, m0[k], k ? r1 : 1.0, m1[k], r);
    };

    rings.reserve(steps + 1);
    rings.push_back({a.position, a.heading, a.left, a.up, r0, 0});
    for (int k = 1; k < steps; ++k) {
        const double r = static_cast<double>(k) / steps;
        const double t = at(r, 0);
        CylinderRing ring;
        ring.centre = centre.at(t);
        Vec3 slope = centre.slope(t);
        ring.heading = length(slope) > 1e-12 ? normalized(slope) : a.heading;
        ring.up = carryUp(a.up, a.heading, ring.heading);
        ring.left = cross(ring.up, ring.heading);
        ring.radius = at(r, 1);
        ring.blend = t;
        rings.push_back(ring);
    }
    rings.push_back({b.position, b.heading, b.left, b.up, r1, 1});
    return rings;
}

SweptTube sweepRings(const std::vector<CylinderRing>& rings, const std::vector<Vec3>& first,
                     const std::vector<Vec3>& second, bool closed, std::uint16_t color) {
    SweptTube tube;
    tube.ringSize = static_cast<std::uint32_t>(std::min(first.size(), second.size()));
    tube.closed = closed;
    tube.color = color;
    tube.points.reserve(rings.size() * tube.ringSize);
    for (const CylinderRing& ring : rings) {
        tube.headings.push_back(ring.heading);
        for (std::uint32_t i = 0; i < tube.ringSize; ++i) {
            // cpfg places a contour's x along its up vector (our -U) and y along -L.
            const Vec3 q = (first[i] * (1 - ring.blend) + second[i] * ring.blend) * ring.radius;
            tube.points.push_back(ring.centre - ring.up * q.x - ring.left * q.y);
        }
    }
    return tube;
}

void appendSweptTubes(const Scene& scene, Mesh& mesh) {
    for (const SweptTube& tube : scene.sweptTubes) {
        const std::size_t n = tube.ringSize;
        if (n < 2 || tube.headings.size() < 2 || tube.points.size() != n * tube.headings.size())
            continue;
        const std::size_t rings = tube.headings.size();
        auto point = [&](std::size_t k, std::size_t i) { return tube.points[k * n + i]; };
        // Which way the cross-section runs about the centre line decides the winding.
        Vec3 centre{0, 0, 0};
        for (std::size_t i = 0; i < n; ++i) centre = centre + point(0, i);
        centre = centre * (1.0 / n);
        Vec3 turn{0, 0, 0};
        for (std::size_t i = 0; i + 1 < n; ++i)
            turn = turn + cross(point(0, i) - centre, point(0, i + 1) - centre);
        const double sign = dot(turn, tube.headings[0]) >= 0 ? 1.0 : -1.0;

        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (std::size_t k = 0; k < rings; ++k) {
            for (std::size_t i = 0; i < n; ++i) {
                // Along the cross-section: neighbours, around the seam of a closed one.
                std::size_t before = i > 0 ? i - 1 : (tube.closed && n > 2 ? n - 2 : i);
                std::size_t after = i + 1 < n ? i + 1 : (tube.closed && n > 2 ? 1 : i);
                Vec3 around = point(k, after) - point(k, before);
                Vec3 normal = cross(around, tube.headings[k]) * sign;
                normal = length(normal) > 1e-12 ? normalized(normal) : tube.headings[k];
                mesh.positions.push_back(toVec3f(point(k, i)));
                mesh.normals.push_back(toVec3f(normal));
            }
        }
        for (std::size_t k = 0; k + 1 < rings; ++k) {
            for (std::size_t i = 0; i + 1 < n; ++i) {
                const auto a0 = static_cast<std::uint32_t>(base + k * n + i), a1 = a0 + 1;
                const auto b0 = static_cast<std::uint32_t>(a0 + n), b1 = b0 + 1;
                if (sign > 0)
                    mesh.indices.insert(mesh.indices.end(), {a0, a1, b1, a0, b1, b0});
                else
                    mesh.indices.insert(mesh.indices.end(), {a0, b1, a1, a0, b0, b1});
                mesh.triangleColor.insert(mesh.triangleColor.end(), {tube.color, tube.color});
            }
        }
    }
}

Scene withoutSweptCentreLines(const Scene& scene) {
    Scene rest = scene;
    rest.sweptTubes.clear();
    std::vector<bool> centreLine(scene.segments.size(), false);
    for (const SweptTube& tube : scene.sweptTubes)
        for (std::uint32_t s = tube.firstSegment;
             s < tube.firstSegment + tube.segmentCount && s < centreLine.size(); ++s)
            centreLine[s] = true;
    std::vector<std::uint32_t> renumbered(scene.segments.size(), kNoSegment);
    rest.segments.clear();
    for (std::size_t s = 0; s < scene.segments.size(); ++s) {
        if (centreLine[s]) continue;
        Segment kept = scene.segments[s];
        if (kept.previous != kNoSegment)
            kept.previous = kept.previous < s ? renumbered[kept.previous] : kNoSegment;
        renumbered[s] = static_cast<std::uint32_t>(rest.segments.size());
        rest.segments.push_back(kept);
    }
    return rest;
}

}  // namespace graftal
