// The view file's `curve: FILE [samples]` line: reads the curve file (beside the view file)
// into the L-system's curves, for curveX/Y/Z(id, t) with ids in the order of those lines.
#pragma once

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/parser_target.hpp"

namespace graftal {

void loadCurveSetting(LSystem& lsystem, const ViewSetting& setting, DiagnosticList& diagnostics);

}  // namespace graftal
