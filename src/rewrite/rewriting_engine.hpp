// One parallel rewriting step over a list of productions: choose a production for every
// module, prefix-sum the successor sizes, write the successors. Used for derivation steps
// (with tables) and for the recursive decomposition and homomorphism passes.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "bracket_index.hpp"
#include "context_rewriter.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/lang/lsystem.hpp"

namespace graftal {

class CpfgRandom;

class RewritingEngine {
  public:
    RewritingEngine(const LSystem& ls, const std::vector<Production>& productions,
                    std::uint64_t seed, unsigned threads);
    ~RewritingEngine();

    // Rewrites `cur` into `next` with the productions of `table`. When `activeIn` is given,
    // only modules flagged there are rewritten; `activeOut` (when given) flags the modules
    // that came from a production. Returns false when no production applied anywhere.
    // Throws Error when the result would exceed `memoryLimit` bytes.
    bool step(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
              std::size_t memoryLimit, const std::vector<std::uint8_t>* activeIn = nullptr,
              std::vector<std::uint8_t>* activeOut = nullptr);
    // step() for a caller done with `cur` once the step succeeds: the context path may then
    // note its choices over `cur` itself instead of beside it (a byte a module less at the
    // step's peak). Afterwards `cur` holds no string; if the step throws, it is as it was.
    bool stepConsuming(ModuleString& cur, ModuleString& next, int stepNumber, int table,
                       std::size_t memoryLimit);

    // The L-system's state (LSystem::stateNames) that blocks and expressions read and
    // write, and where printf writes. Without it, expressions that need them fail.
    // Draw cpfg's random numbers from `random` (cpfg_random.hpp), in cpfg's order: modules
    // are rewritten one after the other; when `stochastic` (cpfg: the file has a `seed:`
    // line) every module draws once to choose among its applicable productions, each
    // weighted by its probability (1 when it has none); otherwise the first applicable
    // production applies and probabilities are not read.
    // With `cuts`, a `%` no production rewrites cuts its branch as the step reaches it (cpfg
    // cuts there, so the modules before it see the whole string in their contexts).
    void useCpfgRandom(CpfgRandom* random, bool stochastic, bool cuts = false) {
        cpfg_ = random;
        cpfgStochastic_ = stochastic;
        cpfgCuts_ = cuts;
        sequential_ = true;
        parametric_ = true;
    }

    void setState(double* state, const std::function<void(std::string_view)>* print,
                  OutputFiles* files = nullptr) {
        state_ = state;
        print_ = print;
        files_ = files;
    }
    // Runs a block of statements with `slots` bound (nullptr for Start: and the like).
    void runBlock(const Block& block, double* slots, int stepNumber, std::uint64_t position) const;

    bool parametric() const { return parametric_; }
    bool usesContext() const { return needBrackets_ || multiPred_; }
    // True when some symbol has a production in some table (false: identity for ever).
    bool rewrites(Symbol s) const;

    // The modules of each symbol (indexed by symbol id) that step() would write, counted
    // without writing them. False (counts untouched) when such a step must be done in full:
    // productions with blocks, and the paths that write as they choose.
    bool countStep(const ModuleString& cur, std::vector<std::uint64_t>& counts, int stepNumber,
                   int table, std::size_t memoryLimit);

    // Appends to `out` the successor of module i of `s` (or the module itself when no
    // production applies), choosing as a derivation step would for the module at
    // `position` of its string: the depth-first streamed derivation uses this.
    // Context-free productions only.
    void expandOne(const ModuleString& s, std::size_t i, std::uint64_t position, int stepNumber,
                   int table, ModuleString& out);

    // For tests: every step takes the generic path, choosing with choose() and binding with
    // matches(), which the fast paths must agree with.
    void useGenericPathOnly() { genericOnly_ = true; }
    // True when context-sensitive steps take the ContextRewriter.
    bool usesContextPath() const { return context_ != nullptr; }

  private:
    struct Draws;
    bool stepFast(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                  std::size_t limit);
    bool stepContext(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                     std::size_t limit);
    bool stepSequential(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                        std::size_t limit, const std::vector<std::uint8_t>* activeIn,
                        std::vector<std::uint8_t>* activeOut);
    void runStatements(const Block& block, double* slots, Draws& draws) const;
    bool stepGeneric(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                     std::size_t limit, const std::vector<std::uint8_t>* activeIn,
                     std::vector<std::uint8_t>* activeOut);
    // The production that rewrites module i (kIdentity: none). On return `slots` hold the
    // chosen production's parameters, as its pre block left them.
    std::int32_t choose(const ModuleString& s, std::size_t i, std::uint64_t position,
                        int stepNumber, int table, double* slots,
                        std::vector<double>& weights) const;
    // choose() the way cpfg chooses, on cpfg's generators (useCpfgRandom).
    std::int32_t chooseCpfg(const ModuleString& s, std::size_t i, int stepNumber, int table,
                            double* slots) const;
    bool matches(const Production& p, const ModuleString& s, std::size_t i, double* slots) const;
    bool matchLeft(const Production& p, const ModuleString& s, std::size_t i, double* slots,
                   int& slot) const;
    bool matchRight(const Production& p, const ModuleString& s, std::size_t from, double* slots,
                    int& slot) const;
    double evaluate(const Expression& e, const double* slots, Draws& draws) const;
    // Blocks (which run on one thread) always print; expressions only in sequential steps.
    double evaluate(const Expression& e, const double* slots, Draws& draws, bool mayPrint) const;
    // Re-raises an expression's error under the production being applied (`p`; when null,
    // the error already names it), naming the module and the derivation step.
    [[noreturn]] void rethrowAt(const class Error& err, const ModuleString& s, std::size_t i,
                                int stepNumber, const Production* p = nullptr) const;
    static double stringBytes(std::size_t modules, std::size_t params, bool parametric,
                              std::size_t paramBytes);
    void chooseAll(const ModuleString& cur, int stepNumber, int table,
                   const std::vector<std::uint8_t>* activeIn, std::size_t chunks,
                   std::vector<std::size_t>& modCount, std::vector<std::size_t>& paramCount,
                   std::vector<std::size_t>& rewritten);
    template <class T>
    void writeGeneric(const ModuleString& cur, const T* params, T* outParams, Symbol* outSyms,
                      std::uint32_t* outStart, const std::vector<std::size_t>& modOff,
                      const std::vector<std::size_t>& paramOff, std::size_t chunks, int stepNumber,
                      std::vector<std::uint8_t>* activeOut);
    void prepareOutput(const ModuleString& cur, ModuleString& next, std::size_t modules,
                       std::size_t params, bool parametric, std::size_t extra,
                       std::size_t limit) const;
    void checkLimit(int stepNumber, std::size_t modules, std::size_t params, std::size_t extra,
                    const ModuleString& cur, std::size_t limit) const;
    std::size_t chunkCount(std::size_t n) const;
    void buildFastTables();
    void buildQuickChoices();

    const LSystem& ls_;
    const std::vector<Production>& productions_;
    std::uint64_t seed_;
    unsigned threads_;
    bool fast_ = false;
    bool multiPred_ = false;
    bool parametric_ = false;
    bool needBrackets_ = false;
    bool genericOnly_ = false;
    // Productions with blocks or printf: modules are rewritten one after the other, in
    // string order, on one thread (what a block writes is seen by the modules after it).
    bool sequential_ = false;
    CpfgRandom* cpfg_ = nullptr;  // cpfg's generators (useCpfgRandom), or graftal's streams
    bool cpfgStochastic_ = false;
    bool cpfgCuts_ = false;
    double* state_ = nullptr;
    const std::function<void(std::string_view)>* print_ = nullptr;
    OutputFiles* files_ = nullptr;
    int maxSlots_ = 1;
    std::size_t tableCount_ = 1;

    // Per table: productions whose predecessor starts with a symbol, in file order.
    std::vector<std::vector<std::vector<std::uint32_t>>> candidates_;
    // Fast path, per table: the successor of each symbol, flattened (identity included).
    std::vector<std::vector<std::uint32_t>> fastStart_;
    std::vector<std::vector<Symbol>> fastSymbols_;
    // When every successor of a table has at most kShortSuccessor symbols: each one padded
    // to a fixed slot (written with one vector store) and its length.
    static constexpr std::size_t kShortSuccessor = 16;
    struct ShortSuccessor {
        Symbol symbols[kShortSuccessor];
    };
    std::vector<std::vector<ShortSuccessor>> fastShort_;
    std::vector<std::vector<std::uint8_t>> fastLength_;

    // Parametric steps: see buildQuickChoices.
    static constexpr std::size_t kQuickArity = 8;
    struct QuickChoice {
        bool simple = false;
        std::array<std::int32_t, kQuickArity> byArity{};
    };
    std::vector<std::vector<QuickChoice>> quick_;                    // per table, per symbol
    std::vector<std::uint32_t> successorModules_, successorParams_;  // per production
    // A production's successor laid out flat: its symbols, where each module's arguments
    // begin, and the arguments; `direct` when they can be evaluated on the predecessor's
    // own parameters (no context, one module, no ran()).
    struct Flat {
        std::vector<Symbol> symbols;
        std::vector<std::uint32_t> argStart;
        std::vector<const Expression*> args;
        bool direct = false;
    };
    std::vector<Flat> flat_;  // per production

    // Context-sensitive steps without parameters, when the contexts are single modules.
    std::unique_ptr<ContextRewriter> context_;

    BracketIndex brackets_;
    std::vector<double> scratchSlots_, scratchWeights_, scratchArgs_;
    // The production chosen for every module of the step being written (see ChoiceCode).
    std::vector<std::uint16_t, UninitializedAllocator<std::uint16_t>> choice_;
};

}  // namespace graftal
