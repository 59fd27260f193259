// The compiled L-system: what the parser produces and the derivation engine runs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/diagnostics.hpp"
#include "graftal/environment.hpp"
#include "graftal/expression.hpp"
#include "graftal/module_string.hpp"
#include "graftal/scene.hpp"

namespace graftal {

// How the picture is drawn: the view settings a .l file may carry.
enum class LineStyle { Lines, Cylinders };

// A predefined surface a file names: `surface: l leaf.s 0.5` places leaf.s at `~l`.
struct SurfaceDeclaration {
    std::string name;  // what follows ~ in module strings
    std::string file;  // a .s file, relative to the L-system file, or a built-in name
    double scale = 1;
    SourceLocation location;
};

struct ViewSettings {
    double angleDegrees = 90;                    // δ, the turn of + and -
    double stepLength = 1;                       // length of F and f
    double initialHeading = 0;                   // degrees counter-clockwise from up (+y)
    double scaleFactor = 100;                    // pfg's picture size in percent of the window
    bool clockwisePlus = false;                  // pfg data files: + turns right on screen
    double initialWidth = 0.1;                   // stem diameter before any ! or #, in model units
    double widthFactor = 0.7;                    // ! multiplies the width by this, # divides by it
    LineStyle lineStyle = LineStyle::Cylinders;  // how 3D outputs draw segments
    // Tropism (LSFP ch. 3.1): after each segment H turns toward `tropism` by e·|H × T|.
    std::optional<Vec3> tropism;
    double elasticity = 0;
    // Camera and light for pictures of 3D scenes (cpfg's view-file names).
    std::optional<Vec3> viewpoint, viewReferencePoint, upVector, lightDirection;
    std::optional<double> fieldOfView;  // degrees
    bool parallelProjection = false;
    std::optional<Rgb> background;
    std::string colorMap;        // a cpfg .map file, relative to the L-system file
    int splineSubdivisions = 0;  // > 0: draw turtle paths as B-splines (LSFP Fig 2.10)
    std::vector<SurfaceDeclaration> surfaces;
};

std::ostream& operator<<(std::ostream& os, const ViewSettings& v);

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
        Assign,         // state[target] = value
        AssignElement,  // state[address] = value (an array element)
        Evaluate,       // value, for its effect (printf)
        If,             // if (value) body else elseBody
        While,          // while (value) body
        DoWhile,        // do body while (value)
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
    // `ring lsystem`: for context matching the string is a ring (its last module is
    // followed by its first).
    bool ring = false;
    ViewSettings view;
    bool legacyPfg = false;                    // read as a pfg data file (no Lsystem: header)
    std::vector<EnvironmentLine> environment;  // `environment:` lines, in file order
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
    std::vector<Diagnostic> warnings;  // what the parser noticed but accepted

    // The table used by derivation step `step` (1-based); 0 when there are no tables.
    int tableForStep(int step) const;
    bool usesCut() const;  // any '%' in the axiom or a successor
    bool hasContext() const;
    bool hasMultiModulePredecessor() const;
    bool isParametric() const;
    // Whether a derivation step has effects beyond its string: a production block, or an
    // expression that writes (printf). Such steps rewrite the modules in string order.
    bool hasSideEffects() const;
    bool hasGlobalBlocks() const {
        return !startBlock.empty() || !startEachBlock.empty() || !endEachBlock.empty() ||
               !endBlock.empty();
    }
    // Prints the L-system back in the .l language.
    void print(std::ostream& os) const;
};

std::ostream& operator<<(std::ostream& os, const LSystem& ls);

struct ParseOptions {
    std::string fileName;                        // used in locations
    std::map<std::string, std::string> defines;  // -D NAME=VALUE; wins over #define
};

// Parses .l text. Collects every diagnostic it can and throws Error carrying all of them
// if any is an error; warnings end up in LSystem::warnings.
LSystem parseLSystem(std::string_view text, const ParseOptions& options = {});

// Reads and parses a file (ParseOptions::fileName defaults to the path).
LSystem loadLSystem(const std::filesystem::path& path, ParseOptions options = {});

}  // namespace graftal
