// The cross-section points of a contour, sampled as cpfg samples them.
#pragma once

#include <vector>

#include "graftal/core/contour_shape.hpp"
#include "graftal/core/vec3.hpp"

namespace graftal {

// The points of a cross-section of radius 1 with `sides` sides: for a closed contour
// sides + 1 points, the last repeating the first; for an open one sides + 1 points from
// end to end. cpfg's method: the B-spline (periodic for closed contours, uniform for open
// ones) is measured at 10 points per span, and the points are spaced evenly along that
// length; a closed contour is turned about its centre so that it starts on the +x axis.
std::vector<Vec3> contourPoints(const Contour& contour, int sides);

// The default cross-section: `sides` points around the unit circle from (1, 0), and the
// first again (cpfg's contour 0).
std::vector<Vec3> circleContourPoints(int sides);

}  // namespace graftal
