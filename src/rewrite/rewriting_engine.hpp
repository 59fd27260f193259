// One parallel rewriting step over a list of productions: choose a production for every
// module, prefix-sum the successor sizes, write the successors. Used for derivation steps
// (with tables) and for the recursive decomposition and homomorphism passes.
#pragma once

#include <cstdint>
#include <vector>

#include "bracket_index.hpp"
#include "graftal/lsystem.hpp"
#include "graftal/module_string.hpp"

namespace graftal {

class RewritingEngine {
  public:
    RewritingEngine(const LSystem& ls, const std::vector<Production>& productions,
                    std::uint64_t seed, unsigned threads);

    // Rewrites `cur` into `next` with the productions of `table`. When `activeIn` is given,
    // only modules flagged there are rewritten; `activeOut` (when given) flags the modules
    // that came from a production. Returns false when no production applied anywhere.
    // Throws Error when the result would exceed `memoryLimit` bytes.
    bool step(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
              std::size_t memoryLimit, const std::vector<std::uint8_t>* activeIn = nullptr,
              std::vector<std::uint8_t>* activeOut = nullptr);

    bool parametric() const { return parametric_; }
    bool usesContext() const { return needBrackets_ || multiPred_; }
    // True when some symbol has a production in some table (false: identity for ever).
    bool rewrites(Symbol s) const;

    // Appends to `out` the successor of module i of `s` (or the module itself when no
    // production applies), choosing as a derivation step would for the module at
    // `position` of its string: the depth-first streamed derivation uses this.
    // Context-free productions only.
    void expandOne(const ModuleString& s, std::size_t i, std::uint64_t position, int stepNumber,
                   int table, ModuleString& out);

  private:
    struct Draws;
    bool stepFast(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                  std::size_t limit);
    bool stepGeneric(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                     std::size_t limit, const std::vector<std::uint8_t>* activeIn,
                     std::vector<std::uint8_t>* activeOut);
    std::int32_t choose(const ModuleString& s, std::size_t i, std::uint64_t position,
                        int stepNumber, int table, double* slots,
                        std::vector<double>& weights) const;
    bool matches(const Production& p, const ModuleString& s, std::size_t i, double* slots) const;
    bool matchLeft(const Production& p, const ModuleString& s, std::size_t i, double* slots,
                   int& slot) const;
    bool matchRight(const Production& p, const ModuleString& s, std::size_t from, double* slots,
                    int& slot) const;
    double evaluate(const Expression& e, const double* slots, Draws& draws) const;
    [[noreturn]] void rethrowAt(const class Error& err, const ModuleString& s, std::size_t i,
                                int stepNumber) const;
    void checkLimit(int stepNumber, std::size_t modules, std::size_t params, std::size_t extra,
                    const ModuleString& cur, std::size_t limit) const;
    std::size_t chunkCount(std::size_t n) const;
    void buildFastTables();

    const LSystem& ls_;
    const std::vector<Production>& productions_;
    std::uint64_t seed_;
    unsigned threads_;
    bool fast_ = false;
    bool multiPred_ = false;
    bool parametric_ = false;
    bool needBrackets_ = false;
    int maxSlots_ = 1;
    std::size_t tableCount_ = 1;

    // Per table: productions whose predecessor starts with a symbol, in file order.
    std::vector<std::vector<std::vector<std::uint32_t>>> candidates_;
    // Fast path, per table: the successor of each symbol, flattened (identity included).
    std::vector<std::vector<std::uint32_t>> fastStart_;
    std::vector<std::vector<Symbol>> fastSymbols_;

    BracketIndex brackets_;
    std::vector<double> scratchSlots_, scratchWeights_;
    std::vector<std::int32_t, UninitializedAllocator<std::int32_t>> choice_;
};

}  // namespace graftal
