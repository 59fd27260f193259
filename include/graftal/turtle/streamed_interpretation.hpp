// The turtle on a streamed derivation (streaming.hpp): counts, bounds and geometry of
// strings too large to hold, with memory proportional to the derivation depth.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal {

// What a streamed pass learns without keeping the string or the geometry.
struct StreamedMeasure {
    std::uint64_t modules = 0;
    std::vector<std::uint64_t> symbolCounts;  // indexed by symbol id
    std::uint64_t segments = 0, polygons = 0;
    Bounds bounds;   // of segment ends and polygon vertices
    double ink = 0;  // sum of inkLength() over the segments
    float baseWidth = 1;
    bool is3D = false;
};

// Derives depth-first and walks the turtle over the modules as they come (when
// `geometry`), keeping only counts and bounds; with `viewVolume` the bounds are cpfg's view
// volume (cpfgViewVolume()) instead of the drawing's box.
StreamedMeasure measureStreamed(const Model& model, int steps,
                                const DerivationOptions& options = {}, bool geometry = true,
                                bool viewVolume = false);

// The same counts and bounds for a string already derived, walking the turtle without
// storing any geometry (what `graftal stats` needs, at any size).
StreamedMeasure measureModules(const Model& model, const ModuleString& modules);

// cpfg's view volume of a derived string: the box cpfg writes (its `box` line), which is
// not the box of the drawn geometry: it holds the turtle's position wherever cpfg ends a
// segment (before every move drawn or not, at [ and ], { }, ~ and @, and at the end, so
// the origin is always inside), where @M lands, the squares of @o (at z = 0) and @c and
// the cube of @O; line widths do not count.
Bounds cpfgViewVolume(const Model& model, const ModuleString& modules);

// The Scene interpret(derive(...)) would give, built from a streamed derivation.
Scene interpretStreamed(const Model& model, int steps, const DerivationOptions& options = {});

// Receives what a streamed turtle draws, one primitive at a time, for a writer that never
// holds the geometry (the streamed PNG). A virtual call per primitive: drawing it costs far
// more.
class StreamedDrawing {
  public:
    virtual ~StreamedDrawing() = default;
    virtual void segment(const Segment& s) = 0;
    virtual void polygon(std::span<const Vec3> vertices, std::uint16_t color) = 0;
};

// Derives depth-first and hands every segment and polygon the turtle draws to `drawing`.
void drawStreamed(const Model& model, int steps, const DerivationOptions& options,
                  StreamedDrawing& drawing);

}  // namespace graftal
