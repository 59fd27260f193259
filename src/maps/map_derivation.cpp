// The two phases of a map L-system step (the book's chapter 5): every edge replaced by its
// successor, then the matching branches inside every cell connected and the others removed.
// The new map is built from scratch, the old one only read.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "graftal/maps/plane_map.hpp"

namespace graftal {

std::vector<std::uint32_t> PlaneMap::boundary(std::uint32_t r) const {
    std::vector<std::uint32_t> out;
    const std::uint32_t start = regionEdge[r];
    std::uint32_t h = start;
    do {
        out.push_back(h);
        h = next[h];
    } while (h != start && out.size() <= next.size());
    return out;
}

PlaneMap axiomMap(const MapLSystem& sys) {
    PlaneMap m;
    const std::size_t n = sys.axiom.size();
    // The axiom cycle runs clockwise, the cell on the right of its unreversed edges (read
    // counter-clockwise, no two branches of de Boer's listings ever meet): a regular
    // polygon, its first edge horizontal at the bottom, running right to left.
    for (std::size_t i = 0; i < n; ++i) {
        const double a = -std::numbers::pi / 2 + std::numbers::pi / static_cast<double>(n) -
                         2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
        m.position.push_back({std::cos(a), std::sin(a), 0});
        m.vertexSide.push_back(kCorner);
    }
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t u = static_cast<std::uint32_t>(i),
                      v = static_cast<std::uint32_t>((i + 1) % n);
        if (sys.axiom[i].reversed) std::swap(u, v);
        m.label.push_back(sys.axiom[i].label);
        m.tail.push_back(u);
        m.head.push_back(v);
        m.born.push_back(0);
        m.edgeSide.push_back(static_cast<std::int32_t>(i));
    }
    // The half-edge of edge i that runs from vertex i+1 back to vertex i bounds the cell
    // (counter-clockwise); its twin bounds the outside.
    auto cellHalf = [&](std::size_t i) {
        return static_cast<std::uint32_t>(2 * i + (sys.axiom[i].reversed ? 0 : 1));
    };
    m.next.assign(2 * n, 0);
    m.region.assign(2 * n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t before = (i + n - 1) % n, after = (i + 1) % n;
        m.next[cellHalf(i)] = cellHalf(before);
        m.region[cellHalf(i)] = 1;
        m.next[PlaneMap::twin(cellHalf(i))] = PlaneMap::twin(cellHalf(after));
        m.region[PlaneMap::twin(cellHalf(i))] = kOutside;
    }
    m.regionEdge = {PlaneMap::twin(cellHalf(0)), cellHalf(n - 1)};
    m.regionBorn = {0, 0};
    return m;
}

namespace {

// A branch waiting in a region for its partner.
struct Stub {
    std::uint32_t vertex;
    char label;
    bool towards;
};

// An element of a region's new boundary: a half-edge, or a branch (index into stubs).
struct Item {
    bool isStub;
    std::uint32_t index;
};

}  // namespace

PlaneMap deriveMapStep(const PlaneMap& old, const MapLSystem& sys,
                       const MapDerivationOptions& options, MapStepReport* report) {
    MapStepReport rep;
    PlaneMap m;
    m.step = old.step + 1;
    const std::size_t oldEdges = old.edgeCount();

    // Phase one: each edge becomes its successor's main axis; the axis's inner vertices and
    // edges are numbered in the order of the old edges.
    std::vector<const MapProduction*> prod(oldEdges);
    std::vector<std::uint32_t> firstVertex(oldEdges + 1), firstEdge(oldEdges + 1);
    std::size_t vertices = old.vertexCount(), edges = 0;
    for (std::size_t e = 0; e < oldEdges; ++e) {
        prod[e] = sys.production(old.label[e]);
        if (!prod[e])
            throw Error(SourceLocation{sys.file, 0, 0},
                        std::string("no production for edge label '") + old.label[e] + "'");
        firstVertex[e] = static_cast<std::uint32_t>(vertices);
        firstEdge[e] = static_cast<std::uint32_t>(edges);
        vertices += prod[e]->axis.size() - 1;
        edges += prod[e]->axis.size();
    }
    firstVertex[oldEdges] = static_cast<std::uint32_t>(vertices);
    firstEdge[oldEdges] = static_cast<std::uint32_t>(edges);

    m.position = old.position;
    m.vertexSide = old.vertexSide;
    m.position.resize(vertices);
    m.vertexSide.resize(vertices);
    m.label.resize(edges);
    m.tail.resize(edges);
    m.head.resize(edges);
    m.born.resize(edges);
    m.edgeSide.resize(edges);
    auto chainVertex = [&](std::size_t e, std::size_t k) -> std::uint32_t {
        const std::size_t n = prod[e]->axis.size();
        if (k == 0) return old.tail[e];
        if (k == n) return old.head[e];
        return static_cast<std::uint32_t>(firstVertex[e] + k - 1);
    };
    for (std::size_t e = 0; e < oldEdges; ++e) {
        const MapProduction& p = *prod[e];
        const std::size_t n = p.axis.size();
        const Vec3 a = old.position[old.tail[e]], b = old.position[old.head[e]];
        for (std::size_t k = 1; k < n; ++k) {
            const double t = static_cast<double>(k) / static_cast<double>(n);
            m.position[firstVertex[e] + k - 1] = a + (b - a) * t;
            m.vertexSide[firstVertex[e] + k - 1] = old.edgeSide[e];
        }
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t ne = firstEdge[e] + static_cast<std::uint32_t>(i);
            std::uint32_t u = chainVertex(e, i), v = chainVertex(e, i + 1);
            if (p.axis[i].reversed) std::swap(u, v);
            m.label[ne] = p.axis[i].label;
            m.tail[ne] = u;
            m.head[ne] = v;
            m.born[ne] = old.born[e];
            m.edgeSide[ne] = old.edgeSide[e];
        }
    }

    // Phase two, region by region: the region's new boundary with the branches that enter
    // it, the pairs that match, the new edges, and the walk that splits the region.
    m.next.assign(2 * edges, 0);
    std::vector<Item> items;
    std::vector<Stub> stubs;
    std::vector<std::size_t> stubItem;          // stub -> position in items
    std::vector<std::int64_t> partner;          // stub -> stub, or -1
    std::vector<std::uint32_t> stubOut;         // stub -> half-edge leaving its vertex
    std::vector<std::uint32_t> newRegionStart;  // per new region, a half-edge
    std::vector<int> newRegionBorn;
    std::vector<std::uint32_t> firstItemOfRegion;
    std::vector<std::uint32_t> regionOfHalf;  // filled after the walk
    struct Chord {
        std::uint32_t tail, head;
        char label;
    };
    std::vector<Chord> chords;
    // The next-pointers are set per region; the region walk follows them afterwards.
    std::vector<std::pair<std::uint32_t, int>> regionSeeds;  // (half-edge, born) in order

    for (std::uint32_t r = 0; r < old.regionCount(); ++r) {
        items.clear();
        stubs.clear();
        const bool outside = r == kOutside;
        for (std::uint32_t h : old.boundary(r)) {
            const std::uint32_t e = PlaneMap::edgeOf(h);
            const MapProduction& p = *prod[e];
            const std::size_t n = p.axis.size();
            const bool fwd = PlaneMap::forward(h);
            auto addStubs = [&](std::size_t k) {
                // Branches at axis vertex k on this half-edge's left: `+` along the edge,
                // `-` against it; written order along the edge, mirrored against it.
                const std::size_t nb = p.branches.size();
                for (std::size_t j = 0; j < nb; ++j) {
                    const MapBranch& b = p.branches[fwd ? j : nb - 1 - j];
                    if (b.vertex != k || b.left != fwd) continue;
                    if (outside) {
                        ++rep.outside;
                        continue;
                    }
                    items.push_back({true, static_cast<std::uint32_t>(stubs.size())});
                    stubs.push_back({chainVertex(e, k), b.label, b.towards});
                }
            };
            if (fwd) {
                for (std::size_t k = 0; k <= n; ++k) {
                    addStubs(k);
                    if (k < n)
                        items.push_back({false, 2 * (firstEdge[e] + static_cast<std::uint32_t>(k)) +
                                                    (p.axis[k].reversed ? 1u : 0u)});
                }
            } else {
                for (std::size_t k = n + 1; k-- > 0;) {
                    addStubs(k);
                    if (k > 0)
                        items.push_back(
                            {false, 2 * (firstEdge[e] + static_cast<std::uint32_t>(k - 1)) +
                                        (p.axis[k - 1].reversed ? 0u : 1u)});
                }
            }
        }

        // Matching: an away branch pairs with the next branch of its label counter-clockwise
        // around the region when that one points towards its axis.
        const std::size_t ns = stubs.size();
        partner.assign(ns, -1);
        if (ns > 1) {
            for (std::size_t i = 0; i < ns; ++i) {
                if (stubs[i].towards) continue;
                for (std::size_t d = 1; d < ns; ++d) {
                    const std::size_t j = (i + d) % ns;
                    if (stubs[j].label != stubs[i].label) continue;
                    if (stubs[j].towards && stubs[j].vertex != stubs[i].vertex) {
                        partner[i] = static_cast<std::int64_t>(j);
                        partner[j] = static_cast<std::int64_t>(i);
                    }
                    break;
                }
            }
            // Pairs whose edges would cross are both dropped.
            std::vector<char> crossing(ns, 0);
            for (std::size_t i = 0; i < ns; ++i) {
                if (partner[i] < 0 || static_cast<std::size_t>(partner[i]) < i) continue;
                const std::size_t j = static_cast<std::size_t>(partner[i]);
                for (std::size_t k = i + 1; k < j; ++k) {
                    if (partner[k] < 0) continue;
                    const std::size_t l = static_cast<std::size_t>(partner[k]);
                    if (l < i || l > j) crossing[i] = crossing[j] = crossing[k] = crossing[l] = 1;
                }
            }
            for (std::size_t i = 0; i < ns; ++i)
                if (crossing[i]) {
                    partner[i] = -1;
                    ++rep.crossing;
                }
        }
        stubOut.assign(ns, 0);
        std::size_t made = 0;
        for (std::size_t i = 0; i < ns; ++i) {
            if (partner[i] < 0) {
                ++rep.discarded;
                continue;
            }
            const std::size_t j = static_cast<std::size_t>(partner[i]);
            if (j < i) continue;
            const std::size_t a = stubs[i].towards ? j : i, t = stubs[i].towards ? i : j;
            const std::uint32_t ce = static_cast<std::uint32_t>(edges + chords.size());
            chords.push_back({stubs[a].vertex, stubs[t].vertex, stubs[a].label});
            stubOut[a] = 2 * ce;
            stubOut[t] = 2 * ce + 1;
            ++made;
        }
        rep.connected += made;

        // The new next-pointers: what leaves the corner after element i is element i + 1.
        std::size_t w = 0;
        for (const Item& it : items)
            if (!it.isStub || partner[it.index] >= 0) items[w++] = it;
        items.resize(w);
        if (m.next.size() < 2 * (edges + chords.size())) m.next.resize(2 * (edges + chords.size()));
        auto outOf = [&](const Item& it) { return it.isStub ? stubOut[it.index] : it.index; };
        auto inOf = [&](const Item& it) {
            return it.isStub ? PlaneMap::twin(stubOut[it.index]) : it.index;
        };
        for (std::size_t i = 0; i < w; ++i) m.next[inOf(items[i])] = outOf(items[(i + 1) % w]);
        // Seeds for numbering the pieces of this region: each element's outgoing half-edge,
        // in boundary order (the walk below skips those already numbered).
        const int born = made > 0 ? m.step : old.regionBorn[r];
        for (std::size_t i = 0; i < w; ++i) {
            regionSeeds.push_back({outOf(items[i]), born});
            if (items[i].isStub) regionSeeds.push_back({inOf(items[i]), born});
        }
    }

    for (std::size_t c = 0; c < chords.size(); ++c) {
        m.label.push_back(chords[c].label);
        m.tail.push_back(chords[c].tail);
        m.head.push_back(chords[c].head);
        m.born.push_back(m.step);
        m.edgeSide.push_back(kNotOnOutline);
    }
    const std::size_t totalEdges = m.label.size();
    m.next.resize(2 * totalEdges);

    // Number the regions: the walk from each seed in order; the outside is seeded first
    // (region 0's boundary came first) and stays region 0.
    constexpr std::uint32_t kUnset = 0xFFFFFFFFu;
    m.region.assign(2 * totalEdges, kUnset);
    for (const auto& [seed, born] : regionSeeds) {
        if (m.region[seed] != kUnset) continue;
        const std::uint32_t id = static_cast<std::uint32_t>(m.regionEdge.size());
        std::uint32_t h = seed;
        do {
            m.region[h] = id;
            h = m.next[h];
        } while (h != seed);
        m.regionEdge.push_back(seed);
        m.regionBorn.push_back(born);
    }
    if (report) *report = rep;
    if (options.geometry == MapGeometry::Relaxed) {
        int it = relaxMap(m, options);
        if (report) report->relaxIterations = it;
    }
    return m;
}

PlaneMap deriveMap(const MapLSystem& sys, int steps, const MapDerivationOptions& options,
                   const std::function<void(const PlaneMap&, const MapStepReport&)>& perStep) {
    PlaneMap m = axiomMap(sys);
    MapDerivationOptions early = options;
    early.relaxTolerance = std::max(options.relaxTolerance, options.relaxStartTolerance);
    for (int s = 0; s < steps; ++s) {
        MapStepReport rep;
        m = deriveMapStep(m, sys, s + 1 == steps ? options : early, &rep);
        if (perStep) perStep(m, rep);
    }
    return m;
}

}  // namespace graftal
