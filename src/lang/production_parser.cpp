// Productions of the .l language, and the checks over the whole L-system once every line
// is read (see parser.hpp).
#include <algorithm>
#include <cctype>
#include <cmath>

#include "parser.hpp"

namespace graftal::parsing {

bool Parser::parsePatterns(const SourceLine& line, std::size_t from, std::size_t to,
                           std::vector<ModulePattern>& out, std::vector<std::string>& formals,
                           const char* what, bool allowEmpty) {
    std::string_view part = std::string_view(line.text).substr(from, to - from);
    if (trimView(part) == "*" && allowEmpty) return true;
    if (isBlank(part)) {
        if (allowEmpty) return true;
        diags_.error(at(line, from), std::string("expected the ") + what + " (use '*' for none)");
        return false;
    }
    std::vector<ModuleToken> toks;
    SourceLocation loc = at(line, from);
    if (!tokenizeModules(part, loc, static_cast<int>(from) + 1, target_.symbols(), toks, diags_,
                         surfaceLetters_))
        return false;
    for (auto& t : toks) {
        ModulePattern p;
        p.symbol = t.symbol;
        p.location = src_.at(line.number, t.column);
        for (const auto& a : t.args) {
            std::string_view name = trimView(a.text);
            bool ok = !name.empty() &&
                      (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_');
            for (char c : name)
                ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
            if (!ok) {
                // A formal made only of blanks (even \v or \f) has no first character.
                std::size_t offset = name.empty() ? 0 : a.text.find(name[0]);
                diags_.error(src_.at(line.number, a.column + static_cast<int>(offset)),
                             std::string("a ") + what + " names its parameters (e.g. A(x,y)); '" +
                                 std::string(name) + "' is not a name");
                return false;
            }
            if (std::find(formals.begin(), formals.end(), name) != formals.end()) {
                diags_.error(
                    src_.at(line.number, a.column),
                    "parameter '" + std::string(name) + "' is bound twice in this production");
                return false;
            }
            formals.emplace_back(name);
            p.formals.emplace_back(name);
        }
        out.push_back(std::move(p));
    }
    return true;
}

void Parser::parseProduction(const SourceLine& line, Arrow arrow) {
    std::string_view t = line.text;
    Production prod;
    std::size_t lineStart = firstNonBlank(t);
    prod.location = at(line, lineStart);
    prod.location.endLine = line.number;
    prod.location.endColumn = static_cast<int>(t.find_last_not_of(" \t\r\f\v")) + 2;

    // Left of the arrow: [lc <] pred [> rc] [: condition]
    std::string_view lhs = t.substr(0, arrow.pos);
    std::size_t condColon = findTopLevel(lhs, ':');
    std::size_t patEnd = condColon == std::string_view::npos ? arrow.pos : condColon;
    std::string_view pat = lhs.substr(0, patEnd);
    std::size_t lt = findTopLevel(pat, '<');
    std::size_t gt = findTopLevel(pat, '>', lt == std::string_view::npos ? 0 : lt + 1);
    std::size_t predFrom = lt == std::string_view::npos ? 0 : lt + 1;
    std::size_t predTo = gt == std::string_view::npos ? patEnd : gt;

    std::vector<std::string> formals;
    if (lt != std::string_view::npos &&
        !parsePatterns(line, 0, lt, prod.left, formals, "left context", true))
        return;
    if (!parsePatterns(line, predFrom, predTo, prod.predecessor, formals, "predecessor", false))
        return;
    if (prod.predecessor.empty()) {
        diags_.error(at(line, predFrom), "expected a predecessor before the arrow");
        return;
    }
    if (gt != std::string_view::npos &&
        !parsePatterns(line, gt + 1, patEnd, prod.right, formals, "right context", true))
        return;
    // A predecessor's brackets are matched literally (cpfg); a left context cannot enter
    // branches.
    for (const auto& m : prod.left) {
        if (m.symbol == '[' || m.symbol == ']') {
            diags_.error(m.location, "brackets may not appear in a left context");
            return;
        }
    }
    // A predecessor may be a whole branch (`[f(y)P(r)] : r == 0 --> *`, as cpfg allows),
    // but not a lone bracket or one that starts by closing a branch.
    const Symbol first = prod.predecessor.front().symbol;
    if (first == ']' || (first == '[' && prod.predecessor.size() == 1)) {
        diags_.error(prod.predecessor.front().location,
                     first == ']' ? "a predecessor cannot start with ']'"
                                  : "a predecessor cannot be a lone '[': write the branch "
                                    "it starts");
        return;
    }
    prod.slotCount = static_cast<int>(formals.size());

    // The production sees the globals and its own variables (created by its blocks).
    std::map<std::string, std::uint32_t> state = globals_;
    BlockScope blockScope;
    blockScope.formals = &formals;
    blockScope.defines = &defines_;
    blockScope.state = &state;
    blockScope.stateNames = &stateNames_;
    blockScope.arrays = &arrays_;
    blockScope.owner = " (production on line " + std::to_string(line.number) + ")";
    ExpressionScope scope;
    scope.variables = formals;
    scope.defines = &defines_;
    scope.state = &state;
    scope.arrays = &arrays_;
    if (condColon != std::string_view::npos) {
        // `: { pre } condition { post }`, each part optional.
        std::size_t condFrom = condColon + 1, condTo = lhs.size();
        std::size_t pre = lhs.find_first_not_of(" \t\r\f\v", condFrom);
        if (pre != std::string_view::npos && lhs[pre] == '{') {
            std::size_t close = matchingBrace(lhs, pre);
            if (close == std::string_view::npos) {
                diags_.error(at(line, pre), "expected '}' to close this block");
                return;
            }
            if (!parseBlockAt(line, pre, close, blockScope, prod.preBlock)) return;
            condFrom = close + 1;
        }
        if (std::size_t open = lhs.find('{', condFrom); open != std::string_view::npos) {
            std::size_t close = matchingBrace(lhs, open);
            if (close == std::string_view::npos) {
                diags_.error(at(line, open), "expected '}' to close this block");
                return;
            }
            if (!isBlank(lhs.substr(close + 1))) {
                diags_.error(at(line, close + 1),
                             "unexpected text after the block: expected the arrow '-->'");
                return;
            }
            condTo = open;
        }
        std::string_view cond = lhs.substr(condFrom, condTo - condFrom);
        std::size_t off = firstNonBlank(cond);
        if (off == std::string_view::npos || trimView(cond) == "*") {
            // `: *` is cpfg's "no condition"
        } else {
            Expression e =
                compileExpression(trimView(cond), at(line, condFrom + off), scope, diags_);
            if (e.empty()) return;
            prod.condition = std::move(e);
        }
        if (condTo != lhs.size() &&
            !parseBlockAt(line, condTo, matchingBrace(lhs, condTo), blockScope, prod.postBlock))
            return;
    }

    // Right of the arrow: successor [: probability]
    std::size_t succFrom = arrow.pos + arrow.len;
    std::string_view rhs = t.substr(succFrom);
    std::size_t probColon = findLastTopLevel(rhs, ':');
    std::size_t succTo = probColon == std::string_view::npos ? t.size() : succFrom + probColon;
    if (probColon != std::string_view::npos) {
        std::string_view prob = rhs.substr(probColon + 1);
        std::size_t off = firstNonBlank(prob);
        if (off == std::string_view::npos) {
            diags_.error(at(line, succFrom + probColon + 1), "expected a probability after ':'");
            return;
        }
        Expression e = compileExpression(trimView(prob), at(line, succFrom + probColon + 1 + off),
                                         scope, diags_);
        if (e.empty()) return;
        prod.probability = std::move(e);
    }
    std::string_view succ = t.substr(succFrom, succTo - succFrom);
    if (std::size_t again = succ.find("-->"); again != std::string_view::npos) {
        diags_.error(at(line, succFrom + again),
                     "a second arrow '-->' in this production (a line starting with a TAB "
                     "continues the line before it)");
        return;
    }
    if (isBlank(succ)) {
        diags_.error(at(line, succFrom),
                     "expected a successor after the arrow ('*' for "
                     "the empty string)");
        return;
    }
    if (trimView(succ) != "*") {
        std::vector<ModuleToken> toks;
        if (!tokenizeModules(succ, at(line, succFrom), static_cast<int>(succFrom) + 1,
                             target_.symbols(), toks, diags_, surfaceLetters_))
            return;
        for (const auto& tok : toks) {
            SuccessorModule m;
            m.symbol = tok.symbol;
            for (const auto& a : tok.args) {
                std::size_t lead = a.text.find_first_not_of(" \t");
                Expression e = compileExpression(
                    a.text, src_.at(line.number, a.column + static_cast<int>(lead)), scope, diags_);
                if (e.empty()) return;
                m.args.push_back(std::move(e));
            }
            prod.successor.push_back(std::move(m));
        }
        checkBrackets(toks, line, "successor");
    }
    // cpfg allows contexts in homomorphism productions, not in decomposition ones.
    if (section_ == Section::Decomposition && prod.hasContext()) {
        diags_.error(prod.location,
                     "decomposition productions are context-free: remove the context");
        return;
    }
    // A ']' without its '[' walks out of the branch the predecessor stands in; a '['
    // left open asks only how the next branch begins (`-(a) > [!(w)L`, as cpfg reads it).
    prod.table = currentTable_;
    target_.production(section_ == Section::Decomposition  ? ProductionGroup::Decomposition
                       : section_ == Section::Homomorphism ? ProductionGroup::Homomorphism
                                                           : ProductionGroup::Main,
                       std::move(prod));
}

void Parser::resolveSchedule() {
    if (tableNames_.empty()) {
        if (scheduleLine_)
            diags_.error(src_.at(scheduleLine_, 1), "'table schedule:' without any 'table:'");
        return;
    }
    if (!scheduleLine_) {
        diags_.error(src_.at(src_.lines.back().number, 1),
                     "the L-system has tables but no 'table schedule:' saying which table "
                     "applies at which step");
        return;
    }
    std::vector<ScheduleEntry> schedule;
    for (std::size_t k = 0; k < rawSchedule_.size(); ++k) {
        const auto& e = rawSchedule_[k];
        auto it = std::find(tableNames_.begin(), tableNames_.end(), e.name);
        if (it == tableNames_.end()) {
            std::string names;
            for (const auto& n : tableNames_) names += (names.empty() ? "" : ", ") + n;
            diags_.error(e.location, "unknown table '" + e.name + "' (tables: " + names + ")");
            return;
        }
        if (e.steps < 0 && k + 1 != rawSchedule_.size()) {
            diags_.error(e.location, "only the last table of a schedule may omit its step count");
            return;
        }
        schedule.push_back({static_cast<int>(it - tableNames_.begin()), e.steps});
    }
    if (scheduleRepeats_ && !rawSchedule_.empty() && rawSchedule_.back().steps < 0)
        diags_.error(rawSchedule_.back().location,
                     "a repeating schedule needs a step count for every table");
    target_.tableSchedule(std::move(schedule), scheduleRepeats_, src_.at(scheduleLine_, 1));
}

void Parser::finish() {
    if (!sawAxiom_) {
        int last = src_.lines.empty() ? 1 : src_.lines.back().number;
        diags_.error(src_.at(last, 1), "no axiom: expected a line such as 'axiom: F'");
    }
    resolveSchedule();
    target_.stateVariables(stateNames_, arrays_, initialState_);
    target_.endOfInput(src_.at(src_.lines.empty() ? 1 : src_.lines.back().number, 1));
}

}  // namespace graftal::parsing
