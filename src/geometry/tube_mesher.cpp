// Segments to generalized cylinders: one tube per axis, rings shared at the joints, frames
// carried by parallel transport. See tube_mesher.hpp for the shape of the result.
#include "tube_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/parallel.hpp"
#include "graftal/core/vec3.hpp"

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

// Writes one axis at the places counted for its segments.
class Emitter {
  public:
    Emitter(Vec3f* positions, Vec3f* normals, std::uint32_t* indices, std::uint16_t* colors,
            std::uint32_t vertexBase)
        : positions_(positions),
          normals_(normals),
          indices_(indices),
          colors_(colors),
          vertexBase_(vertexBase) {}

    // Moves the cursors to a segment's own vertices and triangles.
    void seek(std::uint64_t vertex, std::uint64_t triangle) {
        vertex_ = vertex;
        triangle_ = triangle;
    }
    std::uint32_t vertex(const Vec3& p, const Vec3& n) {
        positions_[vertex_] = toVec3f(p);
        normals_[vertex_] = toVec3f(n);
        return vertexBase_ + static_cast<std::uint32_t>(vertex_++);
    }
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t color) {
        std::uint32_t* t = indices_ + 3 * triangle_;
        t[0] = a;
        t[1] = b;
        t[2] = c;
        colors_[triangle_++] = color;
    }

  private:
    Vec3f* positions_;
    Vec3f* normals_;
    std::uint32_t* indices_;
    std::uint16_t* colors_;
    std::uint32_t vertexBase_;
    std::uint64_t vertex_ = 0, triangle_ = 0;
};

}  // namespace

TubeMesher::TubeMesher(const Scene& scene, const MeshOptions& options)
    : scene_(scene), options_(options) {
    if (!options_.cylinders || scene_.segments.empty()) return;
    if (!(options_.curveRadius > 0)) options_.curveRadius = 0;
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
        // A curve is not looked through: the tubes on either side of it stay apart.
        const std::uint32_t p = segment.previous;
        if (p < s) previous_[s] = usable(p) || curve(p) ? p : previous_[p];

        const Direction d = directionOf(segment);
        const double rStart = startRadius(s), rEnd = radius(segment.width);
        if (d.length == 0 || (rStart == 0 && rEnd == 0)) continue;
        if (rEnd < options_.curveRadius) {
            flags_[s] = kCurve;
            ++curveCount_;
            continue;
        }
        flags_[s] = kUsable;

        const std::uint32_t before = previous_[s];
        if (before == kNoSegment || !usable(before) || !canJoin(before, s)) continue;
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

    firstVertex_.assign(count, 0);
    firstTriangle_.assign(count, 0);
    for (std::uint32_t s = 0; s < count; ++s) {
        firstVertex_[s] = vertexCount_;
        firstTriangle_[s] = triangleCount_;
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

struct TubeMesher::Output {
    Vec3f* positions;
    Vec3f* normals;
    std::uint32_t* indices;
    std::uint16_t* colors;
    std::uint32_t vertexBase;
};

void TubeMesher::append(Mesh& mesh, unsigned threads) const {
    if (vertexCount_ == 0) return;
    if (mesh.positions.size() + vertexCount_ > std::numeric_limits<std::uint32_t>::max())
        throw Error(SourceLocation{}, "the mesh would have more than 4294967295 vertices");
    const std::size_t v0 = mesh.positions.size(), t0 = mesh.triangleColor.size();
    mesh.positions.resize(v0 + vertexCount_);
    mesh.normals.resize(v0 + vertexCount_);
    mesh.indices.resize(3 * (t0 + triangleCount_));
    mesh.triangleColor.resize(t0 + triangleCount_);
    const Output out{mesh.positions.data() + v0, mesh.normals.data() + v0,
                     mesh.indices.data() + 3 * t0, mesh.triangleColor.data() + t0,
                     static_cast<std::uint32_t>(v0)};
    // Small scenes are not worth a thread.
    constexpr std::size_t kSegmentsPerThread = 4096;
    const std::size_t n = flags_.size();
    const std::size_t chunks =
        std::min<std::size_t>(threads == 0 ? defaultThreadCount() : threads,
                              (n + kSegmentsPerThread - 1) / kSegmentsPerThread);
    forEachChunk(n, chunks, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t s = begin; s < end; ++s)
            if (usable(static_cast<std::uint32_t>(s)) &&
                !joinedStart(static_cast<std::uint32_t>(s)))
                writeAxis(static_cast<std::uint32_t>(s), out);
    });
}

void TubeMesher::appendCurves(std::vector<CurveSegment>& curves) const {
    if (curveCount_ == 0) return;
    curves.reserve(curves.size() + curveCount_);
    // The index each curve got, for the curves that continue it.
    std::vector<std::uint32_t> index(flags_.size(), kNoSegment);
    const std::vector<Segment>& segments = scene_.segments;
    for (std::uint32_t s = 0; s < flags_.size(); ++s) {
        if (!curve(s)) continue;
        const Segment& segment = segments[s];
        CurveSegment c;
        c.a = toVec3f(segment.a);
        c.b = toVec3f(segment.b);
        c.radiusA = static_cast<float>(startRadius(s));
        c.radiusB = static_cast<float>(radius(segment.width));
        c.color = segment.color;
        // Continuing a curve that ends where this one starts: one joint, shared.
        const std::uint32_t p = previous_[s];
        if (p != kNoSegment && curve(p) && curves[index[p]].b == c.a) c.previous = index[p];
        index[s] = static_cast<std::uint32_t>(curves.size());
        curves.push_back(c);
    }
}

// One axis, from its first segment along next_. Rings are emitted once: each segment adds
// its end ring, which the next segment takes as its start ring.
void TubeMesher::writeAxis(std::uint32_t first, const Output& to) const {
    const std::vector<Segment>& segments = scene_.segments;
    const std::uint32_t n = static_cast<std::uint32_t>(cos_.size());
    Emitter out(to.positions, to.normals, to.indices, to.colors, to.vertexBase);
    out.seek(firstVertex_[first], firstTriangle_[first]);

    // A ring of radius r around `centre` in the plane perpendicular to the unit vector d,
    // leaned by the mitre towards `dn` when that is given. Normals follow the taper.
    auto ring = [&](const Vec3& centre, const Vec3& d, const Vec3& u, double r, double slope,
                    const Vec3* dn, const Vec3& un, double slopeN) {
        const Vec3 v = cross(d, u);
        const Vec3 vn = dn ? cross(*dn, un) : Vec3{};
        const double lean = dn ? 1 / (1 + dot(d, *dn)) : 0;
        // e is a unit vector across d, so e - slope * d has length sqrt(1 + slope^2)
        // around the whole ring.
        const double k = 1 / std::sqrt(1 + slope * slope);
        const double kn = 1 / std::sqrt(1 + slopeN * slopeN);
        std::uint32_t start = 0;
        for (std::uint32_t i = 0; i < n; ++i) {
            const Vec3 e = cos_[i] * u + sin_[i] * v;
            Vec3 normal = k * (e - slope * d);
            Vec3 p = centre + r * e;
            if (dn) {
                // Sliding along d onto the plane bisecting the joint puts the vertex on both
                // cylinders at once; the frames agree because `un` is u transported.
                p = p - (r * dot(e, *dn) * lean) * d;
                const Vec3 en = cos_[i] * un + sin_[i] * vn;
                const Vec3 sum = normal + kn * (en - slopeN * (*dn));
                const double l2 = dot(sum, sum);
                normal = l2 > 1e-24 ? (1 / std::sqrt(l2)) * sum : e;
            }
            const std::uint32_t index = out.vertex(p, normal);
            if (i == 0) start = index;
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
        out.seek(firstVertex_[s], firstTriangle_[s]);
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
