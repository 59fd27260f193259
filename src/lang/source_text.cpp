#include "graftal/lang/source_text.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>

namespace graftal {

namespace {

// Length of the valid UTF-8 sequence at s[i], or 0 when it is not one.
std::size_t utf8Length(std::string_view s, std::size_t i) {
    auto c = static_cast<unsigned char>(s[i]);
    std::size_t n = c < 0x80           ? 1
                    : (c >> 5) == 0x6  ? 2
                    : (c >> 4) == 0xE  ? 3
                    : (c >> 3) == 0x1E ? 4
                                       : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
    return n;
}

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

}  // namespace

bool prepareSource(std::string_view bytes, const std::string& fileName, SourceText& out,
                   DiagnosticList& diags) {
    out.fileName = fileName;
    out.lines.clear();

    // Text check first: a binary file gets one message, not hundreds of parse errors.
    int line = 1, column = 1;
    for (std::size_t i = 0; i < bytes.size();) {
        char c = bytes[i];
        auto uc = static_cast<unsigned char>(c);
        std::size_t n = utf8Length(bytes, i);
        if (n == 0 || (uc < 0x20 && c != '\n' && !isSpace(c)) || uc == 0x7F) {
            diags.error({fileName, line, column},
                        "this is not L-system text: found a binary byte 0x" +
                            std::string(1, "0123456789abcdef"[uc >> 4]) +
                            std::string(1, "0123456789abcdef"[uc & 15]) +
                            " (expected a .l file in ASCII or UTF-8)");
            return false;
        }
        if (c == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
        i += n;
    }

    std::string current;
    int number = 1;
    bool inBlock = false;
    int blockLine = 0, blockColumn = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        char c = bytes[i];
        if (c == '\n') {
            if (!current.empty() && current.back() == '\r') current.back() = ' ';
            out.lines.push_back({number++, std::move(current)});
            current.clear();
            continue;
        }
        if (inBlock) {
            if (c == '*' && i + 1 < bytes.size() && bytes[i + 1] == '/') {
                current += "  ";
                ++i;
                inBlock = false;
            } else {
                current += (c == '\t' ? '\t' : ' ');
            }
            continue;
        }
        if (c == '/' && i + 1 < bytes.size() && bytes[i + 1] == '*') {
            inBlock = true;
            blockLine = number;
            blockColumn = static_cast<int>(current.size()) + 1;
            current += "  ";
            ++i;
            continue;
        }
        if (c == '/' && i + 1 < bytes.size() && bytes[i + 1] == '/') {
            bool lineStart = true;
            for (char p : current)
                if (!isSpace(p)) lineStart = false;
            bool spaceBefore = current.empty() || isSpace(current.back());
            bool spaceAfter =
                i + 2 >= bytes.size() || isSpace(bytes[i + 2]) || bytes[i + 2] == '\n';
            if (lineStart || (spaceBefore && spaceAfter)) {
                while (i < bytes.size() && bytes[i] != '\n') ++i;
                --i;  // let the loop see the newline
                continue;
            }
        }
        current += c;
    }
    if (inBlock) {
        diags.error({fileName, blockLine, blockColumn},
                    "unterminated comment: expected '*/' before the end of the file");
        return false;
    }
    if (!current.empty()) out.lines.push_back({number, std::move(current)});
    return true;
}

namespace {

// The brace depth at the end of `line` (strings skipped), and whether the first '{' left
// open stands before a production's arrow (or there is no arrow).
int openBlockDepth(std::string_view line, bool& beforeArrow) {
    int depth = 0;
    std::size_t firstOpen = std::string_view::npos;
    std::vector<std::size_t> open;
    for (std::size_t i = 0; i < line.size(); ++i) {
        i = skipStringLiteral(line, i);
        if (i >= line.size()) break;
        char c = line[i];
        if (c == '"') {
            continue;
        } else if (c == '{') {
            open.push_back(i);
            ++depth;
        } else if (c == '}' && depth > 0) {
            open.pop_back();
            --depth;
        }
    }
    if (!open.empty()) firstOpen = open.front();
    std::size_t arrow = line.find("-->");
    beforeArrow = arrow == std::string_view::npos || firstOpen < arrow;
    return depth;
}

bool startsWithAxiom(std::string_view line) {
    std::size_t a = line.find_first_not_of(" \t");
    if (a == std::string_view::npos) return false;
    std::string head;
    for (std::size_t i = a; i < line.size() && i < a + 5; ++i)
        head += static_cast<char>(std::tolower(static_cast<unsigned char>(line[i])));
    return head == "axiom";
}

// A line's spans, or the one span of a line read straight from the file.
std::vector<SourceSpan> spansOf(const SourceText& text, const SourceLine& line) {
    if (!line.spans.empty()) return line.spans;
    return {SourceSpan{1, text.fileName, line.number, 1}};
}

}  // namespace

SourceLocation SourceText::at(int line, int column) const {
    auto it = std::lower_bound(lines.begin(), lines.end(), line,
                               [](const SourceLine& l, int n) { return l.number < n; });
    if (it == lines.end() || it->number != line || it->spans.empty() || column < 1)
        return {fileName, line, column};
    const SourceSpan* span = &it->spans.front();
    for (const auto& s : it->spans)
        if (s.column <= column) span = &s;
    return {span->file, span->line, span->fileColumn + std::max(0, column - span->column)};
}

void joinBlockLines(SourceText& text) {
    std::vector<SourceLine> out;
    for (std::size_t i = 0; i < text.lines.size(); ++i) {
        SourceLine line = std::move(text.lines[i]);
        bool joinedAny = false;
        const bool axiom = startsWithAxiom(line.text);
        while (i + 1 < text.lines.size()) {
            bool beforeArrow = false;
            bool openBlock = !axiom && openBlockDepth(line.text, beforeArrow) > 0 && beforeArrow;
            // cpfg: a line starting with a TAB continues the line before it.
            const std::string& next = text.lines[i + 1].text;
            bool continued = !next.empty() && next[0] == '\t' &&
                             line.text.find_first_not_of(" \t\r\f\v") != std::string::npos;
            if (!openBlock && !continued) break;
            SourceLine& more = text.lines[++i];
            if (!joinedAny) line.spans = spansOf(text, line);
            joinedAny = true;
            line.text += ' ';
            int base = static_cast<int>(line.text.size());
            for (SourceSpan s : spansOf(text, more)) {
                s.column += base;
                line.spans.push_back(std::move(s));
            }
            line.text += more.text;
        }
        out.push_back(std::move(line));
    }
    text.lines = std::move(out);
}

}  // namespace graftal
