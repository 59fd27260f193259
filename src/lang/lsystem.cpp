// Printing an L-system back in the .l language (debugging, test failures), and the
// small queries over its productions.
#include <ostream>

#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/view_settings.hpp"

namespace graftal {

namespace {

void printPatterns(std::ostream& os, const std::vector<ModulePattern>& ps, const SymbolTable& t) {
    if (ps.empty()) {
        os << '*';
        return;
    }
    for (const auto& p : ps) {
        os << t.name(p.symbol);
        if (!p.formals.empty()) {
            os << '(';
            for (std::size_t i = 0; i < p.formals.size(); ++i) os << (i ? "," : "") << p.formals[i];
            os << ')';
        }
    }
}

}  // namespace

bool Production::isParametric() const {
    for (const auto* part : {&left, &predecessor, &right})
        for (const auto& m : *part)
            if (!m.formals.empty()) return true;
    for (const auto& m : successor)
        if (!m.args.empty()) return true;
    return false;
}

void Production::print(std::ostream& os, const SymbolTable& symbols) const {
    if (!left.empty()) {
        printPatterns(os, left, symbols);
        os << " < ";
    }
    printPatterns(os, predecessor, symbols);
    if (!right.empty()) {
        os << " > ";
        printPatterns(os, right, symbols);
    }
    if (condition) os << " : " << *condition;
    os << " --> ";
    if (successor.empty()) os << '*';
    for (const auto& m : successor) {
        os << symbols.name(m.symbol);
        if (!m.args.empty()) {
            os << '(';
            for (std::size_t i = 0; i < m.args.size(); ++i) os << (i ? "," : "") << m.args[i];
            os << ')';
        }
    }
    if (probability) os << " : " << *probability;
}

int LSystem::tableForStep(int step) const {
    if (tableNames.empty() || schedule.empty()) return 0;
    long period = 0;
    for (const auto& e : schedule) period += e.steps < 0 ? 0 : e.steps;
    long k = step - 1;  // steps done before this one
    if (scheduleRepeats && period > 0) k %= period;
    for (const auto& e : schedule) {
        if (e.steps < 0 || k < e.steps) return e.table;
        k -= e.steps;
    }
    return schedule.back().table;  // a finite schedule keeps its last table
}

bool LSystem::usesCut() const {
    for (Symbol s : axiom.symbols())
        if (s == '%') return true;
    for (const auto* list : {&productions, &decomposition, &homomorphism})
        for (const auto& p : *list)
            for (const auto& m : p.successor)
                if (m.symbol == '%') return true;
    return false;
}

bool LSystem::hasContext() const {
    for (const auto& p : productions)
        if (p.hasContext()) return true;
    return false;
}

bool LSystem::hasMultiModulePredecessor() const {
    for (const auto& p : productions)
        if (p.predecessor.size() > 1) return true;
    return false;
}

bool LSystem::isParametric() const {
    if (axiom.hasParameters()) return true;
    for (const auto* list : {&productions, &decomposition, &homomorphism})
        for (const auto& p : *list)
            if (p.isParametric() || p.condition) return true;
    return false;
}

bool LSystem::hasSideEffects() const {
    for (const auto* list : {&productions, &decomposition, &homomorphism}) {
        for (const auto& p : *list) {
            if (p.hasBlocks()) return true;
            if (p.condition && p.condition->prints()) return true;
            if (p.probability && p.probability->prints()) return true;
            for (const auto& m : p.successor)
                for (const auto& a : m.args)
                    if (a.prints()) return true;
        }
    }
    return false;
}

namespace {

bool blockDrawsRandomNumbers(const Block& block) {
    for (const auto& st : block)
        if (st.value.usesRandom() || st.address.usesRandom() ||
            blockDrawsRandomNumbers(st.body) || blockDrawsRandomNumbers(st.elseBody))
            return true;
    return false;
}

}  // namespace

bool LSystem::drawsRandomNumbers() const {
    for (const auto* list : {&productions, &decomposition}) {
        for (const auto& p : *list) {
            if (p.probability) return true;
            if (p.condition && p.condition->usesRandom()) return true;
            for (const auto& m : p.successor)
                for (const auto& a : m.args)
                    if (a.usesRandom()) return true;
            if (blockDrawsRandomNumbers(p.preBlock) || blockDrawsRandomNumbers(p.postBlock))
                return true;
        }
    }
    for (const auto* b : {&startBlock, &startEachBlock, &endEachBlock, &endBlock})
        if (blockDrawsRandomNumbers(*b)) return true;
    for (const auto& a : axiomArguments)
        if (a.value.usesRandom()) return true;
    return false;
}

void LSystem::print(std::ostream& os, const ViewSettings* view) const {
    if (legacyPfg) os << "/* read as a pfg data file */\n";
    for (std::size_t s = kFirstDeclaredSymbol; s < symbols.size(); ++s)
        os << (s == kFirstDeclaredSymbol ? "module " : ", ") << symbols.name(static_cast<Symbol>(s))
           << (s + 1 == symbols.size() ? ";\n" : "");
    os << "Lsystem: " << name << '\n';
    os << "derivation length: " << derivationLength << '\n';
    if (seed || hasSeedLine) os << "seed: " << seed << '\n';
    if (randomLine || random == RandomStreams::Cpfg)
        os << "random: " << (random == RandomStreams::Cpfg ? "cpfg" : "graftal") << '\n';
    if (view) os << *view;
    os << "axiom: " << (axiom.empty() ? std::string("*") : axiom.toString(symbols)) << '\n';
    std::string ign;
    for (std::size_t s = 0; s < symbols.size(); ++s)
        if (ignored[s] && s > 32 && s != 127) ign += symbols.name(static_cast<Symbol>(s));
    if (!ign.empty()) os << "ignore: " << ign << '\n';
    for (const ModuleAge& a : ages) {
        os << "age: " << symbols.name(a.symbol) << '(';
        for (std::uint32_t k = 0; k < a.parameterCount; ++k)
            os << (k ? ", " : "") << (k == a.parameter ? "a" : "_");
        os << ")\n";
    }
    int table = -1;
    for (const auto& p : productions) {
        if (p.table != table && p.table >= 0) os << "table: " << tableNames[p.table] << '\n';
        table = p.table;
        p.print(os, symbols);
        os << '\n';
    }
    if (!schedule.empty()) {
        os << "table schedule: ";
        for (std::size_t k = 0; k < schedule.size(); ++k) {
            os << (k ? ", " : "") << tableNames[schedule[k].table];
            if (schedule[k].steps >= 0) os << ' ' << schedule[k].steps;
        }
        os << (scheduleRepeats ? ", repeat\n" : "\n");
    }
    for (int section = 0; section < 2; ++section) {
        const auto& list = section == 0 ? decomposition : homomorphism;
        if (list.empty()) continue;
        os << (section == 0 ? "decomposition\nmaximum depth: " : "homomorphism\nmaximum depth: ")
           << (section == 0 ? decompositionDepth : homomorphismDepth) << '\n';
        for (const auto& p : list) {
            p.print(os, symbols);
            os << '\n';
        }
    }
    os << "endlsystem\n";
}

std::ostream& operator<<(std::ostream& os, const LSystem& ls) {
    ls.print(os);
    return os;
}

}  // namespace graftal
