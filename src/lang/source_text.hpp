// Turns raw file bytes into lines the parser can read: checked to be text, comments
// blanked out (so columns stay true), every line numbered.
#pragma once

#include <map>
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
    // Lines joined into one (a block spanning lines): for the joined line's number, where
    // each physical line starts in its text and that line's number.
    struct Segment {
        std::size_t offset = 0;
        int line = 0;
    };
    std::map<int, std::vector<Segment>> joined;

    // `column` counts in the text of line `line`; joined lines map back to the file.
    SourceLocation at(int line, int column) const {
        auto it = joined.find(line);
        if (it == joined.end() || column < 1) return {fileName, line, column};
        const Segment* seg = &it->second.front();
        for (const auto& s : it->second)
            if (s.offset <= static_cast<std::size_t>(column - 1)) seg = &s;
        return {fileName, seg->line, column - static_cast<int>(seg->offset)};
    }
};

// A `//` comment starts at the beginning of a line or after white space when it is also
// followed by white space (or the line's end); anywhere else `//` is two roll modules, as
// in `F//&&leaf`. Returns false (with a diagnostic) when the bytes are not text.
bool prepareSource(std::string_view bytes, const std::string& fileName, SourceText& out,
                   DiagnosticList& diags);

// Joins a line that opens a statement block `{` it does not close with the lines that
// follow, up to the line that closes it (a production's or a Start: block written over
// several lines); a '{' after a production's arrow is a polygon and is left alone. And,
// as in cpfg, a line starting with a TAB continues the line before it.
void joinBlockLines(SourceText& text);

}  // namespace graftal
