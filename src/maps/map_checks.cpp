// What a sound map satisfies, checked from its arrays: for the tests and for `graftal
// stats`, which reports a broken map rather than drawing it.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "graftal/maps/plane_map.hpp"

namespace graftal {

std::string checkPlaneMap(const PlaneMap& m) {
    std::ostringstream why;
    const std::size_t nh = 2 * m.edgeCount();
    if (m.next.size() != nh || m.region.size() != nh) return "half-edge arrays of the wrong size";
    std::vector<char> seen(nh, 0);
    for (std::uint32_t h = 0; h < nh; ++h) {
        const std::uint32_t n = m.next[h];
        if (n >= nh) return "next out of range at half-edge " + std::to_string(h);
        if (m.target(h) != m.origin(n))
            return "half-edge " + std::to_string(h) + " is followed by one that starts elsewhere";
        if (m.region[n] != m.region[h])
            return "half-edge " + std::to_string(h) + " and its next bound different regions";
        if (seen[n]++) return "two half-edges are followed by half-edge " + std::to_string(n);
    }
    std::vector<char> visited(nh, 0);
    std::vector<std::uint32_t> lastSeen(m.vertexCount(), 0xFFFFFFFFu);
    for (std::uint32_t r = 0; r < m.regionCount(); ++r) {
        const auto cycle = m.boundary(r);
        if (m.next[cycle.back()] != cycle.front())
            return "region " + std::to_string(r) + " is open";
        for (std::uint32_t h : cycle) {
            if (m.region[h] != r) return "region " + std::to_string(r) + " has a foreign half-edge";
            if (visited[h]++) return "half-edge " + std::to_string(h) + " in two regions";
            const std::uint32_t v = m.origin(h);
            if (lastSeen[v] == r)
                return "region " + std::to_string(r) + " passes vertex " + std::to_string(v) +
                       " twice (its boundary is not a simple cycle)";
            lastSeen[v] = r;
        }
    }
    if (std::find(visited.begin(), visited.end(), 0) != visited.end())
        return "a half-edge belongs to no region";
    // Connected: union the ends of every edge.
    std::vector<std::uint32_t> parent(m.vertexCount());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (std::size_t e = 0; e < m.edgeCount(); ++e) parent[find(m.tail[e])] = find(m.head[e]);
    for (std::uint32_t v = 0; v < m.vertexCount(); ++v)
        if (find(v) != find(0)) return "vertex " + std::to_string(v) + " is not connected";
    const long long euler = static_cast<long long>(m.vertexCount()) -
                            static_cast<long long>(m.edgeCount()) +
                            static_cast<long long>(m.regionCount());
    if (euler != 2) {
        why << "V - E + F = " << m.vertexCount() << " - " << m.edgeCount() << " + "
            << m.regionCount() << " = " << euler << ", not 2";
        return why.str();
    }
    return {};
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> crossingEdges(const PlaneMap& m,
                                                                   std::size_t limit) {
    // A uniform grid over the layer's box; each edge is tested against the edges sharing a
    // grid cell with it.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    const std::size_t ne = m.edgeCount();
    if (ne == 0) return out;
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Vec3& p : m.position) {
        x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
        x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
    const std::size_t g = std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(double(ne))));
    const double cw = std::max(x1 - x0, 1e-300) / double(g),
                 ch = std::max(y1 - y0, 1e-300) / double(g);
    auto cellX = [&](double x) {
        return std::min<std::size_t>(g - 1, static_cast<std::size_t>(std::max(0.0, (x - x0) / cw)));
    };
    auto cellY = [&](double y) {
        return std::min<std::size_t>(g - 1, static_cast<std::size_t>(std::max(0.0, (y - y0) / ch)));
    };
    std::vector<std::vector<std::uint32_t>> grid(g * g);
    for (std::uint32_t e = 0; e < ne; ++e) {
        const Vec3 a = m.position[m.tail[e]], b = m.position[m.head[e]];
        for (std::size_t i = cellX(std::min(a.x, b.x)); i <= cellX(std::max(a.x, b.x)); ++i)
            for (std::size_t j = cellY(std::min(a.y, b.y)); j <= cellY(std::max(a.y, b.y)); ++j)
                grid[j * g + i].push_back(e);
    }
    auto cross = [](double ax, double ay, double bx, double by, double cx, double cy) {
        return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    };
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (const auto& cell : grid)
        for (std::size_t i = 0; i < cell.size(); ++i)
            for (std::size_t j = i + 1; j < cell.size(); ++j) {
                const std::uint32_t e = std::min(cell[i], cell[j]), f = std::max(cell[i], cell[j]);
                const std::uint32_t ends[4] = {m.tail[e], m.head[e], m.tail[f], m.head[f]};
                if (ends[0] == ends[2] || ends[0] == ends[3] || ends[1] == ends[2] ||
                    ends[1] == ends[3])
                    continue;  // walls meeting at a vertex
                const Vec3 a = m.position[ends[0]], b = m.position[ends[1]];
                const Vec3 c = m.position[ends[2]], d = m.position[ends[3]];
                const double d1 = cross(a.x, a.y, b.x, b.y, c.x, c.y);
                const double d2 = cross(a.x, a.y, b.x, b.y, d.x, d.y);
                const double d3 = cross(c.x, c.y, d.x, d.y, a.x, a.y);
                const double d4 = cross(c.x, c.y, d.x, d.y, b.x, b.y);
                if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) &&
                    ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
                    pairs.emplace_back(e, f);
            }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    if (pairs.size() > limit) pairs.resize(limit);
    return pairs;
}

}  // namespace graftal
