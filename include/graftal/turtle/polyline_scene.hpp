// The turtle's segments kept as polylines instead of Segment records: each point once, and
// runs of links that share a width and a colour. A turtle's path is mostly joined, so a
// segment costs one point (24 bytes) instead of a Segment (88 bytes) and the walk writes a
// quarter of the memory: what a live view needs to redraw a large model at every keystroke.
#pragma once

#include <cstdint>
#include <vector>

#include "graftal/core/module_string.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"

namespace graftal {

struct PolylineScene {
    // A run of `links` consecutive segments drawn with `width` and `color`, each going on
    // from the end of the one before; a jump (`jump`, links 1) moves the pen to the next
    // point without drawing.
    struct Run {
        std::uint32_t links = 0;
        float width = 1;
        std::uint16_t color = 0;
        bool jump = false;
    };
    // The polylines' points in drawing order: the first segment's start, then one end
    // point per link and one point per jump.
    std::vector<Vec3> points;
    std::vector<Run> runs;
    std::uint64_t segments = 0;
    // The box of the segments' finite end points (Scene::bounds() over the segments).
    Bounds segmentBounds;
    // The sum of inkLength() over the segments, in drawing order.
    double ink = 0;
    // Everything else the turtle made (polygons, discs, spheres, surfaces, generalized
    // cylinders), its base width, is3D and palette; `rest.segments` stays empty.
    Scene rest;

    // Scene::bounds() of the scene this one stands for.
    Bounds bounds() const;
    // Empties every buffer, keeping the memory for the next walk.
    void clear();
};

// What interpret(model, modules) draws, as polylines, into `out` (cleared first: its buffers
// are reused). Throws as interpret() does.
void interpretPolylines(const Model& model, const ModuleString& modules, PolylineScene& out);

}  // namespace graftal
