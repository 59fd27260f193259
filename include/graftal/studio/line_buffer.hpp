// The line buffer: the bytes the studio's 2D view and 3D line view draw (docs/studio.md
// lays it out): a 64-byte header, the palette, then the segments as polylines (each point
// once: x y, or x y z in a 3D scene, as 16-bit fractions of the bounding box; runs of links
// with their 16-bit width and palette index, or a jump), and filled triangles (9 floats
// each) with their RGBA colours.
#pragma once

#include <string>

#include "graftal/geometry/scene.hpp"
#include "graftal/turtle/polyline_scene.hpp"

namespace graftal::studio {

// The line buffer of a scene.
std::string encodeLines(const Scene& scene);

// The same bytes from the turtle's polylines (interpretPolylines() of the modules whose
// interpret() is the scene), without a Scene of every segment: what a keystroke costs.
std::string encodeLines(const PolylineScene& lines);

}  // namespace graftal::studio
