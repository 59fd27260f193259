// A contour as a value: the cross-section of generalized cylinders that a `.con` file
// describes (contour.hpp reads and samples it). It lives with the core vocabulary so that
// the view settings, which hold the contours a view file loads, need nothing above it.
#pragma once

#include <string>
#include <vector>

#include "graftal/core/vec3.hpp"

namespace graftal {

struct Contour {
    int id = 0;
    std::string name;  // the file's `name:` line, or the file name
    // The file as a view file's `contour: ID FILE` line names it (empty for a contour set's).
    std::string file;
    bool closed = true;
    std::vector<Vec3> controlPoints;  // x, y across the cylinder (z is read, not drawn)
};

}  // namespace graftal
