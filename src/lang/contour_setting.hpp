// The view file's `contour: ID FILE` line: reads the .con file (beside the view file) into
// the view's contours, for @#(ID) to pick.
#pragma once

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/parser_target.hpp"

namespace graftal {

void loadContourSetting(ViewSettings& view, const ViewSetting& setting,
                        DiagnosticList& diagnostics);

}  // namespace graftal
