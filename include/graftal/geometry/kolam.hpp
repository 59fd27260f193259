// The pulli of a kolam (LSFP ch. 6.2): the grid of dots that the kolam's loops surround.
#pragma once

#include <vector>

#include "graftal/geometry/scene.hpp"

namespace graftal {

// The dots the turtle's path turns around, found from the straight path (before B-spline
// smoothing, with f moves drawn: `spline: path`). Along each run of consecutive segments,
// a stretch of turns all to the same side that adds up to half a turn or more is a loop,
// and its dot is the centre (the mean of the distinct corners) of the loop. Dots closer
// than a quarter of `stepLength` to one already found are the same dot. In drawing order.
std::vector<Vec3> kolamDots(const Scene& scene, double stepLength);

// kolamDots() added to the scene as filled discs of `radius` in colour `color`.
void addKolamDots(Scene& scene, double stepLength, double radius, std::uint16_t color = 0);

}  // namespace graftal
