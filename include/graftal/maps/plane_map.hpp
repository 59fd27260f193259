// The planar map a map L-system rewrites, and its derivation (the book's chapter 5).
//
// A half-edge structure: edge e is directed from tail(e) to head(e); its half-edge 2e runs
// along that direction and 2e + 1 against it. Every half-edge knows the region on its left
// and the next half-edge counter-clockwise around that region, so each edge knows its
// label, its direction and the two regions it separates. Region 0 is the unbounded region
// outside the layer; every other region is a cell. docs/maps.md explains the choices.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "graftal/core/vec3.hpp"
#include "graftal/maps/map_lsystem.hpp"

namespace graftal {

inline constexpr std::uint32_t kOutside = 0;       // the region outside the layer
inline constexpr std::int32_t kNotOnOutline = -1;  // an edge or vertex inside the layer
inline constexpr std::int32_t kCorner = -2;        // a vertex of the axiom's polygon

struct PlaneMap {
    // Vertices.
    std::vector<Vec3> position;
    // The side of the axiom's polygon a vertex lies on (kCorner for the polygon's own
    // vertices, kNotOnOutline inside): the relaxation slides outline vertices along it.
    std::vector<std::int32_t> vertexSide;
    // Edges.
    std::vector<char> label;
    std::vector<std::uint32_t> tail, head;
    std::vector<int> born;               // derivation step that made the wall (0 for the axiom)
    std::vector<std::int32_t> edgeSide;  // side of the axiom's polygon, or kNotOnOutline
    // Half-edges (2 per edge).
    std::vector<std::uint32_t> next;    // next half-edge around the region on the left
    std::vector<std::uint32_t> region;  // the region on the left
    // Regions: one half-edge of each, and the step it was made (0 for the axiom's cell).
    std::vector<std::uint32_t> regionEdge;
    std::vector<int> regionBorn;
    int step = 0;  // derivation steps done

    std::size_t vertexCount() const { return position.size(); }
    std::size_t edgeCount() const { return label.size(); }
    std::size_t regionCount() const { return regionEdge.size(); }  // cells + the outside
    std::size_t cellCount() const { return regionEdge.size() - 1; }

    static std::uint32_t edgeOf(std::uint32_t h) { return h >> 1; }
    static bool forward(std::uint32_t h) { return (h & 1u) == 0; }
    static std::uint32_t twin(std::uint32_t h) { return h ^ 1u; }
    std::uint32_t origin(std::uint32_t h) const {
        return forward(h) ? tail[edgeOf(h)] : head[edgeOf(h)];
    }
    std::uint32_t target(std::uint32_t h) const { return origin(twin(h)); }

    // The half-edges around region r, counter-clockwise for a cell (clockwise around the
    // layer for the outside), starting at regionEdge[r].
    std::vector<std::uint32_t> boundary(std::uint32_t r) const;
};

// The axiom as a map: one cell bounded by the axiom's edges, its vertices a regular polygon
// of circumradius 1 centred on the origin. The axiom cycle runs clockwise (the cell on the
// right of its unreversed edges), its first edge horizontal at the bottom.
PlaneMap axiomMap(const MapLSystem& sys);

// How new vertices are placed, and whether the vertices move after a step.
enum class MapGeometry {
    Siero,    // vertices stay where born (edges subdivided into equal parts)
    Relaxed,  // de Does and Lindenmayer: vertices settle at their neighbours' centre
};

// How the relaxation places the layer's outline (docs/maps.md, "The outline").
enum class MapOutline {
    Growing,  // outline walls move out or in until the cells along them have equal areas
    Polygon,  // the axiom's polygon: corners stay, the vertices of a side spread along it
};

struct MapDerivationOptions {
    MapGeometry geometry = MapGeometry::Siero;
    MapOutline outline = MapOutline::Growing;
    // Growing outline: rounds of (interior settled, outline moved) per step.
    int outlineRounds = 8;
    unsigned threads = 0;  // 0: all cores; the result never depends on it
    // Relaxation: conjugate-gradient iterations per step at most, and the root-mean-square
    // force left on a vertex (the sum of its wall vectors), relative to the mean wall
    // length, below which the layer counts as settled.
    int relaxIterations = 5000;
    // deriveMap settles the steps before the last only this far: the equilibrium depends on
    // the map alone, not on where its vertices were born, so the earlier steps only give
    // the last one a good start.
    double relaxStartTolerance = 3e-2;
    double relaxTolerance = 1e-3;
};

// Counts of what phase two did in one step.
struct MapStepReport {
    std::size_t connected = 0;  // matched pairs made into edges
    std::size_t discarded = 0;  // branches without a partner, removed
    std::size_t crossing = 0;   // matched branches dropped because their edge would cross
    std::size_t outside = 0;    // branches that entered the outside region, removed
    int relaxIterations = 0;    // iterations the relaxation took this step
};

// One derivation step: phase one replaces every edge by its successor, phase two connects
// the matching branches inside every cell and removes the rest. Throws Error when a label
// has no production (parseMapLSystem already rejects that).
PlaneMap deriveMapStep(const PlaneMap& map, const MapLSystem& sys,
                       const MapDerivationOptions& options, MapStepReport* report = nullptr);

// The axiom and `steps` steps; `perStep` (if given) sees each map after its step.
PlaneMap deriveMap(const MapLSystem& sys, int steps, const MapDerivationOptions& options = {},
                   const std::function<void(const PlaneMap&, const MapStepReport&)>& perStep = {});

// The de Does and Lindenmayer relaxation: each interior vertex at the centre of gravity of
// its neighbours, the outline placed by options.outline's rule. The interior's equilibrium is
// solved by conjugate gradients, in parallel, the same for any thread count. Returns the iterations
// done.
int relaxMap(PlaneMap& map, const MapDerivationOptions& options);

// Structural checks: twins, next/region consistency, every region boundary a simple cycle,
// the map connected with V - E + F = 2. Empty when the map is sound, else what is wrong.
std::string checkPlaneMap(const PlaneMap& map);

// Pairs of edges that cross (share a point other than a common end vertex), at most
// `limit`; for tests of the relaxation.
std::vector<std::pair<std::uint32_t, std::uint32_t>> crossingEdges(const PlaneMap& map,
                                                                   std::size_t limit = 16);

// The map as text (docs/maps.md): a header line with the counts, then one line per cell
// and one for the outside, each the cycle of its edges, `a12` the edge 12 labelled a
// traversed along its direction and `~a12` against it.
void writeMapText(const PlaneMap& map, std::ostream& out);

// What writeMapText's text says, read back (for tests and tools): for each region its
// cycle of (edge id, label, traversed along the edge). Throws Error on malformed text.
struct MapTextRegion {
    bool outside = false;
    std::vector<std::uint32_t> edges;
    std::vector<char> labels;
    std::vector<bool> along;
};
std::vector<MapTextRegion> readMapText(std::istream& in);

}  // namespace graftal
