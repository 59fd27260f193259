// The .l language: cpfg's L-system files, and pfg's data files read verbatim. This file
// reads lines, declarations and keyword directives (see parser.hpp).
#include "parser.hpp"

#include "closest_word.hpp"
#include "view_setting_table.hpp"

#include "graftal/lang/model.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

namespace graftal {
namespace parsing {

std::string lower(std::string_view s) {
    std::string r(s);
    for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

bool isBlank(std::string_view s) {
    return s.find_first_not_of(" \t\r\f\v") == std::string_view::npos;
}

// Position of the first non-blank character, or npos.
std::size_t firstNonBlank(std::string_view s) {
    return s.find_first_not_of(" \t\r\f\v");
}

std::string_view trimView(std::string_view s) {
    std::size_t a = s.find_first_not_of(" \t\r\f\v");
    if (a == std::string_view::npos) return {};
    std::size_t b = s.find_last_not_of(" \t\r\f\v");
    return s.substr(a, b - a + 1);
}

// The keywords a line may start with, in the spelling the messages use: the grammar's,
// then the view settings a .l file states (from their table), then the global blocks.
const std::vector<std::string> kKeywords = [] {
    std::vector<std::string> k = {
        "lsystem", "derivation length", "axiom", "ignore",         "consider",    "age", "seed",
        "random",  "maximum depth",     "table", "table schedule", "environment",
    };
    for (const auto& name : lFileSettingNames()) k.push_back(name);
    for (const char* block : {"start", "starteach", "endeach", "end", "define"}) k.push_back(block);
    return k;
}();

// `-->` wins; then the book's `→`; then `->` (not the `<-` `>` of a context like `<->`).
Arrow findArrow(std::string_view s) {
    if (auto p = s.find("-->"); p != std::string_view::npos) return {p, 3};
    if (auto p = s.find("\xE2\x86\x92"); p != std::string_view::npos) return {p, 3};
    for (std::size_t p = s.find("->"); p != std::string_view::npos; p = s.find("->", p + 1))
        if (p == 0 || s[p - 1] != '<') return {p, 2};
    return {};
}

// Finds `c` outside parentheses, from `from`.
std::size_t findTopLevel(std::string_view s, char c, std::size_t from) {
    int depth = 0;
    for (std::size_t i = from; i < s.size(); ++i) {
        if (s[i] == '(')
            ++depth;
        else if (s[i] == ')')
            depth = std::max(0, depth - 1);
        else if (s[i] == c && depth == 0)
            return i;
    }
    return std::string_view::npos;
}

std::size_t findLastTopLevel(std::string_view s, char c) {
    int depth = 0;
    std::size_t found = std::string_view::npos;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '(')
            ++depth;
        else if (s[i] == ')')
            depth = std::max(0, depth - 1);
        else if (s[i] == c && depth == 0)
            found = i;
    }
    return found;
}

void Parser::run() {
    collectDeclarations();
    // The preprocessor has expanded every macro already; its object-like macros stay known
    // as the model's constants.
    for (const auto& [k, v] : src_.defines)
        if (!options_.defines.count(k)) defines_[k] = v;
    for (const auto& [k, v] : options_.defines) defines_[k] = v;
    target_.beginSource(src_.fileName, !sawLsystemHeader_);
    for (const auto& [k, v] : defines_) {
        auto line = defineLines_.find(k);
        bool fromFile = !options_.defines.count(k) && line != defineLines_.end();
        target_.define(k, v, fromFile ? src_.at(line->second, 1) : SourceLocation{});
    }
    parseGlobalBlocks();
    for (const auto& line : src_.lines) {
        parseLine(line);
        if (errorCount() >= kMaxErrors) {
            // A file that is not an L-system at all should not print a page per line.
            diags_.error(src_.at(line.number, 1), "too many errors; giving up on this file");
            return;
        }
    }
    finish();
}

SourceLocation Parser::at(const SourceLine& line, std::size_t offset) const {
    return src_.at(line.number, static_cast<int>(offset) + 1);
}

// Pass 1: #define and module declarations take effect wherever they stand, and the
// presence of an `Lsystem:` header decides between cpfg and legacy pfg files.
void Parser::collectDeclarations() {
    for (const auto& line : src_.lines) {
        std::string_view t = line.text;
        std::size_t start = firstNonBlank(t);
        if (start == std::string_view::npos) continue;
        std::string_view rest = t.substr(start);
        if (rest.rfind("#define", 0) == 0) {
            parseDefine(line, start);
        } else if (isModuleDeclaration(rest)) {
            parseModuleDeclaration(line, start);
        } else if (findArrow(rest).pos == std::string_view::npos) {
            std::size_t colon = rest.find(':');
            if (colon != std::string_view::npos &&
                normaliseKeyword(rest.substr(0, colon)) == "lsystem")
                sawLsystemHeader_ = true;
        }
    }
}

bool Parser::isModuleDeclaration(std::string_view rest) {
    for (std::string_view kw : {"modules", "module"}) {
        if (rest.size() > kw.size() && lower(rest.substr(0, kw.size())) == kw &&
            std::isspace(static_cast<unsigned char>(rest[kw.size()])) &&
            findArrow(rest).pos == std::string_view::npos &&
            rest.find(':') == std::string_view::npos)
            return true;
    }
    return false;
}

std::string Parser::normaliseKeyword(std::string_view s) {
    std::string out;
    bool space = false;
    for (char c : trimView(s)) {
        if (std::isspace(static_cast<unsigned char>(c))) {
            space = true;
            continue;
        }
        if (space && !out.empty()) out += ' ';
        space = false;
        out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return out;
}

void Parser::parseDefine(const SourceLine& line, std::size_t start) {
    std::string_view t = line.text;
    std::size_t p = start + 7;
    if (p < t.size() && !std::isspace(static_cast<unsigned char>(t[p]))) {
        diags_.error(at(line, start), "expected '#define NAME value'");
        return;
    }
    while (p < t.size() && std::isspace(static_cast<unsigned char>(t[p]))) ++p;
    std::size_t nameStart = p;
    while (p < t.size() && (std::isalnum(static_cast<unsigned char>(t[p])) || t[p] == '_')) ++p;
    if (p == nameStart || std::isdigit(static_cast<unsigned char>(t[nameStart]))) {
        diags_.error(at(line, nameStart), "expected a name after #define");
        return;
    }
    std::string name(t.substr(nameStart, p - nameStart));
    std::string value(trimView(t.substr(p)));
    if (value.empty()) value = "1";
    if (!options_.defines.count(name)) defines_[name] = value;
    defineLines_[name] = line.number;
}

void Parser::parseModuleDeclaration(const SourceLine& line, std::size_t start) {
    std::string_view t = line.text;
    std::size_t p = start;
    while (p < t.size() && std::isalpha(static_cast<unsigned char>(t[p]))) ++p;  // keyword
    std::size_t end = t.find(';', p);
    if (end == std::string_view::npos)
        end = t.size();
    else if (!isBlank(t.substr(end + 1)))
        diags_.error(at(line, end + 1), "unexpected text after ';' in a module declaration");
    std::size_t i = p;
    int count = 0;
    while (i < end) {
        char c = t[i];
        if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
            ++i;
            continue;
        }
        std::size_t s = i;
        if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_')) {
            diags_.error(at(line, i),
                         "expected a module name (letters, digits, '_') in "
                         "the declaration, found '" +
                             std::string(1, c) + "'");
            return;
        }
        while (i < end && (std::isalnum(static_cast<unsigned char>(t[i])) || t[i] == '_')) ++i;
        std::string_view name = t.substr(s, i - s);
        if (target_.symbols().size() >= kMaxSymbols && target_.symbols().find(name) < 0) {
            diags_.error(at(line, s), "too many module names: at most " +
                                          std::to_string(kMaxSymbols - kFirstDeclaredSymbol) +
                                          " multi-letter names (and ~surfaces) per file");
            return;
        }
        target_.declareModule(name, at(line, s));
        ++count;
        // cpfg allows an arity after the name, e.g. `module A(2)`; accept and skip it.
        while (i < end && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
        if (i < end && t[i] == '(') {
            std::size_t close = t.find(')', i);
            if (close == std::string_view::npos || close > end) {
                diags_.error(at(line, i), "expected ')' after the parameter count");
                return;
            }
            i = close + 1;
        }
    }
    if (count == 0) diags_.error(at(line, p), "expected module names after 'module'");
}

void Parser::parseLine(const SourceLine& line) {
    std::string_view t = line.text;
    std::size_t start = firstNonBlank(t);
    if (start == std::string_view::npos) return;
    std::string_view rest = t.substr(start);
    if (rest[0] == '#') {
        if (rest.rfind("#define", 0) == 0) return;  // pass 1 took it
        std::size_t e = 1;
        while (e < rest.size() && std::isalpha(static_cast<unsigned char>(rest[e]))) ++e;
        diags_.error(at(line, start), "unknown directive '" + std::string(rest.substr(0, e)) +
                                          "': expected '#define NAME value'");
        return;
    }
    if (isModuleDeclaration(rest)) return;
    Arrow arrow = findArrow(t);
    if (arrow.pos != std::string_view::npos) {
        if (ended_) {
            diags_.error(at(line, start), "production after 'endlsystem'");
            return;
        }
        parseProduction(line, arrow);
        return;
    }
    std::string word = normaliseKeyword(rest);
    if (word == "endlsystem") {
        ended_ = true;
        return;
    }
    if (word.rfind("map l-system:", 0) == 0 || word.rfind("map lsystem:", 0) == 0) {
        diags_.error(at(line, start),
                     "this file is a map L-system (docs/maps.md): graftal derive, stats and "
                     "render read it, not as a string L-system");
        return;
    }
    if (word == "ring lsystem" || word == "ring lsystem:") {
        target_.ring(at(line, firstNonBlank(line.text)));
        return;
    }
    // `decomposition`, `homomorphism`, with or without a colon, optionally followed by
    // `no warnings` (graftal never prints the maximum-depth warning anyway).
    for (const char* section : {"decomposition", "homomorphism"}) {
        std::string s(section);
        if (word == s || word == s + ":" || word == s + ": no warnings" ||
            word == s + " no warnings" || word == s + ":no warnings") {
            section_ = s == "decomposition" ? Section::Decomposition : Section::Homomorphism;
            currentTable_ = -1;
            return;
        }
    }
    std::size_t colon = t.find(':', start);
    if (colon != std::string_view::npos) {
        std::string kw = normaliseKeyword(t.substr(start, colon - start));
        bool known = std::find(kKeywords.begin(), kKeywords.end(), kw) != kKeywords.end();
        bool looksLikeKeyword = !kw.empty() && std::all_of(kw.begin(), kw.end(), [](char c) {
            return std::isalpha(static_cast<unsigned char>(c)) || c == ' ';
        });
        if (known) {
            parseDirective(line, kw, colon + 1);
            return;
        }
        if (looksLikeKeyword) {
            std::string typed = "unknown keyword '" +
                                std::string(trimView(t.substr(start, colon - start))) + ":'; ";
            if (std::string near = lang::closestWord(kw, kKeywords); !near.empty()) {
                diags_.error(at(line, start), typed + "did you mean '" + near + ":'?");
                return;
            }
            std::string list;
            for (const auto& k : kKeywords) list += (list.empty() ? "" : ", ") + k + ":";
            diags_.error(at(line, start), typed + "expected one of " + list);
            return;
        }
    }
    // A line without an arrow that is a misspelt keyword line (endlsytem) is reported as
    // one, not as a production.
    if (std::string near = lang::closestWord(word, {"endlsystem", "decomposition", "homomorphism"});
        !near.empty() && word.find(' ') == std::string::npos) {
        diags_.error(at(line, start), "unknown keyword '" + std::string(trimView(rest)) +
                                          "'; did you mean '" + near + "'?");
        return;
    }
    diags_.error(at(line, start),
                 "expected a production such as 'F --> F+F' (the arrow '-->' is missing) "
                 "or a keyword line such as 'axiom: F'");
}

bool Parser::constantValue(const SourceLine& line, std::size_t from, double& value) {
    std::string_view text = line.text;
    std::string_view v = text.substr(from);
    std::size_t off = firstNonBlank(v);
    if (off == std::string_view::npos) {
        diags_.error(at(line, text.size()), "expected a value after ':'");
        return false;
    }
    ExpressionScope scope;
    scope.defines = &defines_;
    DiagnosticList local;
    Expression e = compileExpression(trimView(v), at(line, from + off), scope, local);
    for (const auto& d : local.items()) diags_.add(d);
    if (e.empty()) return false;
    if (e.usesRandom()) {
        diags_.error(at(line, from + off), "a setting cannot use ran() or nran()");
        return false;
    }
    try {
        value = e.evaluate({});
    } catch (const Error& err) {
        for (const auto& d : err.diagnostics()) diags_.add(d);
        return false;
    }
    if (!std::isfinite(value)) {
        diags_.error(at(line, from + off), "the value is not a finite number");
        return false;
    }
    return true;
}

void Parser::parseDirective(const SourceLine& line, const std::string& kw, std::size_t valueStart) {
    std::string_view value = std::string_view(line.text).substr(valueStart);
    SourceLocation loc =
        at(line, valueStart +
                     (firstNonBlank(value) == std::string_view::npos ? 0 : firstNonBlank(value)));
    double v = 0;
    if (isGlobalBlockKeyword(kw)) {
        return;  // read by parseGlobalBlocks
    } else if (kw == "lsystem") {
        target_.name(std::string(trimView(value)), loc);
    } else if (kw == "derivation length") {
        if (!constantValue(line, valueStart, v)) return;
        if (v < 0 || v != std::floor(v) || v > 1e6) {
            diags_.error(loc,
                         "derivation length must be a whole number from 0 to 1000000, "
                         "not " +
                             formatNumber(v));
            return;
        }
        target_.derivationLength(static_cast<int>(v), loc);
    } else if (kw == "axiom") {
        if (sawAxiom_) {
            diags_.error(
                loc, "a second axiom (the first is on line " + std::to_string(axiomLine_) + ")");
            return;
        }
        sawAxiom_ = true;
        axiomLine_ = line.number;
        parseAxiom(line, valueStart);
    } else if (kw == "ignore" || kw == "consider") {
        parseIgnore(line, kw, valueStart);
    } else if (kw == "age") {
        parseAges(line, valueStart);
    } else if (kw == "maximum depth") {
        if (!constantValue(line, valueStart, v)) return;
        if (section_ == Section::Main) {
            diags_.error(at(line, firstNonBlank(line.text)),
                         "'maximum depth:' belongs in a decomposition or homomorphism section");
            return;
        }
        if (v < 1 || v != std::floor(v) || v > 10000) {
            diags_.error(loc, "maximum depth must be a whole number from 1 to 10000");
            return;
        }
        target_.maximumDepth(section_ == Section::Decomposition ? ProductionGroup::Decomposition
                                                                : ProductionGroup::Homomorphism,
                             static_cast<int>(v), loc);
    } else if (kw == "table") {
        std::string name(trimView(value));
        if (section_ != Section::Main) {
            diags_.error(loc,
                         "tables hold the main productions, not decomposition or homomorphism");
            return;
        }
        if (name.empty()) {
            diags_.error(loc, "expected a table name after 'table:'");
            return;
        }
        auto it = std::find(tableNames_.begin(), tableNames_.end(), name);
        if (it != tableNames_.end()) {
            diags_.error(loc, "table '" + name + "' is defined twice");
            return;
        }
        tableNames_.push_back(name);
        target_.table(name, loc);
        currentTable_ = static_cast<int>(tableNames_.size()) - 1;
    } else if (kw == "environment") {
        if (trimView(value).empty()) {
            diags_.error(loc, "expected an environment name after 'environment:'");
            return;
        }
        target_.environmentLine({std::string(trimView(value)), loc});
    } else if (kw == "table schedule") {
        parseSchedule(line, valueStart);
    } else if (parseViewSetting(line, kw, valueStart)) {
        return;
    } else if (kw == "random") {
        std::string_view word = trimView(std::string_view(line.text).substr(valueStart));
        if (word != "cpfg" && word != "graftal") {
            diags_.error(loc,
                         "random: expects 'cpfg' (cpfg's generators, in cpfg's order) or "
                         "'graftal' (graftal's streams), not '" +
                             std::string(word) + "'");
            return;
        }
        target_.randomStreams(word == "cpfg" ? RandomStreams::Cpfg : RandomStreams::Graftal, loc);
    } else if (kw == "seed") {
        if (!constantValue(line, valueStart, v)) return;
        // 2^64 is the first double above the largest uint64_t.
        if (!(v >= 0 && v < 18446744073709551616.0) || v != std::floor(v)) {
            diags_.error(loc,
                         "seed must be a whole number from 0 to 2^64 - 1, not " + formatNumber(v));
            return;
        }
        target_.seed(static_cast<std::uint64_t>(v), loc);
    }
}

// table schedule: NAME COUNT, NAME COUNT, ..., NAME [COUNT] [, repeat]
void Parser::parseSchedule(const SourceLine& line, std::size_t valueStart) {
    if (!rawSchedule_.empty() || scheduleLine_) {
        diags_.error(at(line, firstNonBlank(line.text)), "a second 'table schedule:'");
        return;
    }
    scheduleLine_ = line.number;
    std::string_view value = std::string_view(line.text).substr(valueStart);
    std::size_t pos = 0;
    while (pos <= value.size()) {
        std::size_t comma = findTopLevel(value, ',', pos);
        if (comma == std::string_view::npos) comma = value.size();
        std::string_view item = value.substr(pos, comma - pos);
        std::size_t lead = firstNonBlank(item);
        std::size_t col = valueStart + pos + (lead == std::string_view::npos ? 0 : lead);
        std::string_view t = trimView(item);
        if (t.empty()) {
            diags_.error(at(line, col), "expected 'TABLE STEPS' in the schedule");
            return;
        }
        if (lower(t) == "repeat") {
            if (comma != value.size()) {
                diags_.error(at(line, col), "'repeat' must end the schedule");
                return;
            }
            scheduleRepeats_ = true;
            break;
        }
        std::size_t sp = t.find_first_of(" \t");
        RawScheduleEntry e;
        e.name = std::string(t.substr(0, sp));
        e.location = at(line, col);
        if (sp != std::string_view::npos) {
            double steps = 0;
            std::size_t countCol = col + sp + firstNonBlank(t.substr(sp));
            ExpressionScope scope;
            scope.defines = &defines_;
            DiagnosticList local;
            Expression ex =
                compileExpression(trimView(t.substr(sp)), at(line, countCol), scope, local);
            for (const auto& d : local.items()) diags_.add(d);
            if (ex.empty()) return;
            try {
                steps = ex.evaluate({});
            } catch (const Error& err) {
                for (const auto& d : err.diagnostics()) diags_.add(d);
                return;
            }
            if (!(steps >= 0 && steps <= std::numeric_limits<int>::max()) ||
                steps != std::floor(steps)) {
                diags_.error(at(line, countCol),
                             "a table runs for a whole number of steps from 0 to 2147483647, "
                             "not " +
                                 formatNumber(steps));
                return;
            }
            e.steps = static_cast<int>(steps);
        }
        rawSchedule_.push_back(std::move(e));
        pos = comma + 1;
        if (comma == value.size()) break;
    }
}

void Parser::parseAxiom(const SourceLine& line, std::size_t valueStart) {
    std::string_view value = std::string_view(line.text).substr(valueStart);
    SourceLocation loc = at(line, valueStart);
    if (trimView(value) == "*") return;  // the empty axiom
    std::vector<ModuleToken> toks;
    if (!tokenizeModules(value, loc, static_cast<int>(valueStart) + 1, target_.symbols(), toks,
                         diags_, surfaceLetters_))
        return;
    if (toks.empty()) {
        diags_.error(at(line, valueStart), "expected the axiom's modules after 'axiom:'");
        return;
    }
    ExpressionScope scope;
    scope.defines = &defines_;
    scope.state = &globals_;
    scope.arrays = &arrays_;
    std::vector<double> args;
    ModuleString axiom;
    struct Deferred {
        std::size_t module, param;
        Expression value;
    };
    std::vector<Deferred> deferred;
    for (const auto& tok : toks) {
        args.clear();
        for (const auto& a : tok.args) {
            SourceLocation aloc = src_.at(line.number, a.column);
            DiagnosticList local;
            Expression e = compileExpression(a.text, aloc, scope, local);
            for (const auto& d : local.items()) diags_.add(d);
            if (e.empty()) return;
            if (e.needsContext()) {
                // Start: runs first, the view file's functions come after the .l, and
                // ran() draws from the derivation's numbers: the derivation evaluates these.
                deferred.push_back({axiom.size(), args.size(), std::move(e)});
                args.push_back(0);
                continue;
            }
            try {
                args.push_back(e.evaluate({}));
            } catch (const Error& err) {
                for (const auto& d : err.diagnostics()) diags_.add(d);
                return;
            }
        }
        axiom.push(tok.symbol, args);
    }
    target_.axiom(std::move(axiom), loc);
    for (auto& d : deferred) target_.deferredAxiomArgument(d.module, d.param, std::move(d.value));
    checkBrackets(toks, line, "axiom");
}

// An axiom or successor with unbalanced brackets is almost always a typo; say where.
void Parser::checkBrackets(const std::vector<ModuleToken>& toks, const SourceLine& line,
                           const char* what) {
    std::vector<int> open;
    for (const auto& t : toks) {
        if (t.symbol == '[') open.push_back(t.column);
        if (t.symbol == ']') {
            if (open.empty()) {
                diags_.error(src_.at(line.number, t.column), std::string("unbalanced ']' in the ") +
                                                                 what + ": no '[' is open here");
                return;
            }
            open.pop_back();
        }
    }
    if (!open.empty())
        diags_.error(src_.at(line.number, open.back()),
                     std::string("unbalanced '[' in the ") + what + ": expected a matching ']'");
}

void Parser::parseIgnore(const SourceLine& line, const std::string& kw, std::size_t valueStart) {
    std::string_view value = std::string_view(line.text).substr(valueStart);
    SourceLocation loc = at(line, valueStart);
    if ((kw == "ignore" && sawConsider_) || (kw == "consider" && sawIgnore_)) {
        diags_.error(loc, "use either 'ignore:' or 'consider:', not both");
        return;
    }
    std::vector<ModuleToken> toks;
    if (!tokenizeModules(value, loc, static_cast<int>(valueStart) + 1, target_.symbols(), toks,
                         diags_, surfaceLetters_))
        return;
    for (const auto& t : toks) {
        if (t.hasParens) {
            diags_.error(src_.at(line.number, t.column),
                         "'" + kw + ":' lists module names without parameters");
            return;
        }
    }
    (kw == "ignore" ? sawIgnore_ : sawConsider_) = true;
    std::vector<Symbol> listed;
    for (const auto& t : toks) listed.push_back(t.symbol);
    target_.ignore(listed, kw == "consider", loc);
}

// age: I(i) L(i) F(_, a): the one named parameter of each module is its age; the others
// are written _.
void Parser::parseAges(const SourceLine& line, std::size_t valueStart) {
    std::string_view value = std::string_view(line.text).substr(valueStart);
    SourceLocation loc = at(line, valueStart);
    std::vector<ModuleToken> toks;
    if (!tokenizeModules(value, loc, static_cast<int>(valueStart) + 1, target_.symbols(), toks,
                         diags_, surfaceLetters_))
        return;
    if (toks.empty()) {
        diags_.error(loc,
                     "expected modules with their age parameter after 'age:', e.g. 'age: I(i)'");
        return;
    }
    for (const auto& t : toks) {
        const SourceLocation where = src_.at(line.number, t.column);
        const std::string name = target_.symbols().name(t.symbol);
        int age = -1, named = 0;
        for (std::size_t k = 0; k < t.args.size(); ++k) {
            const std::string arg(trimView(t.args[k].text));
            if (arg == "_") continue;
            ++named;
            age = static_cast<int>(k);
        }
        if (!t.hasParens || named != 1) {
            diags_.error(where, "'age:' names one parameter of '" + name + "' as its age: write " +
                                    name + "(a), or " + name +
                                    "(_, a) with _ for the other parameters");
            return;
        }
        target_.moduleAge(ModuleAge{t.symbol, static_cast<std::uint32_t>(age),
                                    static_cast<std::uint32_t>(t.args.size()), where});
    }
}

bool Parser::isGlobalBlockKeyword(const std::string& kw) {
    return kw == "start" || kw == "starteach" || kw == "endeach" || kw == "end" || kw == "define";
}

void Parser::parseGlobalBlocks() {
    // Arrays first: the blocks may use them wherever the lines stand.
    for (bool arrays : {true, false}) {
        for (const auto& line : src_.lines) {
            std::string_view t = line.text;
            std::size_t start = firstNonBlank(t);
            if (start == std::string_view::npos) continue;
            std::size_t colon = t.find(':', start);
            if (colon == std::string_view::npos) continue;
            std::string kw = normaliseKeyword(t.substr(start, colon - start));
            if (!isGlobalBlockKeyword(kw) || (kw == "define") != arrays) continue;
            parseGlobalBlock(line, kw, colon + 1);
        }
    }
}

bool Parser::parseBlockAt(const SourceLine& line, std::size_t open, std::size_t close,
                          BlockScope& scope, Block& out) {
    std::string_view inside = std::string_view(line.text).substr(open + 1, close - open - 1);
    std::function<SourceLocation(std::size_t)> locate = [&](std::size_t i) {
        return at(line, open + 1 + i);
    };
    return parseBlock(inside, locate, scope, out, diags_);
}

bool Parser::parseGlobalBlock(const SourceLine& line, const std::string& kw,
                              std::size_t valueStart) {
    std::string_view t = line.text;
    std::size_t open = t.find_first_not_of(" \t\r\f\v", valueStart);
    if (open == std::string_view::npos || t[open] != '{') {
        diags_.error(
            at(line, open == std::string_view::npos ? t.size() : open),
            "expected a block '{ ... }' after '" +
                std::string(trimView(t.substr(firstNonBlank(t), valueStart - firstNonBlank(t)))) +
                "'");
        return false;
    }
    std::size_t close = matchingBrace(t, open);
    if (close == std::string_view::npos) {
        diags_.error(at(line, open), "expected '}' to close this block");
        return false;
    }
    if (!isBlank(t.substr(close + 1))) {
        diags_.error(at(line, close + 1), "unexpected text after the block");
        return false;
    }
    if (kw == "define") {
        std::string_view inside = t.substr(open + 1, close - open - 1);
        std::function<SourceLocation(std::size_t)> locate = [&](std::size_t i) {
            return at(line, open + 1 + i);
        };
        ArrayState state{&defines_, &arrays_, &stateNames_, &initialState_};
        return parseArrayDeclarations(inside, locate, state, diags_);
    }
    GlobalBlock which = kw == "start"       ? GlobalBlock::Start
                        : kw == "starteach" ? GlobalBlock::StartEach
                        : kw == "endeach"   ? GlobalBlock::EndEach
                                            : GlobalBlock::End;
    BlockScope scope;
    scope.defines = &defines_;
    scope.state = &globals_;
    scope.stateNames = &stateNames_;
    scope.arrays = &arrays_;
    Block block;
    if (!parseBlockAt(line, open, close, scope, block)) return false;
    target_.globalBlock(which, std::move(block), at(line, firstNonBlank(t)));
    return true;
}

std::size_t Parser::errorCount() const {
    std::size_t n = 0;
    for (const auto& d : diags_.items()) n += d.severity == Severity::Error;
    return n;
}

}  // namespace parsing

LSystem parseLSystem(std::string_view text, const ParseOptions& options) {
    return std::move(parse(text, options).orThrow().lsystem);
}

LSystem loadLSystem(const std::filesystem::path& path, ParseOptions options) {
    return std::move(loadModel(path, std::move(options)).orThrow().lsystem);
}

}  // namespace graftal
