// cpfg's contours: the cross-sections of generalized cylinders (@Gs, @Gc, @Ge). A contour
// is a closed or open cubic B-spline over control points drawn in vlab's contour editor,
// kept in a `.con` file that the view file names with `contour: ID FILE`; `@#(ID)` makes it
// the cross-section of the next control points. The circle (id 0) needs no file.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/contour_shape.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/vec3.hpp"

namespace graftal {

// Reads a `.con` file. Three layouts are accepted, as cpfg reads them:
//   old:      `N DIM closed|open`, then N points of DIM (2 or 3) numbers;
//   cver 1 1: `cver 1 1`, `name: NAME`, `points: N TOTAL`, `type: open|closed`, then N
//             lines `x y z m` (the point repeated m times, TOTAL points in all);
//   cver 1 2 and 1 3: the same with `type: or|cr|oe|ce` (open/closed, regular/end
//             points), and for 1 3 a `samples: n` line, an optional `background:` line
//             and `markers: k` followed by k lines, before the points.
// Throws Error at `fileName`:line:column naming what was expected.
Contour parseContourFile(std::string_view text, const std::string& fileName, int id = 0);

// Reads a contour set (`.cset`, vlab's contour gallery): `contourgalleryver 1 1`, `items:
// k`, then k contours in the `cver` layouts above. cpfg itself never reads these (its view
// file names one `.con` per `contour:` line); lpfg does, giving the contours ids 1 to k in
// file order, and so does graftal. Throws Error at `fileName`:line:column.
std::vector<Contour> parseContourSet(std::string_view text, const std::string& fileName);

}  // namespace graftal
