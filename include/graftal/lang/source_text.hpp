// Turns raw file bytes into lines the parser can read: checked to be text, comments
// blanked out (so columns stay true), every line numbered.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

// Where a piece of a line came from, for lines the preprocessor produced or lines joined
// into one: from `column` of the line on, the text is `file`'s line `line` from `fileColumn`.
struct SourceSpan {
    int column = 1;
    std::string file;
    int line = 0;
    int fileColumn = 1;
};

struct SourceLine {
    int number = 0;                 // 1-based
    std::string text;               // comments replaced by spaces
    std::vector<SourceSpan> spans;  // empty: the line is line `number` of the file
};

struct SourceText {
    std::string fileName;
    std::vector<SourceLine> lines;               // in increasing order of `number`
    std::map<std::string, std::string> defines;  // object-like #defines the preprocessor saw

    // The user's file, line and column of column `column` of the line numbered `line`
    // (through the line's spans when it was preprocessed or joined).
    SourceLocation at(int line, int column) const;
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

// When text[i] opens a string literal ("...", backslash escapes), the index of its closing
// quote (text.size() when it is not closed); any other i is returned as it is. The
// scanners that count brackets skip strings with it.
inline std::size_t skipStringLiteral(std::string_view text, std::size_t i) {
    if (i >= text.size() || text[i] != '"') return i;
    for (++i; i < text.size(); ++i) {
        if (text[i] == '\\')
            ++i;
        else if (text[i] == '"')
            return i;
    }
    return text.size();
}

}  // namespace graftal
