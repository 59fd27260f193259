// The derivation engine: parallel rewriting of a module string, step by step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "graftal/lsystem.hpp"
#include "graftal/module_string.hpp"

namespace graftal {

struct DerivationOptions {
    // Bytes the module strings may take; a step that would need more is refused before
    // anything is allocated, with a message saying how large the string would get.
    std::size_t memoryLimit = std::size_t(2) << 30;
    std::optional<std::uint64_t> seed;  // overrides the file's seed
    unsigned threads = 0;               // 0: one per core. The output never depends on it.
    // Answers ?E modules. nullptr: the one the file's `environment:` lines describe (if any).
    Environment* environment = nullptr;
    // Called after every step with the step number and the string's size (for progress).
    std::function<void(int step, std::size_t modules)> progress;
    // Where printf writes (cpfg writes to standard error). Empty: the text is dropped.
    std::function<void(std::string_view)> print;
};

class Derivation {
  public:
    // The derivation keeps its own copy of the L-system: `Derivation d(parseLSystem(text))`
    // is safe, and so is changing the original afterwards.
    explicit Derivation(LSystem lsystem, DerivationOptions options = {});
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

  private:
    void afterStep(int stepNumber);
    void decompose(int stepNumber);
    void answerQueries(int stepNumber);

    LSystem lsystem_;
    DerivationOptions options_;
    std::unique_ptr<ModuleString> current_, next_;
    std::unique_ptr<class RewritingEngine> rules_, decomposition_;
    std::unique_ptr<Environment> ownedEnvironment_;
    Environment* environment_ = nullptr;
    bool queries_ = false;
    bool finished_ = false;
    int steps_ = 0;
    std::vector<double> state_;
    std::unique_ptr<class ModelOutputFiles> files_;  // fopen/fprintf in the model
};

// Derives `steps` steps from the axiom (steps < 0: the file's derivation length).
ModuleString derive(const LSystem& lsystem, int steps = -1, DerivationOptions options = {});

// The string the turtle sees: `modules` with the homomorphism productions applied
// recursively (up to the homomorphism's maximum depth). A copy when there are none.
ModuleString applyHomomorphism(const LSystem& lsystem, const ModuleString& modules,
                               DerivationOptions options = {});

}  // namespace graftal
