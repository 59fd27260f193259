// cpfg's view file (.v): the second front end. It reads the view settings cpfg keeps apart
// from the L-system and writes them through the same ParserTarget the .l parser uses, so the
// checks on each value live in one place (applyViewSetting).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/parser_target.hpp"

namespace graftal {

// Reads .v text line by line ("name: value"). Settings graftal knows go to
// target.viewSetting(); a bad value is an error at file:line:column naming the setting;
// a line graftal does not know, or knows but does not draw, is a warning at file:line.
void parseViewFileInto(std::string_view text, const std::string& fileName, ParserTarget& target,
                       DiagnosticList& diagnostics);

// The one-letter names of the view file's `surface:` lines, in file order ("L" for
// `surface: L leaf.s 2`): cpfg reads `~LF` as the surface L then F, so the .l parser needs
// them before it reads the L-system (ParseOptions::surfaceLetters).
std::string viewFileSurfaceLetters(std::string_view text);

// The values of the view file's lines called `name` (lower case, as `function set`), in
// file order, trimmed; comments skipped.
std::vector<std::string> viewFileValues(std::string_view text, std::string_view name);

// Whether the view file has a `box:` line (see LSystem::cpfgViewBox).
bool viewFileGivesBox(std::string_view text);

}  // namespace graftal
