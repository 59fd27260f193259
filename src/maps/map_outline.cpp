// The outline rules of the relaxation (docs/maps.md, "The outline").
#include "map_outline.hpp"

#include <algorithm>
#include <cmath>

namespace graftal {

namespace {

// The outline's vertices in the order of the outside region's walk (clockwise around the
// layer, so the layer is on the right of the walk).
std::vector<std::uint32_t> outlineRing(const PlaneMap& m, std::vector<std::uint32_t>* halves) {
    std::vector<std::uint32_t> walk = m.boundary(kOutside), ring;
    ring.reserve(walk.size());
    for (std::uint32_t h : walk) ring.push_back(m.origin(h));
    if (halves) *halves = std::move(walk);
    return ring;
}

double cross2(const Vec3& a, const Vec3& b) {
    return a.x * b.y - a.y * b.x;
}

}  // namespace

void placeOutlineOnPolygon(PlaneMap& m) {
    const std::vector<std::uint32_t> ring = outlineRing(m, nullptr);
    const std::size_t n = ring.size();
    std::size_t first = n;
    for (std::size_t i = 0; i < n; ++i)
        if (m.vertexSide[ring[i]] == kCorner) {
            first = i;
            break;
        }
    if (first == n) return;
    std::size_t i = first;
    do {
        std::size_t j = (i + 1) % n;
        std::size_t between = 0;
        while (m.vertexSide[ring[j]] != kCorner) {
            j = (j + 1) % n;
            ++between;
        }
        const Vec3 a = m.position[ring[i]], b = m.position[ring[j]];
        for (std::size_t k = 1; k <= between; ++k)
            m.position[ring[(i + k) % n]] =
                a + (b - a) * (static_cast<double>(k) / static_cast<double>(between + 1));
        i = j;
    } while (i != first);
}

void moveGrowingOutline(PlaneMap& m) {
    // How much of its area deficit a cell makes up in one round, how far a vertex slides
    // towards the middle of its outline neighbours, and the longest move as a fraction of
    // the vertex's shorter outline wall.
    constexpr double kGain = 0.5, kSlide = 0.5, kLongestMove = 0.3;
    constexpr int kSmoothing = 4;
    std::vector<std::uint32_t> halves;
    const std::vector<std::uint32_t> ring = outlineRing(m, &halves);
    const std::size_t n = ring.size();
    if (n < 3) return;
    // The cells along the outline: their areas, and the length of outline each has.
    std::vector<double> area(m.regionCount(), 0), outline(m.regionCount(), 0);
    std::vector<char> along(m.regionCount(), 0);
    for (std::uint32_t h : halves) along[m.region[PlaneMap::twin(h)]] = 1;
    double meanArea = 0;
    std::size_t cells = 0;
    for (std::uint32_t c = 1; c < m.regionCount(); ++c) {
        if (!along[c]) continue;
        double twice = 0;
        for (std::uint32_t h : m.boundary(c))
            twice += cross2(m.position[m.origin(h)], m.position[m.target(h)]);
        area[c] = twice / 2;
        meanArea += area[c];
        ++cells;
    }
    meanArea /= static_cast<double>(std::max<std::size_t>(1, cells));
    std::vector<double> wallLength(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 d = m.position[ring[(i + 1) % n]] - m.position[ring[i]];
        wallLength[i] = std::sqrt(d.x * d.x + d.y * d.y);
        outline[m.region[PlaneMap::twin(halves[i])]] += wallLength[i];
    }
    // Outline wall i moves outwards by push[i]: the area the cell behind it gains, spread
    // over the cell's outline.
    std::vector<double> push(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t c = m.region[PlaneMap::twin(halves[i])];
        push[i] = outline[c] > 0 ? kGain * (meanArea - area[c]) / outline[c] : 0;
    }
    // Smoothed along the outline: neighbouring cells differ, the outline should not zigzag.
    std::vector<double> smooth(n);
    for (int pass = 0; pass < kSmoothing; ++pass) {
        for (std::size_t i = 0; i < n; ++i)
            smooth[i] = (push[(i + n - 1) % n] + 2 * push[i] + push[(i + 1) % n]) / 4;
        push.swap(smooth);
    }
    // A vertex the outline passes twice (a layer pinched to one vertex) stays.
    std::vector<int> visits(m.vertexCount(), 0);
    for (std::uint32_t v : ring) ++visits[v];
    std::vector<Vec3> moved(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t before = (i + n - 1) % n, after = (i + 1) % n;
        const Vec3 u = m.position[ring[before]], v = m.position[ring[i]],
                   w = m.position[ring[after]];
        moved[i] = v;
        if (visits[ring[i]] != 1) continue;
        Vec3 t = w - u;
        const double tl = std::sqrt(t.x * t.x + t.y * t.y);
        if (tl == 0) continue;
        t = t * (1 / tl);
        const Vec3 outward{-t.y, t.x, 0};  // the layer is on the right of the walk
        const Vec3 middle = (u + w) * 0.5;
        const double normal = (push[before] + push[i]) / 2;
        Vec3 d = (middle - v) * kSlide + outward * normal;
        const double dl = std::sqrt(d.x * d.x + d.y * d.y);
        const double longest = kLongestMove * std::min(wallLength[before], wallLength[i]);
        if (dl > longest) d = d * (longest / dl);
        moved[i] = v + d;
    }
    // The layer keeps its area: the rule shapes the outline, it does not grow or shrink it.
    double before = 0, after = 0;
    Vec3 centre{0, 0, 0};
    for (std::size_t i = 0; i < n; ++i) {
        before += cross2(m.position[ring[i]], m.position[ring[(i + 1) % n]]);
        after += cross2(moved[i], moved[(i + 1) % n]);
        centre = centre + moved[i];
    }
    centre = centre * (1.0 / static_cast<double>(n));
    // The walk runs clockwise: both sums are negative.
    const double scale = after < 0 && before < 0 ? std::sqrt(before / after) : 1.0;
    for (std::size_t i = 0; i < n; ++i) m.position[ring[i]] = centre + (moved[i] - centre) * scale;
}

}  // namespace graftal
