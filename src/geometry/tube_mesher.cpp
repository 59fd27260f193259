// Segments to generalized cylinders: one tube per axis, rings shared at the joints, frames
// carried by parallel transport. See tube_mesher.hpp for the shape of the result.
#include "tube_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "graftal/vec3.hpp"

namespace graftal {

namespace {

// A joint bending further than this (cosine of 120 degrees) is capped on both sides: its
// mitre would stretch the ring to more than twice the stem's radius.
constexpr double kMaxBendCos = -0.5;
// How far along a segment (as a fraction of its length) a mitre may lean a ring vertex;
// half leaves room for the mitre at the segment's other end, so rings never cross.
constexpr double kMitreReach = 0.5;
// Ends closer than this fraction of the segments' lengths count as the same joint.
constexpr double kJoinTolerance = 1e-6;
// Shorter segments than this fraction of their distance from the origin vanish in the
// single-precision mesh anyway.
constexpr double kMinRelativeLength = 1e-10;

// Where a segment goes; `length` is 0 when it has no usable direction.
struct Direction {
    Vec3 unit;
    double length = 0;
};

Direction directionOf(const Segment& s) {
    const Vec3 a(s.a), b(s.b);
    if (!isFinite(a) || !isFinite(b)) return {};
    const Vec3 ab = b - a;
    const double l = length(ab);
    const double scale = std::max(length(a), length(b));
    if (!(l > kMinRelativeLength * scale) || !std::isfinite(l)) return {};
    return {(1.0 / l) * ab, l};
}

// Rotates the frame vector `u` (perpendicular to `from`) by the smallest rotation taking
// `from` to `to`: parallel transport, which is what keeps a tube from twisting.
Vec3 transport(const Vec3& u, const Vec3& from, const Vec3& to) {
    const Vec3 k = cross(from, to);
    const double c = dot(from, to);
    const Vec3 rotated = c * u + cross(k, u) + (dot(k, u) / (1 + c)) * k;
    // Renormalising against `to` stops rounding errors from accumulating along long axes.
    return perpendicularPart(rotated, to);
}

// Appends to a mesh whose storage has been reserved.
class Emitter {
  public:
    explicit Emitter(Mesh& mesh) : mesh_(mesh) {}

    std::uint32_t vertex(const Vec3& p, const Vec3& n) {
        mesh_.positions.push_back(toVec3f(p));
        mesh_.normals.push_back(toVec3f(n));
        return static_cast<std::uint32_t>(mesh_.positions.size() - 1);
    }
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t color) {
        mesh_.indices.push_back(a);
        mesh_.indices.push_back(b);
        mesh_.indices.push_back(c);
        mesh_.triangleColor.push_back(color);
    }

  private:
    Mesh& mesh_;
};

}  // namespace

TubeMesher::TubeMesher(const Scene& scene, const MeshOptions& options)
    : scene_(scene), options_(options) {
    if (!options_.cylinders || scene_.segments.empty()) return;
    const int n = options_.tubeSides;
    cos_.resize(n);
    sin_.resize(n);
    for (int i = 0; i < n; ++i) {
        const double angle = 2 * std::numbers::pi * i / n;
        cos_[i] = std::cos(angle);
        sin_[i] = std::sin(angle);
    }
    plan();
}

double TubeMesher::radius(float width) const {
    double r = static_cast<double>(width) * options_.widthScale / 2;
    if (!(r > 0) || !std::isfinite(r)) r = 0;
    return std::max(r, options_.minimumRadius);
}

// The tube narrows from the width of the segment before to this one's: the turtle sets the
// width before drawing, so a width change shows as a taper, not a step.
double TubeMesher::startRadius(std::uint32_t s) const {
    const std::uint32_t p = previous_[s];
    return radius(scene_.segments[p != kNoSegment ? p : s].width);
}

bool TubeMesher::canJoin(std::uint32_t p, std::uint32_t s) const {
    const Segment& before = scene_.segments[p];
    const Segment& after = scene_.segments[s];
    const Direction dp = directionOf(before), ds = directionOf(after);
    const double gap = length(Vec3(after.a) - Vec3(before.b));
    if (!(gap <= kJoinTolerance * std::max(dp.length, ds.length))) return false;
    const double c = dot(dp.unit, ds.unit);
    if (c < kMaxBendCos) return false;
    const double r = radius(before.width);
    if (!(r > 0)) return false;
    // The mitre leans ring vertices along the axis by up to r * tan(bend / 2).
    const double tanHalfBend = length(cross(dp.unit, ds.unit)) / (1 + c);
    return r * tanHalfBend <= kMitreReach * std::min(dp.length, ds.length);
}

void TubeMesher::plan() {
    const std::vector<Segment>& segments = scene_.segments;
    const std::size_t count = segments.size();
    previous_.assign(count, kNoSegment);
    next_.assign(count, kNoSegment);
    flags_.assign(count, 0);
    const std::size_t n = cos_.size();

    for (std::uint32_t s = 0; s < count; ++s) {
        const Segment& segment = segments[s];
        // Only earlier segments can be continued: that rules out cycles, and the turtle
        // emits an axis in order. Unusable segments (zero length) are looked through.
        const std::uint32_t p = segment.previous;
        if (p < s) previous_[s] = usable(p) ? p : previous_[p];

        const Direction d = directionOf(segment);
        const double rStart = startRadius(s), rEnd = radius(segment.width);
        if (d.length == 0 || (rStart == 0 && rEnd == 0)) continue;
        flags_[s] = kUsable;

        const std::uint32_t before = previous_[s];
        if (before == kNoSegment || !canJoin(before, s)) continue;
        if (const std::uint32_t rival = next_[before]; rival != kNoSegment) {
            // Two segments continue the same one (a branch marked as a continuation): the
            // straighter one carries the tube on, the other starts a tube of its own.
            const Vec3 db = directionOf(segments[before]).unit;
            const double rivalCos = dot(db, directionOf(segments[rival]).unit);
            if (rivalCos >= dot(db, d.unit)) continue;
            flags_[rival] &= static_cast<std::uint8_t>(~kJoinedStart);
        }
        next_[before] = s;
        flags_[s] |= kJoinedStart;
    }

    for (std::uint32_t s = 0; s < count; ++s) {
        if (!usable(s)) continue;
        const bool apexStart = startRadius(s) == 0;
        const bool apexEnd = radius(segments[s].width) == 0;
        if (!joinedStart(s)) {
            vertexCount_ += apexStart ? 1 : n + 1;
            triangleCount_ += apexStart ? 0 : n;
        }
        if (joinedEnd(s)) {
            vertexCount_ += n;
        } else {
            vertexCount_ += apexEnd ? 1 : n + 1;
            triangleCount_ += apexEnd ? 0 : n;
        }
        triangleCount_ += (apexStart ? 0 : n) + (apexEnd ? 0 : n);
    }
}

void TubeMesher::append(Mesh& mesh) const {
    for (std::uint32_t s = 0; s < flags_.size(); ++s)
        if (usable(s) && !joinedStart(s)) appendAxis(s, mesh);
}

// One axis, from its first segment along next_. Rings are emitted once: each segment adds
// its end ring, which the next segment takes as its start ring.
void TubeMesher::appendAxis(std::uint32_t first, Mesh& mesh) const {
    const std::vector<Segment>& segments = scene_.segments;
    const std::uint32_t n = static_cast<std::uint32_t>(cos_.size());
    Emitter out(mesh);

    // A ring of radius r around `centre` in the plane perpendicular to the unit vector d,
    // leaned by the mitre towards `dn` when that is given. Normals follow the taper.
    auto ring = [&](const Vec3& centre, const Vec3& d, const Vec3& u, double r, double slope,
                    const Vec3* dn, const Vec3& un, double slopeN) {
        const Vec3 v = cross(d, u);
        const Vec3 vn = dn ? cross(*dn, un) : Vec3{};
        const double lean = dn ? 1 / (1 + dot(d, *dn)) : 0;
        const std::uint32_t start = static_cast<std::uint32_t>(mesh.positions.size());
        for (std::uint32_t i = 0; i < n; ++i) {
            const Vec3 e = cos_[i] * u + sin_[i] * v;
            Vec3 normal = normalizedOr(e - slope * d, e);
            Vec3 p = centre + r * e;
            if (dn) {
                // Sliding along d onto the plane bisecting the joint puts the vertex on both
                // cylinders at once; the frames agree because `un` is u transported.
                p = p - (r * dot(e, *dn) * lean) * d;
                const Vec3 en = cos_[i] * un + sin_[i] * vn;
                normal = normalizedOr(normal + normalizedOr(en - slopeN * (*dn), en), e);
            }
            out.vertex(p, normal);
        }
        return start;
    };
    auto cap = [&](const Vec3& centre, const Vec3& normal, std::uint32_t rim, bool start,
                   std::uint16_t color) {
        const std::uint32_t c = out.vertex(centre, normal);
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t j = (i + 1) % n;
            if (start)
                out.triangle(c, rim + j, rim + i, color);
            else
                out.triangle(c, rim + i, rim + j, color);
        }
    };

    std::uint32_t s = first;
    const Segment* segment = &segments[s];
    Direction d = directionOf(*segment);
    const Vec3 a(segment->a);
    Vec3 b(segment->b);
    Vec3 u = perpendicularPart(Vec3(segment->up), d.unit);
    double rA = startRadius(s), rB = radius(segment->width);
    double slope = (rB - rA) / d.length;

    bool apexA = rA == 0;
    std::uint32_t ringA;
    if (apexA) {
        ringA = out.vertex(a, -d.unit);
    } else {
        ringA = ring(a, d.unit, u, rA, slope, nullptr, u, 0);
        cap(a, -d.unit, ringA, true, segment->color);
    }

    for (;;) {
        const std::uint32_t following = next_[s];
        std::uint32_t ringB;
        bool apexB = false;
        Vec3 uNext;
        Direction dNext;
        double rNext = 0, slopeNext = 0;
        if (following == kNoSegment) {
            apexB = rB == 0;
            ringB = apexB ? out.vertex(b, d.unit) : ring(b, d.unit, u, rB, slope, nullptr, u, 0);
        } else {
            dNext = directionOf(segments[following]);
            rNext = radius(segments[following].width);
            slopeNext = (rNext - rB) / dNext.length;
            uNext = transport(u, d.unit, dNext.unit);
            ringB = ring(b, d.unit, u, rB, slope, &dNext.unit, uNext, slopeNext);
        }

        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t j = (i + 1) % n;
            const std::uint32_t ai = apexA ? ringA : ringA + i, aj = apexA ? ringA : ringA + j;
            const std::uint32_t bi = apexB ? ringB : ringB + i, bj = apexB ? ringB : ringB + j;
            // Counter-clockwise seen from outside: the ring runs from u towards d x u.
            if (!apexA) out.triangle(ai, aj, bj, segment->color);
            if (!apexB) out.triangle(ai, bj, bi, segment->color);
        }

        if (following == kNoSegment) {
            if (!apexB) cap(b, d.unit, ringB, false, segment->color);
            return;
        }
        s = following;
        segment = &segments[s];
        b = Vec3(segment->b);
        d = dNext;
        u = uNext;
        rA = rB;
        rB = rNext;
        slope = slopeNext;
        ringA = ringB;
        apexA = false;
    }
}

}  // namespace graftal
