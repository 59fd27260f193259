// B-spline smoothing of turtle paths: the uniform cubic B-spline of a control polygon, and
// the search for the chains of consecutive segments in a Scene whose points become the
// control polygons (the book's Figures 2.10 and 2.11).
#include "graftal/core/bit_cast.hpp"
#include "graftal/geometry/bspline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

namespace {

Vec3 combine(double w0, const Vec3& p0, double w1, const Vec3& p1, double w2, const Vec3& p2,
             double w3, const Vec3& p3) {
    return {w0 * p0.x + w1 * p1.x + w2 * p2.x + w3 * p3.x,
            w0 * p0.y + w1 * p1.y + w2 * p2.y + w3 * p3.y,
            w0 * p0.z + w1 * p1.z + w2 * p2.z + w3 * p3.z};
}

// p reflected through the point c: 2 c - p.
Vec3 mirrored(const Vec3& p, const Vec3& c) {
    return {2 * c.x - p.x, 2 * c.y - p.y, 2 * c.z - p.z};
}

// The uniform cubic B-spline span of four control points at t in [0, 1].
Vec3 spanPoint(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double t) {
    double t2 = t * t, t3 = t2 * t, u = 1 - t;
    return combine(u * u * u / 6, p0, (3 * t3 - 6 * t2 + 4) / 6, p1,
                   (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, p2, t3 / 6, p3);
}

void checkSubdivisions(int subdivisions) {
    if (subdivisions < 1)
        throw Error(SourceLocation{},
                    "B-spline smoothing needs at least 1 subdivision per "
                    "segment, got " +
                        std::to_string(subdivisions));
}

// Appends the points of one span after its start (t = 1/subdivisions .. 1).
void appendSpan(std::vector<Vec3>& out, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                const Vec3& p3, int subdivisions) {
    for (int k = 1; k <= subdivisions; ++k)
        out.push_back(spanPoint(p0, p1, p2, p3, static_cast<double>(k) / subdivisions));
}

// Exact coordinates as a hash key: the turtle writes a segment's start as a copy of the
// previous end, so consecutive segments meet bit for bit. Adding 0.0 folds -0 into +0.
struct PointKey {
    double x, y, z;
    friend bool operator==(const PointKey&, const PointKey&) = default;
};

struct PointKeyHash {
    std::size_t operator()(const PointKey& k) const {
        std::uint64_t h = bitCast<std::uint64_t>(k.x);
        h = h * 0x9E3779B97F4A7C15ull ^ bitCast<std::uint64_t>(k.y);
        h = h * 0x9E3779B97F4A7C15ull ^ bitCast<std::uint64_t>(k.z);
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

// Whether a chain returns to its start. The turtle reaches the start of a closed outline
// again only up to rounding (a Koch island closes to within 1e-12 or so), so this one test
// uses a tolerance relative to the chain's size.
bool returnsToStart(const std::vector<Segment>& segs, const std::vector<std::uint32_t>& chain) {
    Bounds box;
    for (std::uint32_t s : chain) box.extend(segs[s].b);
    double size =
        std::max({box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z, 1e-300});
    const Vec3& a = segs[chain.front()].a;
    const Vec3& b = segs[chain.back()].b;
    double gap = std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
    return gap <= 1e-9 * size;
}

bool finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

PointKey keyOf(const Vec3& p) {
    return {p.x + 0.0, p.y + 0.0, p.z + 0.0};
}

}  // namespace

std::vector<Vec3> bsplineCurve(std::span<const Vec3> cps, int subdivisions, bool closed) {
    checkSubdivisions(subdivisions);
    std::size_t n = cps.size();
    if (n <= 1) return {cps.begin(), cps.end()};
    std::vector<Vec3> out;
    if (closed && n >= 3) {
        out.reserve(n * static_cast<std::size_t>(subdivisions) + 1);
        out.push_back(spanPoint(cps[n - 1], cps[0], cps[1], cps[2], 0));
        for (std::size_t i = 0; i < n; ++i)
            appendSpan(out, cps[(i + n - 1) % n], cps[i], cps[(i + 1) % n], cps[(i + 2) % n],
                       subdivisions);
        out.back() = out.front();  // closed exactly, not up to rounding
        return out;
    }
    // Phantom points mirror the second and the last but one control point through the
    // ends. With them the spline starts at P0 (1/6 P-1 + 4/6 P0 + 1/6 P1 = P0) with the
    // weights of the real points still non-negative, so the curve stays in their hull.
    auto at = [&](std::ptrdiff_t i) -> Vec3 {
        if (i < 0) return mirrored(cps[1], cps[0]);
        if (i >= static_cast<std::ptrdiff_t>(n)) return mirrored(cps[n - 2], cps[n - 1]);
        return cps[static_cast<std::size_t>(i)];
    };
    out.reserve((n - 1) * static_cast<std::size_t>(subdivisions) + 1);
    out.push_back(cps[0]);
    for (std::ptrdiff_t i = 0; i + 1 < static_cast<std::ptrdiff_t>(n); ++i)
        appendSpan(out, at(i - 1), at(i), at(i + 1), at(i + 2), subdivisions);
    out.back() = cps[n - 1];  // exactly the end point, not up to rounding
    return out;
}

Scene smoothSegments(const Scene& scene, int subdivisions, ClosedChains closed) {
    checkSubdivisions(subdivisions);
    const std::vector<Segment>& segs = scene.segments;
    const std::size_t n = segs.size();
    const auto subs = static_cast<std::size_t>(subdivisions);
    if (n > std::size_t{kNoSegment} / subs)
        throw Error(SourceLocation{},
                    "B-spline smoothing of " + std::to_string(n) + " segments with " +
                        std::to_string(subdivisions) +
                        " subdivisions each would exceed the 32-bit segment indices; expected "
                        "fewer subdivisions");

    // The segment each one continues: its `previous` when that really ends where it starts,
    // else (no `previous` given) the latest earlier segment ending exactly there.
    std::vector<std::uint32_t> pred(n, kNoSegment);
    std::vector<char> explicitLink(n, 0);
    std::unordered_map<PointKey, std::uint32_t, PointKeyHash> lastEndingAt;
    lastEndingAt.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Segment& s = segs[i];
        if (s.previous != kNoSegment) {
            if (s.previous < i && segs[s.previous].b == s.a) {
                pred[i] = s.previous;
                explicitLink[i] = 1;
            }
        } else if (finite(s.a)) {
            auto it = lastEndingAt.find(keyOf(s.a));
            if (it != lastEndingAt.end()) pred[i] = it->second;
        }
        if (finite(s.b)) lastEndingAt[keyOf(s.b)] = static_cast<std::uint32_t>(i);
    }

    // Which successor carries a chain on: an explicit link beats a found one, and among
    // equals the later one wins (after "F[+F]F" the main axis is the F after the bracket).
    std::vector<std::uint32_t> next(n, kNoSegment);
    std::vector<char> nextExplicit(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t p = pred[i];
        if (p == kNoSegment) continue;
        if (next[p] == kNoSegment || explicitLink[i] || !nextExplicit[p]) {
            next[p] = static_cast<std::uint32_t>(i);
            nextExplicit[p] = explicitLink[i];
        }
    }

    Scene out = scene;
    out.segments.assign(n * subs, Segment{});
    std::vector<std::uint32_t> chain;
    std::vector<Vec3> points;
    // Heads in increasing order: a head's parent has a smaller index and so does the head
    // of the parent's chain, which is therefore smoothed before the branch that needs it.
    for (std::size_t head = 0; head < n; ++head) {
        std::uint32_t p = pred[head];
        if (p != kNoSegment && next[p] == head) continue;  // inside a chain, not its head
        chain.clear();
        for (auto s = static_cast<std::uint32_t>(head); s != kNoSegment; s = next[s])
            chain.push_back(s);

        const Segment& first = segs[chain.front()];
        bool periodic = closed == ClosedChains::Periodic && p == kNoSegment && chain.size() >= 3 &&
                        returnsToStart(segs, chain);
        points.clear();
        if (periodic) {
            for (std::uint32_t s : chain) points.push_back(segs[s].a);
        } else {
            // A branch starts where its smoothed parent passes, not where the parent's
            // control point was, or it would float beside the curve.
            points.push_back(p != kNoSegment ? out.segments[p * subs + subs - 1].b : first.a);
            for (std::uint32_t s : chain) points.push_back(segs[s].b);
        }
        std::vector<Vec3> curve = bsplineCurve(points, subdivisions, periodic);

        for (std::size_t j = 0; j < chain.size(); ++j) {
            const Segment& original = segs[chain[j]];
            std::size_t base = chain[j] * subs;
            for (std::size_t k = 0; k < subs; ++k) {
                Segment& piece = out.segments[base + k];
                piece = original;
                piece.a = curve[j * subs + k];
                piece.b = curve[j * subs + k + 1];
                if (k > 0) {
                    piece.previous = static_cast<std::uint32_t>(base + k - 1);
                } else if (original.previous != kNoSegment && original.previous < n) {
                    piece.previous =
                        static_cast<std::uint32_t>(original.previous * subs + subs - 1);
                } else {
                    piece.previous = kNoSegment;
                }
            }
        }
    }
    return out;
}

}  // namespace graftal
