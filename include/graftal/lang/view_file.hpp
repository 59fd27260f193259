// cpfg's view file (.v): the second front end. It reads the view settings cpfg keeps apart
// from the L-system and writes them through the same ParserTarget the .l parser uses, so the
// checks on each value live in one place (applyViewSetting).
#pragma once

#include <string>
#include <string_view>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/parser_target.hpp"

namespace graftal {

// Reads .v text line by line ("name: value"). Settings graftal knows go to
// target.viewSetting(); a bad value is an error at file:line:column naming the setting;
// a line graftal does not know, or knows but does not draw, is a warning at file:line.
void parseViewFileInto(std::string_view text, const std::string& fileName, ParserTarget& target,
                       DiagnosticList& diagnostics);

}  // namespace graftal
