// Turns raw file bytes into lines the parser can read: checked to be text, comments
// blanked out (so columns stay true), every line numbered.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "graftal/diagnostics.hpp"

namespace graftal {

struct SourceLine {
    int number = 0;    // 1-based
    std::string text;  // comments replaced by spaces
};

struct SourceText {
    std::string fileName;
    std::vector<SourceLine> lines;

    SourceLocation at(int line, int column) const { return {fileName, line, column}; }
};

// A `//` comment starts at the beginning of a line or after white space when it is also
// followed by white space (or the line's end); anywhere else `//` is two roll modules, as
// in `F//&&leaf`. Returns false (with a diagnostic) when the bytes are not text.
bool prepareSource(std::string_view bytes, const std::string& fileName, SourceText& out,
                   DiagnosticList& diags);

}  // namespace graftal
