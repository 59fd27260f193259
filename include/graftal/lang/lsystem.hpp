// The compiled L-system: the grammar the parser produces and the derivation engine runs.
// How it is drawn is a separate value (ViewSettings, view_settings.hpp); a parse yields both
// as a Model (model.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/core/rgb.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/lang/curve_xyz.hpp"
#include "graftal/lang/environment_line.hpp"
#include "graftal/lang/expression.hpp"
#include "graftal/lang/graphical_function.hpp"

namespace graftal {

// One module of a predecessor or context: a symbol and the names of its formal parameters.
struct ModulePattern {
    Symbol symbol = 0;
    std::vector<std::string> formals;
    SourceLocation location;
};

// One module of a successor: a symbol and one compiled expression per parameter.
struct SuccessorModule {
    Symbol symbol = 0;
    std::vector<Expression> args;
};

// One statement of a `{ ... }` block (cpfg's C-like statements). Variables other than a
// production's formal parameters live in the L-system's state (LSystem::stateNames).
struct Statement {
    enum class Kind {
        Assign,           // state[target] = value
        AssignElement,    // state[address] = value (an array element)
        AssignParameter,  // the production's parameter number `target` = value (cpfg: a
                          // block may change a parameter; the condition, later statements
                          // and the successor see the new value)
        Evaluate,         // value, for its effect (printf)
        If,               // if (value) body else elseBody
        While,            // while (value) body
        DoWhile,          // do body while (value)
    };
    Kind kind = Kind::Evaluate;
    std::uint32_t target = 0;
    Expression value;
    Expression address;  // AssignElement: gives the element's state slot
    std::vector<Statement> body, elseBody;
};
using Block = std::vector<Statement>;

struct Production {
    std::vector<ModulePattern> left;         // left context, in string order
    std::vector<ModulePattern> predecessor;  // strict predecessor (pfg allows several)
    std::vector<ModulePattern> right;        // right context
    std::optional<Expression> condition;
    std::vector<SuccessorModule> successor;  // empty for *
    std::optional<Expression> probability;
    // `pred : { pre } condition { post } --> succ`: pre runs whenever the predecessor and
    // context match (before the condition), post when the production is applied (before
    // the successor's parameters are evaluated).
    Block preBlock, postBlock;
    SourceLocation location;
    int slotCount = 0;  // formal parameters bound, in all three parts
    int table = -1;     // index into LSystem::tableNames; -1: every table

    bool hasContext() const { return !left.empty() || !right.empty(); }
    bool hasBlocks() const { return !preBlock.empty() || !postBlock.empty(); }
    bool isParametric() const;
    void print(std::ostream& os, const SymbolTable& symbols) const;
};

// One entry of a table schedule: use `table` for `steps` derivation steps (-1: for ever).
struct ScheduleEntry {
    int table = 0;
    int steps = -1;
};

struct ViewSettings;  // view_settings.hpp

// `age: I(i)`: parameter `parameter` of every `symbol` module is its age, which grows by
// one per derivation step. Between steps an animation draws the module at fractional ages
// (its homomorphism production, evaluated at the fractional age, is its growth function).
struct ModuleAge {
    Symbol symbol = 0;
    std::uint32_t parameter = 0;  // from 0
    std::uint32_t parameterCount = 1;
    SourceLocation location;
};

enum class RandomStreams { Graftal, Cpfg };

class LSystem {
  public:
    std::string name;  // the `Lsystem:` label (the file name if none)
    std::string file;  // where it was read from: used in error locations
    SymbolTable symbols;
    ModuleString axiom;
    std::vector<Production> productions;
    // cpfg's sub-sections: decomposition is applied after every step (and to the axiom),
    // homomorphism only when the string is interpreted. Both recurse up to their depth.
    std::vector<Production> decomposition, homomorphism;
    int decompositionDepth = 1, homomorphismDepth = 1;
    // Table L-systems: named production tables and the schedule that picks one per step.
    std::vector<std::string> tableNames;
    std::vector<ScheduleEntry> schedule;
    bool scheduleRepeats = false;
    int derivationLength = 0;
    // For context matching: symbols treated as absent. `consider:` is turned into its
    // complement here, so the engine only ever looks at this table.
    std::vector<bool> ignored = std::vector<bool>(kMaxSymbols, false);
    std::uint64_t seed = 0;
    // A `seed:` line was given: for cpfg this is what makes an L-system stochastic (without
    // it cpfg ignores the probabilities and applies the first applicable production).
    bool hasSeedLine = false;
    // Whose random numbers a derivation draws: graftal's counter-based streams (the same
    // string for any thread count) or cpfg's own generators in cpfg's order
    // (graftal/core/cpfg_random.hpp). `random: cpfg` in the .l sets Cpfg, and so does
    // loadModel() for a model read with a cpfg view file; DerivationOptions::random wins.
    RandomStreams random = RandomStreams::Graftal;
    bool randomLine = false;  // the .l file has a `random:` line
    // The view file gives cpfg's `box:`: cpfg then computes no view volume, which is the
    // interpretation that fills the query modules of its last string, so that string shows
    // them as the step before left them. With cpfg's random numbers graftal does the same.
    bool cpfgViewBox = false;
    // `ring lsystem`: for context matching the string is a ring (its last module is
    // followed by its first).
    bool ring = false;
    bool legacyPfg = false;                    // read as a pfg data file (no Lsystem: header)
    std::vector<EnvironmentLine> environment;  // `environment:` lines, in file order
    // Graphical functions for func(id, x), id counted from 1: the view file's `function:`
    // lines or its `function set:` (they are not part of the .l text).
    std::vector<GraphicalFunction> functions;
    // Functions of the program that embeds the library, called by func(id, x) in place of
    // the id-th graphical function (an empty one keeps it): never read from a file.
    std::shared_ptr<const std::vector<UserFunction>> userFunctions;
    // Curves for curveX/Y/Z(id, t) and curveGAL(id), id counted from 1: the view file's
    // `curve:` lines.
    std::vector<CurveXYZ> curves;
    std::map<std::string, std::string> defines;
    // State shared by blocks and expressions: slot 0 is Q (the step being performed), 1 is Z
    // (the derivation length); then the globals (assigned in Start:, StartEach:, EndEach:
    // or End:) and each production's own variables, which keep their value between
    // applications. All start at 0.
    std::vector<std::string> stateNames = {"Q", "Z"};
    Block startBlock, startEachBlock, endEachBlock, endBlock;
    // Global arrays (`define: { array a[3] = {1, 2, 3}; }`) and the initial values of
    // their elements (state slot, value); every other slot starts at 0.
    std::map<std::string, ArrayShape> arrays;
    std::vector<std::pair<std::uint32_t, double>> initialState;
    // Axiom parameters that read the state: evaluated after Start: when a derivation begins.
    struct DeferredArgument {
        std::size_t module = 0, param = 0;
        Expression value;
    };
    std::vector<DeferredArgument> axiomArguments;
    std::vector<ModuleAge> ages;  // `age:` declarations, in file order

    // The table used by derivation step `step` (1-based); 0 when there are no tables.
    int tableForStep(int step) const;
    bool usesCut() const;  // any '%' in the axiom or a successor
    bool hasContext() const;
    bool hasMultiModulePredecessor() const;
    bool isParametric() const;
    // Whether a derivation step has effects beyond its string: a production block, or an
    // expression that writes (printf). Such steps rewrite the modules in string order.
    bool hasSideEffects() const;
    // Whether a derivation ever draws a random number: a stochastic production, or ran(),
    // nran(), bran(), biran() or srand() in a condition, a successor's parameters, a block
    // or the axiom (decomposition included; the homomorphism is not part of a derivation).
    bool drawsRandomNumbers() const;
    bool hasGlobalBlocks() const {
        return !startBlock.empty() || !startEachBlock.empty() || !endEachBlock.empty() ||
               !endBlock.empty();
    }
    // Prints the L-system back in the .l language; the view settings, when given, go where
    // a .l file usually has them (after the seed).
    void print(std::ostream& os, const ViewSettings* view = nullptr) const;
};

std::ostream& operator<<(std::ostream& os, const LSystem& ls);

struct ParseOptions {
    std::string fileName;                        // used in locations
    std::map<std::string, std::string> defines;  // -D NAME=VALUE; wins over #define
    // A cpfg view file (.v) read after the .l (loadModel only). Its settings win over the
    // same settings in the .l, as cpfg reads view settings only from the view file.
    std::string viewFile;
    // The one-letter surface names the view file declares (`surface: L leaf.s`), known
    // before the .l is read so that `~LF` is the surface L then F, as in cpfg. parse() with
    // a view file's text and loadModel() fill it in.
    std::string surfaceLetters;
};

// The grammar of .l text, for programs that only rewrite: parse(text, options) (model.hpp)
// with the errors thrown as one Error carrying all of them; the view and the warnings are
// dropped. Use parse() or loadModel() to keep them.
LSystem parseLSystem(std::string_view text, const ParseOptions& options = {});

// The same for a file (ParseOptions::fileName defaults to the path).
LSystem loadLSystem(const std::filesystem::path& path, ParseOptions options = {});

}  // namespace graftal
