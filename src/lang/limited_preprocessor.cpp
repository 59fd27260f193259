// The preprocessor of the web build, where no mcpp can run (limited_preprocessor.hpp): the
// directives the book's models use, each line mapped back to the user's file as mcpp's
// output is. Also the test that decides whether a text needs a preprocessor at all, which
// both builds share.
#include "limited_preprocessor.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>
#include <set>
#include <vector>

#include "preprocessor.hpp"

namespace graftal {

namespace {

constexpr std::size_t kMaxPreprocessedBytes = 64u << 20;
constexpr std::size_t kPreprocessedPerInputByte = 16;
constexpr std::size_t kMinPreprocessedLimit = 256u << 10;
constexpr int kMaxExpansionDepth = 200;

bool isIdentifierStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}

bool isIdentifierChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::size_t skipBlanks(std::string_view s, std::size_t i) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    return i;
}

std::size_t identifierEnd(std::string_view s, std::size_t i) {
    while (i < s.size() && isIdentifierChar(s[i])) ++i;
    return i;
}

// A preprocessing number (C's pp-number): `2E` is one token, so a macro E is not expanded
// in it.
std::size_t ppNumberEnd(std::string_view s, std::size_t i) {
    ++i;
    while (i < s.size()) {
        const char c = s[i];
        if ((c == '+' || c == '-') && (s[i - 1] == 'e' || s[i - 1] == 'E' || s[i - 1] == 'p' ||
                                       s[i - 1] == 'P'))
            ++i;
        else if (isIdentifierChar(c) || c == '.')
            ++i;
        else
            break;
    }
    return i;
}

bool startsNumber(std::string_view s, std::size_t i) {
    return std::isdigit(static_cast<unsigned char>(s[i])) ||
           (s[i] == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])));
}

// Runs of blanks made one space, the ends trimmed: a replacement list as C defines it.
std::string normalisedBody(std::string_view body) {
    std::string out;
    bool blank = false;
    for (char c : body) {
        if (c == ' ' || c == '\t' || c == '\r') {
            blank = !out.empty();
            continue;
        }
        if (blank) out += ' ';
        blank = false;
        out += c;
    }
    return out;
}

struct Macro {
    bool functionLike = false;
    std::vector<std::string> parameters;
    std::string body;
    bool predefined = false;  // -D: not listed among the file's defines
};

struct Failure {
    std::string message;
    int column = 1;
};

class LimitedPreprocessor {
  public:
    LimitedPreprocessor(const PreprocessOptions& options, DiagnosticList& diags,
                        std::size_t limit)
        : options_(options), diags_(diags), limit_(limit) {
        for (const auto& [name, value] : options.defines)
            macros_[name] = Macro{false, {}, normalisedBody(value), true};
    }

    bool run(const SourceText& in, SourceText& out) {
        out.fileName = options_.fileName;
        out.lines.clear();
        out.defines.clear();
        struct Branch {
            bool active, taken, sawElse;
            int line;
        };
        std::vector<Branch> branches;
        const auto active = [&] { return branches.empty() || branches.back().active; };
        for (const SourceLine& line : in.lines) {
            SourceLine produced;
            produced.number = static_cast<int>(out.lines.size()) + 1;
            produced.spans.push_back({1, options_.fileName, line.number, 1});
            const std::string_view text = line.text;
            std::size_t i = skipBlanks(text, 0);
            if (i < text.size() && text[i] == '#') {
                const std::size_t nameStart = skipBlanks(text, i + 1);
                const std::size_t nameEnd = identifierEnd(text, nameStart);
                const std::string directive(text.substr(nameStart, nameEnd - nameStart));
                const std::size_t operand = skipBlanks(text, nameEnd);
                const std::string_view rest = text.substr(operand);
                const SourceLocation at{options_.fileName, line.number,
                                        static_cast<int>(operand) + 1};
                if (directive == "if" || directive == "ifdef" || directive == "ifndef") {
                    bool value = false;
                    if (active()) {
                        if (directive == "if") {
                            if (!condition(rest, line.number, static_cast<int>(operand), value))
                                return false;
                        } else {
                            const std::string name(
                                rest.substr(0, identifierEnd(rest, 0)));
                            value = macros_.count(name) == (directive == "ifdef" ? 1u : 0u);
                        }
                    }
                    branches.push_back({active() && value, active() && value, false, line.number});
                } else if (directive == "elif" || directive == "else") {
                    if (branches.empty() || branches.back().sawElse) {
                        diags_.error(at, "#" + directive + " without a matching #if");
                        return false;
                    }
                    Branch& b = branches.back();
                    const bool outer =
                        branches.size() < 2 || branches[branches.size() - 2].active;
                    bool value = true;
                    if (directive == "elif" && outer && !b.taken &&
                        !condition(rest, line.number, static_cast<int>(operand), value))
                        return false;
                    b.active = outer && !b.taken && value;
                    b.taken = b.taken || b.active;
                    b.sawElse = directive == "else";
                } else if (directive == "endif") {
                    if (branches.empty()) {
                        diags_.error(at, "#endif without a matching #if");
                        return false;
                    }
                    branches.pop_back();
                } else if (!active()) {
                    // a directive in a skipped branch does nothing
                } else if (directive == "define") {
                    if (!define(rest, at)) return false;
                } else if (directive == "undef") {
                    const std::string name(rest.substr(0, identifierEnd(rest, 0)));
                    if (!options_.defines.count(name)) macros_.erase(name);
                } else if (directive == "error") {
                    diags_.error({options_.fileName, line.number, 1},
                                 "#error " + std::string(rest));
                    return false;
                } else if (directive == "include") {
                    diags_.error(at,
                                 "#include is not available in the web build (a model there is "
                                 "one file); the graftal command reads included files");
                    return false;
                } else if (directive == "pragma" || directive == "line" || directive.empty()) {
                    // nothing to do: cpfg's files use neither
                } else {
                    diags_.error({options_.fileName, line.number, static_cast<int>(i) + 1},
                                 "preprocessor: unknown directive '#" + directive + "'");
                    return false;
                }
            } else if (active()) {
                try {
                    expandLine(text, line.number, produced);
                } catch (const Failure& f) {
                    diags_.error({options_.fileName, line.number, f.column}, f.message);
                    return false;
                }
            }
            size_ += produced.text.size() + 1;
            if (size_ > limit_) {
                diags_.error({options_.fileName, line.number, 1},
                             "the preprocessed text grows past " + std::to_string(limit_ >> 10) +
                                 " KiB here: a macro expands to too much text (is it defined "
                                 "in terms of another several times over?)");
                return false;
            }
            out.lines.push_back(std::move(produced));
        }
        if (!branches.empty()) {
            diags_.error({options_.fileName, branches.back().line, 1},
                         "this #if has no #endif before the end of the file");
            return false;
        }
        for (const auto& [name, macro] : macros_)
            if (!macro.functionLike && !macro.predefined)
                out.defines[name] = macro.body.empty() ? "1" : macro.body;
        return true;
    }

  private:
    bool define(std::string_view rest, const SourceLocation& at) {
        const std::size_t nameEnd = identifierEnd(rest, 0);
        if (nameEnd == 0) {
            diags_.error(at, "preprocessor: #define needs a macro name");
            return false;
        }
        const std::string name(rest.substr(0, nameEnd));
        if (options_.defines.count(name)) return true;  // the command line wins
        Macro macro;
        std::size_t i = nameEnd;
        if (i < rest.size() && rest[i] == '(') {
            macro.functionLike = true;
            const std::size_t close = rest.find(')', i);
            if (close == std::string_view::npos) {
                diags_.error(at, "preprocessor: the parameters of macro '" + name +
                                     "' need a closing ')'");
                return false;
            }
            std::size_t p = i + 1;
            while (p < close) {
                p = skipBlanks(rest, p);
                const std::size_t e = identifierEnd(rest, p);
                if (e == p) {
                    if (p == close) break;
                    diags_.error(at, "preprocessor: a parameter of macro '" + name +
                                         "' is not a name (variadic macros are not available "
                                         "in the web build)");
                    return false;
                }
                macro.parameters.emplace_back(rest.substr(p, e - p));
                p = skipBlanks(rest, e);
                if (p < close && rest[p] == ',') ++p;
            }
            i = close + 1;
        }
        macro.body = normalisedBody(rest.substr(i));
        if (macro.body.find('#') != std::string::npos && macro.functionLike) {
            diags_.error(at, "the # and ## operators of macro '" + name +
                                 "' are not available in the web build");
            return false;
        }
        macros_[name] = std::move(macro);
        return true;
    }

    // `text` with its macros expanded; `hidden` are the macros being expanded around it.
    std::string expand(std::string_view text, const std::set<std::string>& hidden, int depth,
                       int column) {
        if (depth > kMaxExpansionDepth)
            throw Failure{"a macro expands into itself too deeply", column};
        std::string out;
        std::size_t i = 0;
        while (i < text.size()) {
            const char c = text[i];
            if (c == '"') {
                const std::size_t end = std::min(skipStringLiteral(text, i) + 1, text.size());
                out.append(text.substr(i, end - i));
                i = end;
                continue;
            }
            if (startsNumber(text, i)) {
                const std::size_t end = ppNumberEnd(text, i);
                out.append(text.substr(i, end - i));
                i = end;
                continue;
            }
            if (!isIdentifierStart(c)) {
                out += c;
                ++i;
                continue;
            }
            const std::size_t end = identifierEnd(text, i);
            const std::string name(text.substr(i, end - i));
            std::size_t next = end;
            const std::optional<std::string> replaced =
                replacement(text, name, next, hidden, depth, column);
            if (!replaced) {
                out += name;
                i = end;
                continue;
            }
            out += *replaced;
            i = next;
            if (out.size() > limit_)
                throw Failure{"the preprocessed text grows past " + std::to_string(limit_ >> 10) +
                                  " KiB here: a macro expands to too much text (is it defined "
                                  "in terms of another several times over?)",
                              column};
        }
        return out;
    }

    // The expansion of the macro `name` whose name ends at `next` in `text` (moved past its
    // arguments), or nothing when `name` is no macro to expand there.
    std::optional<std::string> replacement(std::string_view text, const std::string& name,
                                           std::size_t& next, const std::set<std::string>& hidden,
                                           int depth, int column) {
        const auto it = macros_.find(name);
        if (it == macros_.end() || hidden.count(name)) return std::nullopt;
        const Macro& macro = it->second;
        std::set<std::string> inner = hidden;
        inner.insert(name);
        if (!macro.functionLike) return expand(macro.body, inner, depth + 1, column);
        std::size_t open = skipBlanks(text, next);
        if (open >= text.size() || text[open] != '(') return std::nullopt;  // the name alone
        std::vector<std::string> arguments(1);
        int nesting = 0;
        std::size_t p = open + 1;
        for (; p < text.size(); ++p) {
            const char c = text[p];
            if (c == '"') {
                const std::size_t end = std::min(skipStringLiteral(text, p), text.size() - 1);
                arguments.back().append(text.substr(p, end - p + 1));
                p = end;
                continue;
            }
            if (c == '(') ++nesting;
            if (c == ')' && nesting-- == 0) break;
            if (c == ',' && nesting == 0) {
                arguments.emplace_back();
                continue;
            }
            arguments.back() += c;
        }
        if (p >= text.size())
            throw Failure{"the call of macro '" + name +
                              "' needs its ')' on the same line in the web build",
                          column};
        next = p + 1;
        if (macro.parameters.empty() && arguments.size() == 1 &&
            normalisedBody(arguments[0]).empty())
            arguments.clear();
        if (arguments.size() != macro.parameters.size())
            throw Failure{"macro '" + name + "' takes " +
                              std::to_string(macro.parameters.size()) + " arguments, " +
                              std::to_string(arguments.size()) + " given",
                          column};
        for (std::string& a : arguments) a = expand(normalisedBody(a), hidden, depth + 1, column);
        // The parameters replaced by their expanded arguments, then the whole rescanned.
        std::string body;
        const std::string_view b = macro.body;
        for (std::size_t k = 0; k < b.size();) {
            if (b[k] == '"') {
                const std::size_t end = std::min(skipStringLiteral(b, k) + 1, b.size());
                body.append(b.substr(k, end - k));
                k = end;
            } else if (startsNumber(b, k)) {
                const std::size_t end = ppNumberEnd(b, k);
                body.append(b.substr(k, end - k));
                k = end;
            } else if (isIdentifierStart(b[k])) {
                const std::size_t end = identifierEnd(b, k);
                const auto word = b.substr(k, end - k);
                const auto param =
                    std::find(macro.parameters.begin(), macro.parameters.end(), word);
                body += param == macro.parameters.end()
                            ? std::string(word)
                            : arguments[static_cast<std::size_t>(param - macro.parameters.begin())];
                k = end;
            } else {
                body += b[k++];
            }
        }
        return expand(body, inner, depth + 1, column);
    }

    // One line's text with its macros expanded; each expansion is mapped to its call and
    // the text after it to its own column, as mcpp's annotations map them.
    void expandLine(std::string_view text, int lineNumber, SourceLine& out) {
        std::size_t i = 0;
        while (i < text.size()) {
            const char c = text[i];
            if (c == '"') {
                const std::size_t end = std::min(skipStringLiteral(text, i) + 1, text.size());
                out.text.append(text.substr(i, end - i));
                i = end;
                continue;
            }
            if (startsNumber(text, i)) {
                const std::size_t end = ppNumberEnd(text, i);
                out.text.append(text.substr(i, end - i));
                i = end;
                continue;
            }
            if (!isIdentifierStart(c)) {
                out.text += c;
                ++i;
                continue;
            }
            const std::size_t end = identifierEnd(text, i);
            const std::string name(text.substr(i, end - i));
            std::size_t next = end;
            const int column = static_cast<int>(i) + 1;
            const std::optional<std::string> replaced =
                replacement(text, name, next, {}, 0, column);
            if (!replaced) {
                out.text += name;
                i = end;
                continue;
            }
            const int at = static_cast<int>(out.text.size()) + 1;
            out.spans.push_back({at, options_.fileName, lineNumber, column});
            out.text += *replaced;
            out.spans.push_back({static_cast<int>(out.text.size()) + 1, options_.fileName,
                                 lineNumber, static_cast<int>(next) + 1});
            i = next;
        }
    }

    // ---- #if expressions: integers, as the C preprocessor computes them ----------------

    bool condition(std::string_view expression, int lineNumber, int offset, bool& value) {
        // `defined X` and `defined(X)` first, then the macros, then the arithmetic.
        std::string resolved;
        std::size_t i = 0;
        while (i < expression.size()) {
            if (isIdentifierStart(expression[i])) {
                const std::size_t end = identifierEnd(expression, i);
                if (expression.substr(i, end - i) == "defined") {
                    std::size_t p = skipBlanks(expression, end);
                    const bool paren = p < expression.size() && expression[p] == '(';
                    if (paren) p = skipBlanks(expression, p + 1);
                    const std::size_t nameEnd = identifierEnd(expression, p);
                    resolved += macros_.count(std::string(expression.substr(p, nameEnd - p)))
                                    ? " 1 "
                                    : " 0 ";
                    p = nameEnd;
                    if (paren) {
                        p = skipBlanks(expression, p);
                        if (p < expression.size() && expression[p] == ')') ++p;
                    }
                    i = p;
                    continue;
                }
                resolved.append(expression.substr(i, end - i));
                i = end;
                continue;
            }
            resolved += expression[i++];
        }
        try {
            expr_ = expand(resolved, {}, 0, offset + 1);
            pos_ = 0;
            const std::int64_t v = conditional();
            skip();
            if (pos_ < expr_.size()) throw Failure{"unexpected '" + expr_.substr(pos_) + "'", 0};
            value = v != 0;
            return true;
        } catch (const Failure& f) {
            diags_.error({options_.fileName, lineNumber, offset + 1},
                         "preprocessor: in #if: " + f.message);
            return false;
        }
    }

    void skip() { pos_ = skipBlanks(expr_, pos_); }

    bool accept(std::string_view op) {
        skip();
        if (expr_.compare(pos_, op.size(), op) != 0) return false;
        // `<` is not `<<` or `<=`, `&` not `&&`, `|` not `||`, `=`-less `!` not `!=`.
        if (op.size() == 1 && pos_ + 1 < expr_.size()) {
            const char n = expr_[pos_ + 1];
            if ((op == "<" || op == ">") && (n == op[0] || n == '=')) return false;
            if ((op == "&" || op == "|") && n == op[0]) return false;
            if (op == "!" && n == '=') return false;
        }
        pos_ += op.size();
        return true;
    }

    std::int64_t conditional() {
        const std::int64_t c = logicalOr();
        if (!accept("?")) return c;
        const std::int64_t a = conditional();
        if (!accept(":")) throw Failure{"expected ':' in a ?: expression", 0};
        const std::int64_t b = conditional();
        return c ? a : b;
    }

    std::int64_t logicalOr() {
        std::int64_t v = logicalAnd();
        while (accept("||")) v = (logicalAnd() != 0) || v;
        return v;
    }

    std::int64_t logicalAnd() {
        std::int64_t v = binary(0);
        while (accept("&&")) v = (binary(0) != 0) && v;
        return v;
    }

    // Levels from loosest to tightest: | ^ & (== !=) (< > <= >=) (<< >>) (+ -) (* / %).
    std::int64_t binary(int level) {
        static const std::vector<std::vector<std::string_view>> kLevels = {
            {"|"}, {"^"}, {"&"}, {"==", "!="}, {"<=", ">=", "<", ">"}, {"<<", ">>"},
            {"+", "-"}, {"*", "/", "%"}};
        if (level == static_cast<int>(kLevels.size())) return unary();
        std::int64_t v = binary(level + 1);
        for (;;) {
            std::string_view op;
            for (std::string_view candidate : kLevels[static_cast<std::size_t>(level)])
                if (accept(candidate)) {
                    op = candidate;
                    break;
                }
            if (op.empty()) return v;
            const std::int64_t w = binary(level + 1);
            if ((op == "/" || op == "%") && w == 0) throw Failure{"division by zero", 0};
            v = op == "|"    ? v | w
                : op == "^"  ? v ^ w
                : op == "&"  ? v & w
                : op == "==" ? v == w
                : op == "!=" ? v != w
                : op == "<=" ? v <= w
                : op == ">=" ? v >= w
                : op == "<"  ? v < w
                : op == ">"  ? v > w
                : op == "<<" ? static_cast<std::int64_t>(static_cast<std::uint64_t>(v) << (w & 63))
                : op == ">>" ? v >> (w & 63)
                : op == "+"  ? v + w
                : op == "-"  ? v - w
                : op == "*"  ? v * w
                : op == "/"  ? v / w
                             : v % w;
        }
    }

    std::int64_t unary() {
        if (accept("!")) return !unary();
        if (accept("-")) return -unary();
        if (accept("+")) return unary();
        if (accept("~")) return ~unary();
        if (accept("(")) {
            const std::int64_t v = conditional();
            if (!accept(")")) throw Failure{"expected ')'", 0};
            return v;
        }
        skip();
        if (pos_ < expr_.size() && isIdentifierStart(expr_[pos_])) {
            pos_ = identifierEnd(expr_, pos_);  // a name that is no macro counts as 0
            return 0;
        }
        if (pos_ < expr_.size() && std::isdigit(static_cast<unsigned char>(expr_[pos_]))) {
            const std::size_t end = ppNumberEnd(expr_, pos_);
            std::string digits = expr_.substr(pos_, end - pos_);
            while (!digits.empty() && (digits.back() == 'u' || digits.back() == 'U' ||
                                       digits.back() == 'l' || digits.back() == 'L'))
                digits.pop_back();
            std::size_t used = 0;
            std::int64_t v = 0;
            try {
                v = static_cast<std::int64_t>(std::stoull(digits, &used, 0));
            } catch (...) {
                used = 0;
            }
            if (used != digits.size() || digits.empty())
                throw Failure{"'" + expr_.substr(pos_, end - pos_) +
                                  "' is not an integer (#if computes with integers)",
                              0};
            pos_ = end;
            return v;
        }
        throw Failure{pos_ < expr_.size() ? "unexpected '" + expr_.substr(pos_) + "'"
                                          : std::string("the expression ends too soon"),
                      0};
    }

    const PreprocessOptions& options_;
    DiagnosticList& diags_;
    std::size_t limit_;
    std::size_t size_ = 0;
    std::map<std::string, Macro> macros_;
    std::string expr_;
    std::size_t pos_ = 0;
};

}  // namespace

bool needsPreprocessing(std::string_view text, const PreprocessOptions& options) {
    if (!options.defines.empty()) return true;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::size_t i = start;
        while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
        if (i < end && text[i] == '#') return true;
        start = end + 1;
    }
    return false;
}

bool preprocessLimited(std::string_view text, const PreprocessOptions& options, SourceText& out,
                       DiagnosticList& diags) {
    SourceText source;
    if (!prepareSource(text, options.fileName, source, diags)) return false;
    std::size_t limit = options.maxOutputBytes;
    if (limit == 0)
        limit = std::min(kMaxPreprocessedBytes,
                         kMinPreprocessedLimit + kPreprocessedPerInputByte * text.size());
    return LimitedPreprocessor(options, diags, limit).run(source, out);
}

#ifdef GRAFTAL_NO_MCPP
// The web build has no mcpp: every file goes through the limited preprocessor.
bool preprocessSource(std::string_view text, const PreprocessOptions& options, SourceText& out,
                      DiagnosticList& diags) {
    return preprocessLimited(text, options, out, diags);
}

bool mcppComparesWithinNames() {
    return true;
}
#endif

}  // namespace graftal
