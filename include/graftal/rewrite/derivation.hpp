// The derivation engine: parallel rewriting of a module string, step by step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "graftal/core/cancellation.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal {

// Walks the turtle over `modules` (the string after the homomorphism) and calls
// visit(i, frame) for every module whose symbol is flagged in `wanted` (indexed by symbol
// id): how a derivation learns where its query modules ?P ?H ?L ?U and ?E are. The turtle
// layer supplies one (turtleQueryResolver() in turtle.hpp); the derivation does not know
// the turtle.
using QueryResolver = std::function<void(
    const LSystem& lsystem, const ModuleString& modules, const std::vector<bool>& wanted,
    const std::function<void(std::size_t, const TurtleFrame&)>& visit)>;

struct DerivationOptions {
    // Bytes the module strings may take; a step that would need more is refused before
    // anything is allocated, with a message saying how large the string would get.
    std::size_t memoryLimit = std::size_t(2) << 30;
    std::optional<std::uint64_t> seed;  // overrides the file's seed
    // Overrides LSystem::random: cpfg's generators (the string cpfg gives; the steps then
    // run in string order on one thread) or graftal's streams.
    std::optional<RandomStreams> random;
    unsigned threads = 0;  // 0: one per core. The output never depends on it.
    // Answers ?E modules. nullptr: the one the file's `environment:` lines describe (if any).
    Environment* environment = nullptr;
    // Called after every step with the step number and the string's size (for progress).
    // A streamed derivation calls it every million modules of its last string with the
    // last step's number and the modules out so far.
    std::function<void(int step, std::size_t modules)> progress;
    // Fills query modules after every step. Empty: a string with query modules is an error.
    QueryResolver queryResolver;
    // Raised from another thread to stop: checked before and after every step's rewriting;
    // a cancelled step throws Cancelled and leaves the current string as it was.
    CancellationToken cancel;
    // Where printf writes (cpfg writes to standard error). Empty: the text is dropped.
    std::function<void(std::string_view)> print;
    // How the derived strings store parameters: 32-bit floats, as cpfg (half the memory),
    // or doubles. Expressions are evaluated in double either way.
    Precision precision = Precision::Single;
};

class Derivation {
  public:
    // The derivation keeps its own copy of the L-system: `Derivation d(parseLSystem(text))`
    // is safe, and so is changing the original afterwards.
    explicit Derivation(LSystem lsystem, DerivationOptions options = {});
    // The grammar of a model (query modules are placed by options.queryResolver, which
    // knows the view: turtleQueryResolver(model.view)).
    Derivation(const Model& model, DerivationOptions options = {});
    ~Derivation();
    Derivation(const Derivation&) = delete;
    Derivation& operator=(const Derivation&) = delete;

    // Performs one derivation step. Throws Error when a limit would be exceeded or an
    // expression fails; the current string is then left as it was.
    void step();
    void run(int steps);
    // Runs the End: block, once, after the last step (not when no step was done, as cpfg).
    // derive() calls it; callers that drive step() themselves call it when done.
    void finish();
    // The L-system's variables (LSystem::stateNames): Q, Z, then globals and the
    // productions' own variables.
    const std::vector<double>& state() const { return state_; }

    int stepsDone() const { return steps_; }
    const ModuleString& current() const { return *current_; }
    ModuleString take() { return std::move(*current_); }

    // The number of modules of each symbol (indexed by symbol id) that one more step would
    // make, counted without writing that string: what `stats` needs of the last step, for
    // half the memory. Empty when the step cannot be counted without being done (blocks or
    // printf in productions, decomposition, query modules, environment); the derivation is
    // left as it was either way. Throws what step() would throw.
    std::vector<std::uint64_t> countNextStep();

  private:
    void afterStep(int stepNumber);
    void decompose(int stepNumber);
    void answerQueries(int stepNumber);

    LSystem lsystem_;
    DerivationOptions options_;
    std::unique_ptr<ModuleString> current_, next_;
    std::unique_ptr<class RewritingEngine> rules_, decomposition_;
    std::unique_ptr<class CpfgRandom> cpfgRandom_;  // cpfg's generators, when drawn from
    std::unique_ptr<Environment> ownedEnvironment_;
    Environment* environment_ = nullptr;
    bool queries_ = false;
    // cpfg with a view file's `box:` writes its string before interpreting it: the query
    // modules a step makes are answered when the next step begins, and never after the
    // last (set for cpfg's random numbers and LSystem::cpfgViewBox).
    bool deferQueries_ = false;
    int pendingQueries_ = -1;  // the step whose queries wait, or -1
    bool finished_ = false;
    int steps_ = 0;
    std::vector<double> state_;
    std::unique_ptr<class ModelOutputFiles> files_;  // fopen/fprintf in the model
};

// Derives `steps` steps from the axiom (steps < 0: the file's derivation length).
ModuleString derive(const LSystem& lsystem, int steps = -1, DerivationOptions options = {});
ModuleString derive(const Model& model, int steps = -1, DerivationOptions options = {});

// The string the turtle sees: `modules` with the homomorphism productions applied
// recursively (up to the homomorphism's maximum depth). A copy when there are none.
ModuleString applyHomomorphism(const LSystem& lsystem, const ModuleString& modules,
                               DerivationOptions options = {});

}  // namespace graftal
