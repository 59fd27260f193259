// Map L-systems: the derivation's two phases on hand-checked maps, the book's listings
// against the independent reference (scripts/reference_map_lsystem.py), the map's
// soundness at every step, the relaxation, the text form and the drawing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

#include "graftal/maps/map_drawing.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/maps/plane_map.hpp"

using namespace graftal;
namespace fs = std::filesystem;

namespace {

MapLSystem mapSystem(const std::string& text) {
    ParseOptions o;
    o.fileName = "m.l";
    return parseMapLSystem(text, o).orThrow();
}

MapLSystem example(const std::string& name) {
    return loadMapLSystem(fs::path(GRAFTAL_EXAMPLES_DIR) / name).orThrow();
}

// A square abcd (clockwise, the cell on the right of every edge) with the given
// productions for a, b, c, d; the other labels x, y map to themselves.
MapLSystem square(const std::string& a, const std::string& b, const std::string& c,
                  const std::string& d) {
    return mapSystem("map L-system:\naxiom: abcd\na --> " + a + "\nb --> " + b + "\nc --> " + c +
                     "\nd --> " + d + "\nx --> x\ny --> y\n");
}

PlaneMap oneStep(const MapLSystem& s, MapStepReport* rep = nullptr) {
    return deriveMapStep(axiomMap(s), s, MapDerivationOptions{}, rep);
}

// The edge labelled `label` (the first one).
std::uint32_t edgeLabelled(const PlaneMap& m, char label) {
    for (std::uint32_t e = 0; e < m.edgeCount(); ++e)
        if (m.label[e] == label) return e;
    return 0xFFFFFFFFu;
}

Vec3 midpoint(const Vec3& a, const Vec3& b) {
    return (a + b) * 0.5;
}

void expectNear(const Vec3& p, const Vec3& q) {
    EXPECT_NEAR(p.x, q.x, 1e-12);
    EXPECT_NEAR(p.y, q.y, 1e-12);
}

// tests/expected_map_counts.txt: file -> per step (vertices, edges, cells).
std::map<std::string, std::vector<std::array<std::size_t, 3>>> referenceCounts() {
    std::ifstream in(fs::path(GRAFTAL_TESTS_DIR) / "expected_map_counts.txt");
    std::map<std::string, std::vector<std::array<std::size_t, 3>>> r;
    std::string line, file;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        if (line.rfind("file ", 0) == 0) {
            file = line.substr(5);
            continue;
        }
        std::size_t step = 0, v = 0, e = 0, c = 0;
        ss >> step >> v >> e >> c;
        EXPECT_EQ(step, r[file].size());
        r[file].push_back({v, e, c});
    }
    return r;
}

}  // namespace

TEST(MapDerivation, TheAxiomIsOneCellOfAClockwiseRegularPolygon) {
    PlaneMap m = axiomMap(square("a", "b", "c", "d"));
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(m.vertexCount(), 4u);
    EXPECT_EQ(m.edgeCount(), 4u);
    EXPECT_EQ(m.cellCount(), 1u);
    // a runs along the bottom from right to left, b up the left side.
    EXPECT_GT(m.position[m.tail[0]].x, m.position[m.head[0]].x);
    EXPECT_NEAR(m.position[m.tail[0]].y, m.position[m.head[0]].y, 1e-12);
    EXPECT_LT(m.position[m.tail[1]].y, m.position[m.head[1]].y);
    std::ostringstream text;
    writeMapText(m, text);
    EXPECT_EQ(text.str(),
              "map: step 0, 4 vertices, 4 edges, 1 cells\ncell 1: ~d3 ~c2 ~b1 ~a0\n"
              "outside: a0 b1 c2 d3\n");
}

TEST(MapDerivation, OneMatchedPairSplitsItsRegion) {
    MapStepReport rep;
    PlaneMap m = oneStep(square("a[-x]a", "b", "c[-~x]c", "d"), &rep);
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(m.vertexCount(), 6u);
    EXPECT_EQ(m.edgeCount(), 7u);
    EXPECT_EQ(m.cellCount(), 2u);
    EXPECT_EQ(rep.connected, 1u);
    EXPECT_EQ(rep.discarded, 0u);
    // The new wall x runs from a's midpoint (its away branch) to c's (the towards one).
    PlaneMap axiom = axiomMap(square("a", "b", "c", "d"));
    const std::uint32_t x = edgeLabelled(m, 'x');
    ASSERT_NE(x, 0xFFFFFFFFu);
    expectNear(m.position[m.tail[x]], midpoint(axiom.position[0], axiom.position[1]));
    expectNear(m.position[m.head[x]], midpoint(axiom.position[2], axiom.position[3]));
    EXPECT_EQ(m.born[x], 1);
    // Both cells are new, four-sided, and x separates them.
    EXPECT_NE(m.region[2 * x], m.region[2 * x + 1]);
    EXPECT_NE(m.region[2 * x], kOutside);
    EXPECT_NE(m.region[2 * x + 1], kOutside);
    for (std::uint32_t r = 1; r <= 2; ++r) {
        EXPECT_EQ(m.boundary(r).size(), 4u);
        EXPECT_EQ(m.regionBorn[r], 1);
    }
}

TEST(MapDerivation, AnUnmatchedBranchIsDiscarded) {
    MapStepReport rep;
    // Both branches point away from their axis: no pair.
    PlaneMap m = oneStep(square("a[-x]a", "b", "c[-x]c", "d"), &rep);
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(m.cellCount(), 1u);
    EXPECT_EQ(m.edgeCount(), 6u);
    EXPECT_EQ(m.vertexCount(), 6u);
    EXPECT_EQ(rep.discarded, 2u);
    EXPECT_EQ(edgeLabelled(m, 'x'), 0xFFFFFFFFu);
    EXPECT_EQ(m.regionBorn[1], 0) << "an undivided cell keeps its age";
    // Different labels do not match either.
    m = oneStep(square("a[-x]a", "b", "c[-~y]c", "d"), &rep);
    EXPECT_EQ(m.cellCount(), 1u);
    EXPECT_EQ(rep.discarded, 2u);
}

TEST(MapDerivation, ABranchIntoTheOutsideIsRemoved) {
    MapStepReport rep;
    // `+` is the left of a, outside the square.
    PlaneMap m = oneStep(square("a[+x]a", "b", "c[+~x]c", "d"), &rep);
    EXPECT_EQ(m.cellCount(), 1u);
    EXPECT_EQ(rep.outside, 2u);
    EXPECT_EQ(rep.connected, 0u);
}

TEST(MapDerivation, TildeOnTheAxiomReversesAnEdge) {
    MapLSystem s = mapSystem("map L-system:\naxiom: ab~c\na --> a\nb --> b\nc --> c\n");
    PlaneMap m = axiomMap(s);
    EXPECT_EQ(checkPlaneMap(m), "");
    // a: 0 -> 1, b: 1 -> 2, c written ~c: it runs 0 -> 2 instead of 2 -> 0.
    EXPECT_EQ(m.tail[2], 0u);
    EXPECT_EQ(m.head[2], 2u);
    std::ostringstream text;
    writeMapText(m, text);
    EXPECT_EQ(text.str(),
              "map: step 0, 3 vertices, 3 edges, 1 cells\ncell 1: c2 ~b1 ~a0\n"
              "outside: a0 b1 ~c2\n");
}

TEST(MapDerivation, TildeOnTheAxisReversesOnePiece) {
    PlaneMap m = oneStep(square("x~y", "b", "c", "d"));
    EXPECT_EQ(checkPlaneMap(m), "");
    const std::uint32_t x = edgeLabelled(m, 'x'), y = edgeLabelled(m, 'y');
    const PlaneMap axiom = axiomMap(square("a", "b", "c", "d"));
    // a ran from vertex 0 to vertex 1; x keeps that direction, y turns round.
    EXPECT_EQ(m.tail[x], 0u);
    EXPECT_EQ(m.head[x], m.head[y]);
    EXPECT_EQ(m.tail[y], 1u);
    expectNear(m.position[m.head[x]], midpoint(axiom.position[0], axiom.position[1]));
}

TEST(MapDerivation, TildeOnABranchSetsTheNewWallsDirection) {
    // Now the branch on c points away and the one on a towards: x runs from c to a.
    PlaneMap m = oneStep(square("a[-~x]a", "b", "c[-x]c", "d"));
    const PlaneMap axiom = axiomMap(square("a", "b", "c", "d"));
    const std::uint32_t x = edgeLabelled(m, 'x');
    ASSERT_NE(x, 0xFFFFFFFFu);
    expectNear(m.position[m.tail[x]], midpoint(axiom.position[2], axiom.position[3]));
    expectNear(m.position[m.head[x]], midpoint(axiom.position[0], axiom.position[1]));
}

TEST(MapDerivation, SeveralCandidatesTheNextCounterClockwiseWins) {
    // One away branch (on a) and two towards branches (on b and c). Counter-clockwise
    // around the cell after a come d, c, b: the away branch pairs with c's.
    MapStepReport rep;
    PlaneMap m = oneStep(square("a[-x]a", "b[-~x]b", "c[-~x]c", "d"), &rep);
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(rep.connected, 1u);
    EXPECT_EQ(rep.discarded, 1u);
    const PlaneMap axiom = axiomMap(square("a", "b", "c", "d"));
    const std::uint32_t x = edgeLabelled(m, 'x');
    expectNear(m.position[m.head[x]], midpoint(axiom.position[2], axiom.position[3]));
}

TEST(MapDerivation, TwoPairsWhoseWallsWouldCrossAreBothDropped) {
    MapStepReport rep;
    PlaneMap m = oneStep(square("a[-x]a", "b[-y]b", "c[-~x]c", "d[-~y]d"), &rep);
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(m.cellCount(), 1u);
    EXPECT_EQ(rep.crossing, 4u);
    EXPECT_EQ(rep.connected, 0u);
    // Two pairs that do not cross both connect: three cells.
    m = oneStep(square("a[-x]a[-y]a", "b", "c[-~y]c[-~x]c", "d"), &rep);
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(m.cellCount(), 3u);
    EXPECT_EQ(rep.connected, 2u);
}

TEST(MapDerivation, BranchesAtOneVertexDoNotPairWithEachOther) {
    MapStepReport rep;
    PlaneMap m = oneStep(square("a[-x][-~x]a", "b", "c", "d"), &rep);
    EXPECT_EQ(m.cellCount(), 1u);
    EXPECT_EQ(rep.connected, 0u);
    EXPECT_EQ(rep.discarded, 2u);
}

TEST(MapDerivation, CountsMatchTheIndependentReference) {
    const auto reference = referenceCounts();
    ASSERT_EQ(reference.size(), 3u);
    for (const auto& [file, steps] : reference) {
        SCOPED_TRACE(file);
        MapLSystem s = example(file);
        PlaneMap m = axiomMap(s);
        for (std::size_t k = 0; k < steps.size(); ++k) {
            SCOPED_TRACE("step " + std::to_string(k));
            if (k > 0) m = deriveMapStep(m, s, {});
            EXPECT_EQ(m.vertexCount(), steps[k][0]);
            EXPECT_EQ(m.edgeCount(), steps[k][1]);
            EXPECT_EQ(m.cellCount(), steps[k][2]);
        }
    }
}

TEST(MapDerivation, EveryStepIsASoundPlanarMap) {
    for (const char* file :
         {"fig5.1-square-map.l", "fig5.2-cell-layer.l", "fig5.3-phascum-leaf.l"}) {
        SCOPED_TRACE(file);
        MapLSystem s = example(file);
        deriveMap(s, 12, {}, [&](const PlaneMap& m, const MapStepReport&) {
            SCOPED_TRACE("step " + std::to_string(m.step));
            // Euler's formula, every boundary a simple cycle, twins and regions agree.
            ASSERT_EQ(checkPlaneMap(m), "");
            EXPECT_EQ(m.vertexCount() - m.edgeCount() + m.regionCount(), 2u);
        });
    }
}

TEST(MapDerivation, Fig51IsASquareGrid) {
    PlaneMap m = deriveMap(example("fig5.1-square-map.l"), 4);
    EXPECT_EQ(m.cellCount(), 16u);
    for (std::uint32_t r = 1; r < m.regionCount(); ++r) {
        const auto b = m.boundary(r);
        std::size_t corners = 0;  // vertices where the boundary turns
        for (std::size_t i = 0; i < b.size(); ++i) {
            const Vec3 p = m.position[m.origin(b[i])], q = m.position[m.target(b[i])];
            const Vec3 o = m.position[m.origin(b[(i + b.size() - 1) % b.size()])];
            const double cross = (p.x - o.x) * (q.y - p.y) - (p.y - o.y) * (q.x - p.x);
            if (std::abs(cross) > 1e-12) ++corners;
        }
        EXPECT_EQ(corners, 4u) << "cell " << r;
    }
}

TEST(MapGeometry, SieroVerticesStayWhereTheyWereBorn) {
    MapLSystem s = example("fig5.2-cell-layer.l");
    PlaneMap before = deriveMap(s, 3);
    PlaneMap after = deriveMapStep(before, s, {});
    for (std::size_t v = 0; v < before.vertexCount(); ++v) {
        EXPECT_EQ(after.position[v].x, before.position[v].x);
        EXPECT_EQ(after.position[v].y, before.position[v].y);
    }
    // Each edge's new vertices divide it into equal parts: a --> c[-~a]x[+~b]g makes
    // thirds.
    const std::uint32_t a = edgeLabelled(before, 'a');
    PlaneMap one = deriveMapStep(axiomMap(s), s, {});
    const PlaneMap axiom = axiomMap(s);
    const std::uint32_t aAxiom = 2;  // gca: a is the third edge
    ASSERT_EQ(axiom.label[aAxiom], 'a');
    (void)a;
    const Vec3 p = axiom.position[axiom.tail[aAxiom]], q = axiom.position[axiom.head[aAxiom]];
    bool third = false, twoThirds = false;
    for (const Vec3& v : one.position) {
        if (std::hypot(v.x - (p.x + (q.x - p.x) / 3), v.y - (p.y + (q.y - p.y) / 3)) < 1e-12)
            third = true;
        if (std::hypot(v.x - (p.x + 2 * (q.x - p.x) / 3), v.y - (p.y + 2 * (q.y - p.y) / 3)) <
            1e-12)
            twoThirds = true;
    }
    EXPECT_TRUE(third);
    EXPECT_TRUE(twoThirds);
}

// Every interior vertex of `m` at the centre of gravity of its neighbours, within `tolerance`.
void expectInteriorSettled(const PlaneMap& m, double tolerance) {
    std::vector<Vec3> sum(m.vertexCount(), Vec3{0, 0, 0});
    std::vector<int> degree(m.vertexCount(), 0);
    for (std::size_t e = 0; e < m.edgeCount(); ++e) {
        sum[m.tail[e]] = sum[m.tail[e]] + m.position[m.head[e]];
        sum[m.head[e]] = sum[m.head[e]] + m.position[m.tail[e]];
        ++degree[m.tail[e]];
        ++degree[m.head[e]];
    }
    for (std::size_t v = 0; v < m.vertexCount(); ++v) {
        if (m.vertexSide[v] != kNotOnOutline) continue;
        const Vec3 c = sum[v] * (1.0 / degree[v]);
        ASSERT_NEAR(c.x, m.position[v].x, tolerance) << "vertex " << v;
        ASSERT_NEAR(c.y, m.position[v].y, tolerance) << "vertex " << v;
    }
}

// The area inside the outline (the outside region's walk runs clockwise around the layer).
double layerArea(const PlaneMap& m) {
    double twice = 0;
    for (std::uint32_t h : m.boundary(kOutside)) {
        const Vec3 a = m.position[m.origin(h)], b = m.position[m.target(h)];
        twice += a.x * b.y - a.y * b.x;
    }
    return -twice / 2;
}

TEST(MapGeometry, RelaxedMapsWithThePolygonOutlineKeepTheAxiomsPolygon) {
    MapDerivationOptions o;
    o.geometry = MapGeometry::Relaxed;
    o.outline = MapOutline::Polygon;
    for (auto [file, steps] : {std::pair{"fig5.2-cell-layer.l", 7},
                               {"fig5.3-phascum-leaf.l", 12},
                               {"fig5.1-square-map.l", 6}}) {
        SCOPED_TRACE(file);
        MapLSystem s = example(file);
        const PlaneMap axiom = axiomMap(s);
        PlaneMap m = deriveMap(s, steps, o);
        EXPECT_EQ(checkPlaneMap(m), "");
        EXPECT_TRUE(crossingEdges(m).empty());
        // Corners stay; outline vertices lie on their side of the axiom's polygon.
        for (std::size_t v = 0; v < axiom.vertexCount(); ++v)
            expectNear(m.position[v], axiom.position[v]);
        for (std::size_t v = 0; v < m.vertexCount(); ++v) {
            const std::int32_t side = m.vertexSide[v];
            if (side < 0) continue;
            const Vec3 a = axiom.position[axiom.tail[side]], b = axiom.position[axiom.head[side]];
            const Vec3 p = m.position[v];
            const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
            EXPECT_NEAR(cross, 0, 1e-9);
        }
        // Settled: every interior vertex is at the centre of gravity of its neighbours; the
        // default tolerance leaves vertices within a small fraction of a wall of that.
        MapDerivationOptions tight = o;
        tight.relaxTolerance = 1e-10;
        PlaneMap settled = deriveMap(s, steps, tight);
        expectInteriorSettled(settled, 1e-8);
        for (std::size_t v = 0; v < settled.vertexCount(); ++v) {
            EXPECT_NEAR(m.position[v].x, settled.position[v].x, 1e-3);
            EXPECT_NEAR(m.position[v].y, settled.position[v].y, 1e-3);
        }
    }
}

TEST(MapGeometry, TheGrowingOutlineLeavesTheAxiomsShapeWithoutCrossingOrCollapsing) {
    MapDerivationOptions o;
    o.geometry = MapGeometry::Relaxed;
    o.relaxTolerance = 1e-9;
    for (auto [file, steps] : {std::pair{"fig5.2-cell-layer.l", 7},
                               {"fig5.3-phascum-leaf.l", 12},
                               {"fig5.1-square-map.l", 6}}) {
        SCOPED_TRACE(file);
        MapLSystem s = example(file);
        const PlaneMap axiom = axiomMap(s);
        PlaneMap m = deriveMap(s, steps, o);
        EXPECT_EQ(checkPlaneMap(m), "");
        EXPECT_TRUE(crossingEdges(m).empty());
        expectInteriorSettled(m, 1e-6);
        // Neither collapsed nor blown up: the layer keeps the axiom's area.
        EXPECT_NEAR(layerArea(m), layerArea(axiom), 1e-9 * layerArea(axiom));
        // Not the axiom's polygon: some outline vertex lies well off every side of it.
        double farthest = 0;
        for (std::uint32_t h : m.boundary(kOutside)) {
            const Vec3 p = m.position[m.origin(h)];
            double nearest = 1e300;
            for (std::size_t e = 0; e < axiom.edgeCount(); ++e) {
                const Vec3 a = axiom.position[axiom.tail[e]], b = axiom.position[axiom.head[e]];
                const double len = std::hypot(b.x - a.x, b.y - a.y);
                nearest = std::min(
                    nearest, std::abs((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / len);
            }
            farthest = std::max(farthest, nearest);
        }
        EXPECT_GT(farthest, 0.1);
    }
}

TEST(MapGeometry, TheGrowingOutlineEvensOutTheCellsAlongIt) {
    // Fig 5.3 on the axiom's triangle crowds small cells along one side; the growing outline
    // makes the cells along the outline more alike in area.
    MapLSystem s = example("fig5.3-phascum-leaf.l");
    auto spread = [&](MapOutline outline) {
        MapDerivationOptions o;
        o.geometry = MapGeometry::Relaxed;
        o.outline = outline;
        PlaneMap m = deriveMap(s, 10, o);
        double smallest = 1e300, largest = 0;
        for (std::uint32_t h : m.boundary(kOutside)) {
            double twice = 0;
            for (std::uint32_t k : m.boundary(m.region[PlaneMap::twin(h)])) {
                const Vec3 a = m.position[m.origin(k)], b = m.position[m.target(k)];
                twice += a.x * b.y - a.y * b.x;
            }
            smallest = std::min(smallest, twice / 2);
            largest = std::max(largest, twice / 2);
        }
        return largest / smallest;
    };
    const double polygon = spread(MapOutline::Polygon), growing = spread(MapOutline::Growing);
    EXPECT_LT(growing, polygon / 4) << "polygon " << polygon << ", growing " << growing;
}

TEST(MapGeometry, RelaxationIsTheSameForAnyThreadCount) {
    // 40 threads are more than the map has blocks of rows to share (about 33,000 vertices
    // in blocks of 1024): some threads get none, and every thread boundary falls between
    // blocks that read each other's rows.
    MapLSystem s = example("fig5.2-cell-layer.l");
    for (MapOutline outline : {MapOutline::Growing, MapOutline::Polygon}) {
        MapDerivationOptions o;
        o.geometry = MapGeometry::Relaxed;
        o.outline = outline;
        std::vector<PlaneMap> maps;
        std::vector<std::vector<int>> iterations;
        for (unsigned t : {1u, 2u, 7u, 40u}) {
            o.threads = t;
            iterations.emplace_back();
            maps.push_back(deriveMap(s, 14, o, [&](const PlaneMap&, const MapStepReport& r) {
                iterations.back().push_back(r.relaxIterations);
            }));
        }
        ASSERT_GT(maps[0].vertexCount(), 32768u) << "large enough to be split among threads";
        EXPECT_GT(iterations[0].back(), 100) << "the last step settled by many iterations";
        for (std::size_t k = 1; k < maps.size(); ++k) {
            EXPECT_EQ(iterations[k], iterations[0]);
            ASSERT_EQ(maps[k].vertexCount(), maps[0].vertexCount());
            for (std::size_t v = 0; v < maps[0].vertexCount(); ++v) {
                ASSERT_EQ(maps[k].position[v].x, maps[0].position[v].x);
                ASSERT_EQ(maps[k].position[v].y, maps[0].position[v].y);
            }
        }
    }
}

TEST(MapText, DeriveTextReadsBackAsTheSameMap) {
    MapLSystem s = example("fig5.3-phascum-leaf.l");
    PlaneMap m = deriveMap(s, 10);
    std::stringstream text;
    writeMapText(m, text);
    std::vector<MapTextRegion> regions = readMapText(text);
    ASSERT_EQ(regions.size(), m.regionCount());
    EXPECT_EQ(std::count_if(regions.begin(), regions.end(),
                            [](const MapTextRegion& r) { return r.outside; }),
              1);
    // Every edge appears twice, once along it and once against, with one label; the
    // vertices are where consecutive edges of a cycle meet.
    std::map<std::uint32_t, std::pair<int, int>> uses;
    std::map<std::uint32_t, char> labels;
    std::vector<std::uint32_t> parent(2 * m.edgeCount());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    // End points: 2e is edge e's tail, 2e + 1 its head.
    for (const auto& r : regions) {
        for (std::size_t i = 0; i < r.edges.size(); ++i) {
            (r.along[i] ? uses[r.edges[i]].first : uses[r.edges[i]].second)++;
            labels[r.edges[i]] = r.labels[i];
            const std::size_t j = (i + 1) % r.edges.size();
            const std::uint32_t end = 2 * r.edges[i] + (r.along[i] ? 1 : 0);
            const std::uint32_t start = 2 * r.edges[j] + (r.along[j] ? 0 : 1);
            parent[find(end)] = find(start);
        }
    }
    ASSERT_EQ(uses.size(), m.edgeCount());
    for (const auto& [e, n] : uses) {
        EXPECT_EQ(n.first, 1) << e;
        EXPECT_EQ(n.second, 1) << e;
        EXPECT_EQ(labels[e], m.label[e]);
    }
    std::size_t vertices = 0;
    for (std::uint32_t p = 0; p < parent.size(); ++p) vertices += find(p) == p;
    EXPECT_EQ(vertices, m.vertexCount());
    std::istringstream bad("cell 1: a1 b\n");
    EXPECT_THROW(readMapText(bad), Error);
}

TEST(MapDrawing, WallsWidenWithAgeAndSplinesOutlineEachCell) {
    PlaneMap m = deriveMap(example("fig5.2-cell-layer.l"), 5);
    Scene straight = mapScene(m);
    ASSERT_EQ(straight.segments.size(), m.edgeCount());
    float widest = 0, thinnest = 1e9;
    for (const Segment& s : straight.segments) {
        widest = std::max(widest, s.width);
        thinnest = std::min(thinnest, s.width);
    }
    EXPECT_EQ(widest, 6.0f) << "the axiom's walls, five steps old";
    EXPECT_EQ(thinnest, 1.0f) << "walls made in the last step";
    EXPECT_EQ(straight.polygonCount(), 0u);

    MapDrawingOptions o;
    o.splines = true;
    o.splineSubdivisions = 4;
    o.fill = MapFill::Age;
    Scene smooth = mapScene(m, o);
    std::size_t sides = 0;
    for (std::uint32_t r = 1; r < m.regionCount(); ++r) sides += m.boundary(r).size();
    EXPECT_EQ(smooth.segments.size(), 4 * sides);
    EXPECT_EQ(smooth.polygonCount(), m.cellCount());
    // Closed curves: each cell's outline ends where it starts.
    EXPECT_EQ(smooth.segments.front().a.x, smooth.segments[4 * m.boundary(1).size() - 1].b.x);
}

TEST(MapDerivation, BranchesAtOneVertexKeepTheirWrittenOrder) {
    // Two branches on one side of one vertex stand in the order written, seen along the
    // predecessor: walked round the cell (against a and c), a's x comes after its y and
    // c's ~y after its ~x, so the pairs nest and both connect (a two-sided cell between).
    MapStepReport rep;
    PlaneMap m = oneStep(square("a[-x][-y]a", "b", "c[-~y][-~x]c", "d"), &rep);
    EXPECT_EQ(checkPlaneMap(m), "");
    EXPECT_EQ(rep.connected, 2u);
    EXPECT_EQ(m.cellCount(), 3u);
    // Written the other way round on c, the pairs would cross: both dropped.
    m = oneStep(square("a[-x][-y]a", "b", "c[-~x][-~y]c", "d"), &rep);
    EXPECT_EQ(rep.crossing, 4u);
    EXPECT_EQ(m.cellCount(), 1u);
}
