// The standard ParserTarget: the calls of a front end become a Model.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <variant>

#include "contour_setting.hpp"
#include "curve_setting.hpp"
#include "graftal/lang/parser_target.hpp"
#include "setting_file.hpp"

namespace graftal {

void ModelBuilder::beginSource(const std::string& file, bool legacyPfg) {
    model_.lsystem.name = file;
    model_.lsystem.file = file;
    model_.lsystem.legacyPfg = legacyPfg;
    model_.view.turtle.clockwisePlus = legacyPfg;  // pfg's + turns right on screen
    // cpfg's angle increment is 45 degrees until a file says otherwise; pfg data files keep
    // the 90 degrees they have always had here.
    if (!legacyPfg) model_.view.turtle.angleDegrees = 45;
}

void ModelBuilder::name(const std::string& name, const SourceLocation&) {
    model_.lsystem.name = name;
}

void ModelBuilder::define(const std::string& name, const std::string& value,
                          const SourceLocation&) {
    model_.lsystem.defines[name] = value;
}

Symbol ModelBuilder::declareModule(std::string_view name, const SourceLocation&) {
    return model_.lsystem.symbols.declare(name);
}

void ModelBuilder::axiom(ModuleString axiom, const SourceLocation& location) {
    model_.lsystem.axiom = std::move(axiom);
    axiomLocation_ = location;
}

void ModelBuilder::deferredAxiomArgument(std::size_t module, std::size_t param, Expression value) {
    model_.lsystem.axiomArguments.push_back({module, param, std::move(value)});
}

void ModelBuilder::globalBlock(GlobalBlock which, Block block, const SourceLocation& where) {
    LSystem& ls = model_.lsystem;
    Block& slot = which == GlobalBlock::Start       ? ls.startBlock
                  : which == GlobalBlock::StartEach ? ls.startEachBlock
                  : which == GlobalBlock::EndEach   ? ls.endEachBlock
                                                    : ls.endBlock;
    if (!slot.empty()) {
        const char* name = which == GlobalBlock::Start       ? "start"
                           : which == GlobalBlock::StartEach ? "starteach"
                           : which == GlobalBlock::EndEach   ? "endeach"
                                                             : "end";
        diags_.error(where, std::string("a second '") + name + ":' block");
        return;
    }
    slot = std::move(block);
}

void ModelBuilder::stateVariables(std::vector<std::string> names,
                                  std::map<std::string, ArrayShape> arrays,
                                  std::vector<std::pair<std::uint32_t, double>> initialValues) {
    LSystem& ls = model_.lsystem;
    ls.stateNames = std::move(names);
    ls.arrays = std::move(arrays);
    ls.initialState = std::move(initialValues);
}

void ModelBuilder::ring(const SourceLocation&) {
    model_.lsystem.ring = true;
}

void ModelBuilder::production(ProductionGroup group, Production production) {
    LSystem& ls = model_.lsystem;
    (group == ProductionGroup::Decomposition  ? ls.decomposition
     : group == ProductionGroup::Homomorphism ? ls.homomorphism
                                              : ls.productions)
        .push_back(std::move(production));
}

void ModelBuilder::maximumDepth(ProductionGroup group, int depth, const SourceLocation&) {
    (group == ProductionGroup::Decomposition ? model_.lsystem.decompositionDepth
                                             : model_.lsystem.homomorphismDepth) = depth;
}

void ModelBuilder::table(const std::string& name, const SourceLocation&) {
    model_.lsystem.tableNames.push_back(name);
}

void ModelBuilder::tableSchedule(std::vector<ScheduleEntry> entries, bool repeats,
                                 const SourceLocation&) {
    model_.lsystem.schedule = std::move(entries);
    model_.lsystem.scheduleRepeats = repeats;
}

void ModelBuilder::derivationLength(int steps, const SourceLocation&) {
    model_.lsystem.derivationLength = steps;
}

void ModelBuilder::moduleAge(const ModuleAge& age) {
    for (const ModuleAge& a : model_.lsystem.ages)
        if (a.symbol == age.symbol) {
            diags_.error(age.location, "the age of '" + model_.lsystem.symbols.name(age.symbol) +
                                           "' is declared twice (first on line " +
                                           std::to_string(a.location.line) + ")");
            return;
        }
    model_.lsystem.ages.push_back(age);
}

void ModelBuilder::seed(std::uint64_t seed, const SourceLocation&) {
    model_.lsystem.seed = seed;
    model_.lsystem.hasSeedLine = true;
}

void ModelBuilder::randomStreams(RandomStreams streams, const SourceLocation&) {
    model_.lsystem.random = streams;
    model_.lsystem.randomLine = true;
}

void ModelBuilder::ignore(const std::vector<Symbol>& symbols, bool consider,
                          const SourceLocation&) {
    std::vector<bool>& ignored = model_.lsystem.ignored;
    if (consider && !considered_) std::fill(ignored.begin(), ignored.end(), true);
    considered_ = considered_ || consider;
    for (Symbol s : symbols) ignored[s] = !consider;
}

void ModelBuilder::environmentLine(EnvironmentLine line) {
    model_.lsystem.environment.push_back(std::move(line));
}

void ModelBuilder::viewSetting(const ViewSetting& setting) {
    if (setting.name == "function" || setting.name == "function set") {
        loadFunctions(setting);
        return;
    }
    if (setting.name == "curve") {
        loadCurveSetting(model_.lsystem, setting, diags_);
        return;
    }
    if (setting.name == "contour") {
        loadContourSetting(model_.view, setting, diags_);
        return;
    }
    std::string problem = applyViewSetting(model_.view, setting);
    if (!problem.empty()) diags_.error(setting.location, std::move(problem));
}

// `function: file.func [samples]` adds one function, `function set: file.fset` replaces
// them all (as in cpfg); files are found beside the view file.
void ModelBuilder::loadFunctions(const ViewSetting& setting) {
    const auto* text = std::get_if<std::string>(&setting.value);
    if (!text || text->empty()) {
        diags_.error(setting.location, "'" + setting.name + ":' expects a file name");
        return;
    }
    std::istringstream words(*text);
    std::string name, samplesWord, extra;
    words >> name >> samplesWord >> extra;
    int samples = 0;
    if (!samplesWord.empty()) {
        char* stop = nullptr;
        double d = std::strtod(samplesWord.c_str(), &stop);
        if (*stop || d != std::floor(d) || d < 0 || d > 1e6 || setting.name != "function") {
            diags_.error(setting.location,
                         "'" + setting.name + ":' expects a file name" +
                             (setting.name == "function" ? std::string(" and a number of samples")
                                                         : std::string()) +
                             ", found '" + *text + "'");
            return;
        }
        samples = static_cast<int>(d);
    }
    const std::filesystem::path path = settingFilePath(setting, name);
    const std::optional<std::string> bytes = readSettingFile(setting, path, "function", diags_);
    if (!bytes) return;
    try {
        if (setting.name == "function set")
            model_.lsystem.functions = parseFunctionSet(*bytes, path.string());
        else
            model_.lsystem.functions.push_back(parseFunctionFile(*bytes, path.string(), samples));
    } catch (const Error& e) {
        for (const auto& d : e.diagnostics()) diags_.add(d);
    }
}

void ModelBuilder::endOfInput(const SourceLocation&) {
    warnShadowedProductions();
    if (!model_.lsystem.legacyPfg) warnSubLsystemEnds();
}

namespace {

bool samePattern(const std::vector<ModulePattern>& a, const std::vector<ModulePattern>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].symbol != b[i].symbol || a[i].formals.size() != b[i].formals.size()) return false;
    return true;
}

}  // namespace

// First applicable production wins; a context-free, unconditional production listed
// before a context-sensitive one for the same predecessor hides it for good.
void ModelBuilder::warnShadowedProductions() {
    const auto& ps = model_.lsystem.productions;
    for (std::size_t j = 0; j < ps.size(); ++j) {
        if (!ps[j].hasContext()) continue;
        for (std::size_t i = 0; i < j; ++i) {
            if (ps[i].hasContext() || ps[i].condition || ps[i].probability) continue;
            if (ps[i].table != -1 && ps[i].table != ps[j].table) continue;
            if (!samePattern(ps[i].predecessor, ps[j].predecessor)) continue;
            diags_.warning(ps[j].location,
                           "this context-sensitive production is never applied: the "
                           "context-free production on line " +
                               std::to_string(ps[i].location.line) +
                               " has the same predecessor and comes first (list "
                               "context-sensitive productions first)");
            break;
        }
    }
}

// cpfg ends a sub-L-system at '$' and ignores an unmatched one with a warning. graftal has
// no sub-L-systems, so every '$' is such a one: say so once, where it first appears.
void ModelBuilder::warnSubLsystemEnds() {
    const LSystem& ls = model_.lsystem;
    const Symbol dollar = '$';
    auto has = [&](const std::vector<SuccessorModule>& ms) {
        return std::any_of(ms.begin(), ms.end(),
                           [&](const SuccessorModule& m) { return m.symbol == dollar; });
    };
    std::optional<SourceLocation> where;
    const auto axiom = ls.axiom.symbols();
    if (std::find(axiom.begin(), axiom.end(), dollar) != axiom.end()) where = axiomLocation_;
    for (const auto* list : {&ls.productions, &ls.decomposition, &ls.homomorphism})
        for (const Production& p : *list)
            if (!where && has(p.successor)) where = p.location;
    if (where)
        diags_.warning(*where,
                       "'$' ends a sub-L-system in cpfg; there is none here, so the turtle "
                       "ignores it (cpfg: \"unmatched $ ignored\")");
}

}  // namespace graftal
