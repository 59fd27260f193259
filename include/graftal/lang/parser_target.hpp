// The interface a front end writes a model through. The .l parser reads text and says what
// it found by calling these functions, in file order; a ModelBuilder turns the calls into a
// Model. Other front ends (a cpfg view-file reader, a map-L-system reader) write through the
// same interface, so the checks on the values (a positive step length, a known line style)
// live in one place: the target.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/core/rgb.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/lang/environment_line.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"

namespace graftal {

// Which list a production belongs to.
enum class ProductionGroup { Main, Decomposition, Homomorphism };

// Which of the global statement blocks a block is.
enum class GlobalBlock { Start, StartEach, EndEach, End };

// One view setting as a file states it: its name in the .l spelling ("step length",
// "viewpoint", "line style", ...; see viewSettingNames()), its value and where it stands.
// Numbers and vectors arrive evaluated; words, colours, file names and `surface:` lines as
// their trimmed text.
struct ViewSetting {
    std::string name;
    std::variant<double, Vec3, std::string> value;
    SourceLocation location;  // of the value (with its end)
};

// Every name ViewSetting::name may take.
const std::vector<std::string>& viewSettingNames();

// Checks one setting and stores it in `view`. Returns "" or the message of an error (e.g.
// "step length must be positive"): the caller reports it at setting.location.
std::string applyViewSetting(ViewSettings& view, const ViewSetting& setting);

class ParserTarget {
  public:
    virtual ~ParserTarget() = default;

    // The source about to be read; `legacyPfg` when it is a pfg data file (no `Lsystem:`).
    virtual void beginSource(const std::string& file, bool legacyPfg) = 0;
    // `Lsystem: NAME`.
    virtual void name(const std::string& name, const SourceLocation& where) = 0;
    // `#define NAME VALUE` (and -D NAME=VALUE, which wins), as text.
    virtual void define(const std::string& name, const std::string& value,
                        const SourceLocation& where) = 0;
    // The table module names are interned in. Front ends tokenise module strings against it,
    // so that symbols in axioms and productions are the model's own.
    virtual SymbolTable& symbols() = 0;
    // `module NAME, ...`: a multi-letter module name.
    virtual Symbol declareModule(std::string_view name, const SourceLocation& where) = 0;
    virtual void axiom(ModuleString axiom, const SourceLocation& where) = 0;
    // A parameter of the axiom that reads the state (a global, an array, ran()): it is
    // evaluated when a derivation begins, after Start:. Comes after axiom(); the axiom holds
    // 0 at (module, param) meanwhile.
    virtual void deferredAxiomArgument(std::size_t module, std::size_t param, Expression value) = 0;
    // `Start: { ... }` and the others; each at most once.
    virtual void globalBlock(GlobalBlock which, Block block, const SourceLocation& where) = 0;
    // The state the blocks and expressions share, once everything is read: the names of its
    // slots (0 is Q, 1 is Z, then globals, array elements and production variables), the
    // arrays and the initial values of their elements (slot, value).
    virtual void stateVariables(std::vector<std::string> names,
                                std::map<std::string, ArrayShape> arrays,
                                std::vector<std::pair<std::uint32_t, double>> initialValues) = 0;
    // `ring lsystem`: the string is a ring for context matching.
    virtual void ring(const SourceLocation& where) = 0;
    // A production; its `table` is the index of the table declared before it (-1: none).
    virtual void production(ProductionGroup group, Production production) = 0;
    // `maximum depth:` of the decomposition or homomorphism section.
    virtual void maximumDepth(ProductionGroup group, int depth, const SourceLocation& where) = 0;
    // `table: NAME`; tables are numbered in the order they are declared.
    virtual void table(const std::string& name, const SourceLocation& where) = 0;
    // `table schedule:` with the table names resolved to their numbers.
    virtual void tableSchedule(std::vector<ScheduleEntry> entries, bool repeats,
                               const SourceLocation& where) = 0;
    virtual void derivationLength(int steps, const SourceLocation& where) = 0;
    virtual void seed(std::uint64_t seed, const SourceLocation& where) = 0;
    // `random: cpfg` or `random: graftal`: whose random numbers the derivation draws.
    virtual void randomStreams(RandomStreams, const SourceLocation&) {}
    // `ignore:` (consider = false) or `consider:` (true) with the symbols listed.
    virtual void ignore(const std::vector<Symbol>& symbols, bool consider,
                        const SourceLocation& where) = 0;
    virtual void environmentLine(EnvironmentLine line) = 0;
    // One view setting by name and value; the target checks it (see applyViewSetting).
    virtual void viewSetting(const ViewSetting& setting) = 0;
    // Everything is read; `last` is the last line, for checks over the whole model.
    virtual void endOfInput(const SourceLocation& last) = 0;
    // `age: I(i)`: which parameter of a module is its age (continuous development).
    virtual void moduleAge(const ModuleAge& age) { (void)age; }
};

// The standard target: builds a Model, reporting what it rejects to `diagnostics`.
class ModelBuilder : public ParserTarget {
  public:
    explicit ModelBuilder(DiagnosticList& diagnostics) : diags_(diagnostics) {}

    Model& model() { return model_; }

    void beginSource(const std::string& file, bool legacyPfg) override;
    void name(const std::string& name, const SourceLocation& where) override;
    void define(const std::string& name, const std::string& value,
                const SourceLocation& where) override;
    SymbolTable& symbols() override { return model_.lsystem.symbols; }
    Symbol declareModule(std::string_view name, const SourceLocation& where) override;
    void axiom(ModuleString axiom, const SourceLocation& where) override;
    void deferredAxiomArgument(std::size_t module, std::size_t param, Expression value) override;
    void globalBlock(GlobalBlock which, Block block, const SourceLocation& where) override;
    void stateVariables(std::vector<std::string> names, std::map<std::string, ArrayShape> arrays,
                        std::vector<std::pair<std::uint32_t, double>> initialValues) override;
    void ring(const SourceLocation& where) override;
    void production(ProductionGroup group, Production production) override;
    void maximumDepth(ProductionGroup group, int depth, const SourceLocation& where) override;
    void table(const std::string& name, const SourceLocation& where) override;
    void tableSchedule(std::vector<ScheduleEntry> entries, bool repeats,
                       const SourceLocation& where) override;
    void derivationLength(int steps, const SourceLocation& where) override;
    void seed(std::uint64_t seed, const SourceLocation& where) override;
    void randomStreams(RandomStreams streams, const SourceLocation& where) override;
    void ignore(const std::vector<Symbol>& symbols, bool consider,
                const SourceLocation& where) override;
    void environmentLine(EnvironmentLine line) override;
    void viewSetting(const ViewSetting& setting) override;
    void endOfInput(const SourceLocation& last) override;
    void moduleAge(const ModuleAge& age) override;

  private:
    void loadFunctions(const ViewSetting& setting);
    void warnShadowedProductions();
    void warnSubLsystemEnds();
    SourceLocation axiomLocation_;

    DiagnosticList& diags_;
    Model model_;
    bool considered_ = false;
};

// Parses .l text into any target; what it finds wrong (and the target rejects) goes to
// `diagnostics`, each with its end position. parse() is this with a ModelBuilder.
void parseInto(std::string_view text, const ParseOptions& options, ParserTarget& target,
               DiagnosticList& diagnostics);

}  // namespace graftal
