// Map L-system text to MapLSystem: the book's listings (Figs 5.2, 5.3) as printed, with a
// `map L-system:` line first so the file reads as a sibling of the string L-systems.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "graftal/core/file_reading.hpp"
#include "graftal/lang/expression.hpp"
#include "graftal/lang/source_text.hpp"
#include "graftal/maps/map_lsystem.hpp"

namespace graftal {

namespace {

bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

bool isLabel(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

std::string lower(std::string_view s) {
    std::string r(s);
    for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

// The first non-blank column (0-based), or npos.
std::size_t firstNonBlank(const std::string& s, std::size_t from = 0) {
    for (std::size_t i = from; i < s.size(); ++i)
        if (!isBlank(s[i])) return i;
    return std::string::npos;
}

// `map L-system:` in its spellings (map Lsystem:, map L-system:), case-insensitive; the
// length of the marker including its colon, or 0.
std::size_t markerLength(std::string_view rest) {
    const std::string l = lower(rest);
    for (const char* m : {"map l-system:", "map lsystem:"})
        if (l.rfind(m, 0) == 0) return std::string_view(m).size();
    return 0;
}

// A keyword line `name:`: the column after its colon, or npos.
std::size_t keyword(const std::string& text, std::size_t start, std::string_view name) {
    const std::string l = lower(std::string_view(text).substr(start));
    if (l.rfind(std::string(name) + ":", 0) != 0) return std::string::npos;
    return start + name.size() + 1;
}

class MapParser {
  public:
    MapParser(const SourceText& src, const ParseOptions& options, DiagnosticList& diags)
        : src_(src), options_(options), diags_(diags) {}

    MapLSystem run() {
        MapLSystem sys;
        sys.file = src_.fileName;
        collectDefines();
        for (const auto& line : src_.lines) statement(line, sys);
        if (!sawMarker_)
            diags_.error({src_.fileName, 1, 1}, "expected 'map L-system:' as the first statement");
        if (!sawAxiom_)
            diags_.error({src_.fileName, src_.lines.empty() ? 1 : src_.lines.back().number, 1},
                         "the map L-system has no 'axiom:' line");
        // Every label an axiom or successor uses needs a production.
        for (const auto& [label, where] : uses_)
            if (!sys.production(label))
                diags_.error(where, std::string("unknown edge label '") + label +
                                        "': no production has it as predecessor");
        return sys;
    }

  private:
    SourceLocation at(int line, std::size_t column0) const {
        return src_.at(line, static_cast<int>(column0) + 1);
    }

    void collectDefines() {
        for (const auto& [k, v] : options_.defines) defines_[k] = v;
        for (const auto& line : src_.lines) {
            std::size_t s = firstNonBlank(line.text);
            if (s == std::string::npos || line.text.compare(s, 7, "#define") != 0) continue;
            std::size_t n = firstNonBlank(line.text, s + 7);
            std::size_t e = n;
            while (e < line.text.size() && !isBlank(line.text[e])) ++e;
            if (n == std::string::npos || n == s + 7) {
                diags_.error(at(line.number, s), "expected '#define NAME value'");
                continue;
            }
            std::string name = line.text.substr(n, e - n);
            std::size_t v = firstNonBlank(line.text, e);
            std::string value = v == std::string::npos ? "1" : line.text.substr(v);
            while (!value.empty() && isBlank(value.back())) value.pop_back();
            if (!options_.defines.count(name)) defines_[name] = value;
        }
    }

    void statement(const SourceLine& line, MapLSystem& sys) {
        const std::string& t = line.text;
        std::size_t s = firstNonBlank(t);
        if (s == std::string::npos) return;
        if (t.compare(s, 7, "#define") == 0) return;  // collectDefines took it
        if (t[s] == '#') {
            diags_.error(at(line.number, s),
                         "expected '#define NAME value' (no other # directive)");
            return;
        }
        if (std::size_t m = markerLength(std::string_view(t).substr(s))) {
            if (sawMarker_ || sawOther_)
                diags_.error(at(line.number, s), "'map L-system:' must be the first statement");
            sawMarker_ = true;
            (void)m;
            return;
        }
        if (!sawMarker_ && !sawOther_)
            diags_.error(at(line.number, s), "expected 'map L-system:' as the first statement");
        sawOther_ = true;
        if (ended_) {
            diags_.error(at(line.number, s), "text after 'endlsystem'");
            return;
        }
        if (lower(std::string_view(t).substr(s)).rfind("endlsystem", 0) == 0) {
            ended_ = true;
            return;
        }
        if (std::size_t c = keyword(t, s, "derivation length"); c != std::string::npos) {
            derivationLength(line, c, sys);
            return;
        }
        if (std::size_t c = keyword(t, s, "axiom"); c != std::string::npos) {
            axiom(line, c, sys);
            return;
        }
        production(line, s, sys);
    }

    void derivationLength(const SourceLine& line, std::size_t c, MapLSystem& sys) {
        std::size_t v = firstNonBlank(line.text, c);
        if (v == std::string::npos) {
            diags_.error(at(line.number, c), "expected a derivation length after ':'");
            return;
        }
        try {
            double n = evaluateConstant(line.text.substr(v), at(line.number, v), defines_);
            if (!(n >= 0) || n != static_cast<int>(n)) {
                diags_.error(at(line.number, v),
                             "the derivation length must be a whole number, 0 or more");
                return;
            }
            sys.derivationLength = static_cast<int>(n);
        } catch (const Error& e) {
            for (const auto& d : e.diagnostics()) diags_.add(d);
        }
    }

    void axiom(const SourceLine& line, std::size_t c, MapLSystem& sys) {
        if (sawAxiom_) diags_.error(at(line.number, c), "a second 'axiom:' line");
        sawAxiom_ = true;
        sys.axiom.clear();
        const std::string& t = line.text;
        for (std::size_t i = c; i < t.size(); ++i) {
            if (isBlank(t[i])) continue;
            std::size_t start = i;
            bool reversed = false;
            if (t[i] == '~') {
                reversed = true;
                ++i;
                while (i < t.size() && isBlank(t[i])) ++i;
            }
            if (i >= t.size() || !isLabel(t[i])) {
                diags_.error(at(line.number, i < t.size() ? i : start),
                             "expected an edge label (a letter or digit)" +
                                 std::string(reversed ? " after '~'" : "") + " in the axiom");
                return;
            }
            sys.axiom.push_back({t[i], reversed});
            uses_.emplace(t[i], at(line.number, i));
        }
        if (sys.axiom.empty())
            diags_.error(at(line.number, c),
                         "the axiom needs at least one edge (a cycle of labels)");
    }

    void production(const SourceLine& line, std::size_t s, MapLSystem& sys) {
        const std::string& t = line.text;
        std::size_t arrow = std::string::npos, arrowLen = 0;
        for (const char* a : {"-->", "->", "\xE2\x86\x92"}) {
            std::size_t p = t.find(a, s);
            if (p != std::string::npos && (arrow == std::string::npos || p < arrow)) {
                arrow = p;
                arrowLen = std::string_view(a).size();
            }
        }
        if (arrow == std::string::npos) {
            diags_.error(at(line.number, s),
                         "expected a production 'a --> successor', 'derivation length:' or "
                         "'axiom:'");
            return;
        }
        std::size_t p = s;
        std::size_t pe = arrow;
        while (pe > p && isBlank(t[pe - 1])) --pe;
        if (pe != p + 1 || !isLabel(t[p])) {
            diags_.error(at(line.number, p),
                         "expected one edge label (a letter or digit) before the arrow");
            return;
        }
        MapProduction prod;
        prod.predecessor = t[p];
        prod.location = at(line.number, p);
        if (sys.production(prod.predecessor)) {
            diags_.error(at(line.number, p),
                         std::string("a second production for edge '") + prod.predecessor + "'");
            return;
        }
        if (!successor(line, arrow + arrowLen, prod)) return;
        sys.productions[static_cast<unsigned char>(prod.predecessor)] = std::move(prod);
    }

    bool successor(const SourceLine& line, std::size_t from, MapProduction& prod) {
        const std::string& t = line.text;
        std::size_t i = from;
        auto skip = [&] {
            while (i < t.size() && isBlank(t[i])) ++i;
        };
        skip();
        const std::size_t successorStart = i;
        while (i < t.size()) {
            char c = t[i];
            if (c == '[') {
                std::size_t open = i;
                ++i;
                skip();
                MapBranch b;
                b.vertex = prod.axis.size();
                if (i < t.size() && (t[i] == '+' || t[i] == '-')) {
                    b.left = t[i] == '+';
                    ++i;
                    skip();
                } else {
                    diags_.error(at(line.number, i < t.size() ? i : open),
                                 "expected '+' or '-' at the start of a branch (which side of "
                                 "the axis it enters)");
                    return false;
                }
                if (i < t.size() && t[i] == '~') {
                    b.towards = true;
                    ++i;
                    skip();
                }
                if (i >= t.size() || !isLabel(t[i])) {
                    if (i < t.size() && t[i] == '[')
                        diags_.error(at(line.number, i), "a branch is one edge: no nested branch");
                    else
                        diags_.error(at(line.number, i < t.size() ? i : open),
                                     i < t.size() && t[i] == ']'
                                         ? "expected the branch's edge label before ']'"
                                         : "expected an edge label in the branch");
                    return false;
                }
                b.label = t[i];
                uses_.emplace(t[i], at(line.number, i));
                ++i;
                skip();
                if (i >= t.size()) {
                    diags_.error(at(line.number, open), "unbalanced bracket: '[' is not closed");
                    return false;
                }
                if (t[i] != ']') {
                    diags_.error(at(line.number, i),
                                 "a branch is one edge: expected ']' after its label");
                    return false;
                }
                ++i;
                prod.branches.push_back(b);
            } else if (c == ']') {
                diags_.error(at(line.number, i), "unbalanced bracket: ']' without '['");
                return false;
            } else if (c == '+' || c == '-') {
                diags_.error(at(line.number, i), std::string("'") + c +
                                                     "' belongs at the start of a branch, as in [" +
                                                     c + "a]");
                return false;
            } else if (c == '~' || isLabel(c)) {
                bool reversed = false;
                std::size_t at0 = i;
                if (c == '~') {
                    reversed = true;
                    ++i;
                    skip();
                }
                if (i >= t.size() || !isLabel(t[i])) {
                    diags_.error(at(line.number, i < t.size() ? i : at0),
                                 "expected an edge label after '~'");
                    return false;
                }
                prod.axis.push_back({t[i], reversed});
                uses_.emplace(t[i], at(line.number, i));
                ++i;
            } else if (isBlank(c)) {
                ++i;
            } else {
                diags_.error(at(line.number, i),
                             std::string("unexpected '") + c +
                                 "' in a successor (expected edge labels, '~', and branches "
                                 "[+a] [-~a])");
                return false;
            }
        }
        if (prod.axis.empty()) {
            diags_.error(at(line.number, successorStart < t.size() ? successorStart : from),
                         "a successor needs at least one edge on its main axis");
            return false;
        }
        return true;
    }

    const SourceText& src_;
    const ParseOptions& options_;
    DiagnosticList& diags_;
    std::map<std::string, std::string> defines_;
    std::multimap<char, SourceLocation> uses_;
    bool sawMarker_ = false, sawOther_ = false, sawAxiom_ = false, ended_ = false;
};

}  // namespace

bool MapParseResult::ok() const {
    return std::none_of(diagnostics.begin(), diagnostics.end(),
                        [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

std::vector<Diagnostic> MapParseResult::errors() const {
    std::vector<Diagnostic> r;
    for (const auto& d : diagnostics)
        if (d.severity == Severity::Error) r.push_back(d);
    return r;
}

std::vector<Diagnostic> MapParseResult::warnings() const {
    std::vector<Diagnostic> r;
    for (const auto& d : diagnostics)
        if (d.severity == Severity::Warning) r.push_back(d);
    return r;
}

MapLSystem MapParseResult::orThrow() && {
    if (!ok()) throw Error(errors());
    return std::move(system);
}

bool isMapLSystemText(std::string_view text) {
    SourceText src;
    DiagnosticList diags;
    if (!prepareSource(text, "", src, diags)) return false;
    for (const auto& line : src.lines) {
        std::size_t s = firstNonBlank(line.text);
        if (s == std::string::npos || line.text.compare(s, 7, "#define") == 0) continue;
        return markerLength(std::string_view(line.text).substr(s)) != 0;
    }
    return false;
}

bool isMapLSystemFile(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    std::string problem;
    const std::optional<std::string> text = readUserFile(path, problem);
    return text && isMapLSystemText(*text);
}

MapParseResult parseMapLSystem(std::string_view text, const ParseOptions& options) {
    MapParseResult r;
    DiagnosticList diags;
    SourceText src;
    if (prepareSource(text, options.fileName, src, diags)) {
        MapParser parser(src, options, diags);
        r.system = parser.run();
    }
    r.system.file = options.fileName;
    r.diagnostics = diags.items();
    return r;
}

MapParseResult loadMapLSystem(const std::filesystem::path& path, ParseOptions options) {
    if (options.fileName.empty()) options.fileName = path.string();
    std::string problem;
    const std::optional<std::string> text = readUserFile(path, problem);
    if (!text) {
        MapParseResult r;
        DiagnosticList diags;
        diags.error(SourceLocation{options.fileName, 0, 0}, problem);
        r.diagnostics = diags.items();
        return r;
    }
    return parseMapLSystem(*text, options);
}

std::string successorText(const MapProduction& p) {
    std::string s;
    std::size_t b = 0;
    auto branchesAt = [&](std::size_t v) {
        while (b < p.branches.size() && p.branches[b].vertex == v) {
            const MapBranch& br = p.branches[b++];
            s += '[';
            s += br.left ? '+' : '-';
            if (br.towards) s += '~';
            s += br.label;
            s += ']';
        }
    };
    for (std::size_t i = 0; i < p.axis.size(); ++i) {
        branchesAt(i);
        if (p.axis[i].reversed) s += '~';
        s += p.axis[i].label;
    }
    branchesAt(p.axis.size());
    return s;
}

}  // namespace graftal
