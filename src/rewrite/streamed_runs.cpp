// Streamed derivation in runs (streamed_runs.hpp). Without parameters or random choices the
// expansion of a module depends only on its symbol and the step it stands at, so the walk
// keeps, for every (step, symbol) whose final expansion has at most kRunModules modules,
// that expansion once made, and hands it over whole wherever the walk meets it again.
// Above those sizes the walk is streamDerivation()'s depth-first walk.
#include "graftal/rewrite/streamed_runs.hpp"

#include <algorithm>
#include <map>
#include <vector>

#include "graftal/rewrite/streaming.hpp"
#include "rewriting_engine.hpp"

namespace graftal {

namespace {

// Runs of up to 64 K modules: large enough that handing one over costs nothing beside its
// copy, small enough that the kept expansions stay in the caches.
constexpr std::uint64_t kRunModules = std::uint64_t(1) << 16;
// Beyond this many kept modules an expansion is made again each time it is met.
constexpr std::size_t kKeptModules = std::size_t(32) << 20;
constexpr std::uint64_t kSaturated = std::uint64_t(1) << 62;

class RunWalker {
  public:
    RunWalker(const LSystem& ls, int steps, const DerivationOptions& options)
        : ls_(ls),
          steps_(steps),
          options_(options),
          engine_(ls, ls.productions, options.seed.value_or(ls.seed), 1),
          symbolCount_(ls.symbols.size()) {
        // The successor of every symbol in every table, once.
        const std::size_t tables = std::max<std::size_t>(1, ls.tableNames.size());
        successors_.resize(tables * symbolCount_);
        ModuleString one;
        ModuleString next;
        for (std::size_t t = 0; t < tables; ++t)
            for (std::size_t s = 0; s < symbolCount_; ++s) {
                one.clear();
                one.push(static_cast<Symbol>(s));
                next.clear();
                if (engine_.rewrites(static_cast<Symbol>(s)))
                    engine_.expandOne(one, 0, 0, stepOfTable(t), static_cast<int>(t), next);
                else
                    next.push(static_cast<Symbol>(s));
                const auto syms = next.symbols();
                successors_[t * symbolCount_ + s].assign(syms.begin(), syms.end());
            }
        // The final modules of each symbol at each level, from the last level up.
        counts_.assign(static_cast<std::size_t>(steps_ + 1) * symbolCount_, 0);
        for (std::size_t s = 0; s < symbolCount_; ++s) count(steps_, s) = 1;
        for (int d = steps_ - 1; d >= 0; --d)
            for (std::size_t s = 0; s < symbolCount_; ++s) {
                std::uint64_t c = 0;
                for (Symbol t : successor(d, static_cast<Symbol>(s)))
                    c = std::min(kSaturated, c + count(d + 1, t));
                count(d, s) = c;
            }
    }

    void walk(const std::function<void(std::span<const Symbol>)>& emit) {
        struct Level {
            const Symbol* at;
            const Symbol* end;
        };
        std::vector<Level> levels;
        const auto axiom = ls_.axiom.symbols();
        levels.push_back({axiom.data(), axiom.data() + axiom.size()});
        std::uint64_t emitted = 0, reported = 0;
        while (!levels.empty()) {
            Level& here = levels.back();
            if (here.at == here.end) {
                levels.pop_back();
                continue;
            }
            const Symbol s = *here.at++;
            const int d = static_cast<int>(levels.size()) - 1;
            const std::uint64_t c = count(d, s);
            if (c > kRunModules) {
                const std::span<const Symbol> next = successor(d, s);
                levels.push_back({next.data(), next.data() + next.size()});
                continue;
            }
            emit(expansion(d, s));
            emitted += c;
            if (emitted - reported >= (1u << 20)) {
                reported = emitted;
                options_.cancel.check();
                if (options_.progress) options_.progress(steps_, static_cast<std::size_t>(emitted));
            }
        }
    }

  private:
    int stepOfTable(std::size_t table) const {
        // A step that uses `table` (its number only matters to expressions, which a
        // non-parametric L-system has none of).
        for (int step = 1; step <= steps_; ++step)
            if (static_cast<std::size_t>(ls_.tableForStep(step)) == table) return step;
        return 1;
    }
    std::uint64_t& count(int d, std::size_t s) {
        return counts_[static_cast<std::size_t>(d) * symbolCount_ + s];
    }
    // The successor that rewrites `s` standing in string d (by step d + 1).
    std::span<const Symbol> successor(int d, Symbol s) const {
        const std::size_t tables = successors_.size() / symbolCount_;
        const std::size_t t = std::min<std::size_t>(
            static_cast<std::size_t>(std::max(0, ls_.tableForStep(d + 1))), tables - 1);
        return successors_[t * symbolCount_ + s];
    }
    // The final modules of `s` standing in string d, kept when there is room.
    std::span<const Symbol> expansion(int d, Symbol s) {
        const std::size_t key = static_cast<std::size_t>(d) * symbolCount_ + s;
        if (auto it = kept_.find(key); it != kept_.end()) return it->second;
        scratch_.clear();
        expandInto(d, s, scratch_);
        if (keptModules_ + scratch_.size() > kKeptModules) return scratch_;
        keptModules_ += scratch_.size();
        return kept_.emplace(key, scratch_).first->second;
    }
    void expandInto(int d, Symbol s, std::vector<Symbol>& out) {
        // A symbol no table rewrites stays itself down to the last string.
        if (d == steps_ || !engine_.rewrites(s)) {
            out.push_back(s);
            return;
        }
        for (Symbol t : successor(d, s)) expandInto(d + 1, t, out);
    }

    const LSystem& ls_;
    int steps_;
    const DerivationOptions& options_;
    RewritingEngine engine_;
    std::size_t symbolCount_;
    std::vector<std::vector<Symbol>> successors_;  // per table, per symbol
    std::vector<std::uint64_t> counts_;            // per level, per symbol (saturated)
    std::map<std::size_t, std::vector<Symbol>> kept_;
    std::size_t keptModules_ = 0;
    std::vector<Symbol> scratch_;
};

}  // namespace

bool streamsInRuns(const LSystem& ls) {
    if (!streamingObstacle(ls).empty() || ls.isParametric()) return false;
    for (const auto& p : ls.productions)
        if (p.probability) return false;
    return true;
}

void streamDerivationRuns(const LSystem& ls, int steps,
                          const std::function<void(std::span<const Symbol>)>& emit,
                          const DerivationOptions& options) {
    if (!streamsInRuns(ls))
        throw Error(SourceLocation{ls.file, 0, 0},
                    "this L-system cannot be streamed in runs: it has parameters, conditions or "
                    "stochastic productions, or cannot be streamed at all");
    if (steps < 0) steps = ls.derivationLength;
    RunWalker(ls, steps, options).walk(emit);
}

}  // namespace graftal
