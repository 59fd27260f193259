// Depth-first expansion. Level k holds the successor being expanded of one module of
// string k-1; only one such successor per level is alive at a time, so memory is
// O(depth × successor length). Visiting level k in depth-first order meets the modules
// of string k from left to right, so each module's position in its string is a running
// counter per level, and the counter-based random stream gives the materialised choices.
#include "graftal/rewrite/streaming.hpp"

#include "graftal/core/parallel.hpp"
#include "graftal/rewrite/parallel_stream.hpp"
#include "rewriting_engine.hpp"

namespace graftal {

std::string streamingObstacle(const LSystem& ls) {
    if (ls.hasContext()) return "its productions have context";
    if (ls.hasMultiModulePredecessor()) return "it has multi-module predecessors";
    if (!ls.decomposition.empty()) return "it has a decomposition section";
    if (!ls.homomorphism.empty()) return "it has a homomorphism section";
    if (ls.usesCut()) return "it uses the cut symbol %";
    if (ls.hasSideEffects() || ls.hasGlobalBlocks() || ls.stateNames.size() > 2 ||
        !ls.axiomArguments.empty())
        return "it has statement blocks or variables (they run in string order)";
    for (const auto& p : ls.productions) {
        bool state = p.condition && p.condition->usesState();
        for (const auto& m : p.successor)
            for (const auto& a : m.args) state |= a.usesState();
        if (state) return "it reads Q, Z or variables";
    }
    if (ls.random == RandomStreams::Cpfg && ls.drawsRandomNumbers())
        return "it draws cpfg's random numbers, which come in string order";
    if (!ls.environment.empty()) return "it talks to an environment";
    for (Symbol s : ls.axiom.symbols())
        if (s >= kQueryE && s <= kQueryU) return "it has query modules";
    for (const auto& p : ls.productions)
        for (const auto& m : p.successor)
            if (m.symbol >= kQueryE && m.symbol <= kQueryU) return "it has query modules";
    return {};
}

void streamDerivation(const LSystem& ls, int steps, ModuleSink& sink,
                      const DerivationOptions& options) {
    if (std::string why = streamingObstacle(ls); !why.empty())
        throw Error(SourceLocation{ls.file, 0, 0}, "this L-system cannot be streamed: " + why);
    if (steps < 0) steps = ls.derivationLength;
    // Without random numbers no module needs its position: workers derive chunks of the
    // string (on one thread, this one) and this thread hands their modules to the sink, in
    // order.
    if (streamsInParallel(ls)) {
        // A block's parameters are read as doubles once, not module by module.
        std::vector<double> values;
        streamDerivationParallel(
            ls, steps, nullptr,
            [&](const StreamBlock& block) {
                const ModuleString& m = block.modules;
                const std::span<const Symbol> symbols = m.symbols();
                if (!m.hasParameters()) {
                    for (Symbol s : symbols) sink.module(s, {});
                    return;
                }
                const double* p = m.doubleParams().data();
                if (m.precision() == Precision::Single) {
                    values.assign(m.floatParams().begin(), m.floatParams().end());
                    p = values.data();
                }
                const std::uint32_t* starts = m.paramStarts().data();
                for (std::size_t i = 0; i < symbols.size(); ++i)
                    sink.module(symbols[i], {p + starts[i], starts[i + 1] - starts[i]});
            },
            options);
        return;
    }
    RewritingEngine engine(ls, ls.productions, options.seed.value_or(ls.seed), 1);
    bool random = false;
    for (const auto& p : ls.productions) {
        random |= p.probability.has_value();
        for (const auto& m : p.successor)
            for (const auto& a : m.args) random |= a.usesRandom();
        if (p.condition) random |= p.condition->usesRandom();
    }
    // A symbol no table ever rewrites goes straight to the sink; only random choices need
    // the positions it would have taken in the deeper strings.
    std::vector<bool> fixed(ls.symbols.size());
    for (std::size_t s = 0; s < fixed.size(); ++s)
        fixed[s] = !engine.rewrites(static_cast<Symbol>(s));

    // Each level stores parameters as a derivation would: streamed and held strings agree.
    std::vector<ModuleString> level(static_cast<std::size_t>(steps) + 1,
                                    ModuleString(options.precision));
    std::vector<std::size_t> cursor(level.size(), 0);
    std::vector<std::uint64_t> position(level.size(), 0);
    std::vector<double> scratch;
    level[0] = ls.axiom;
    level[0].setPrecision(options.precision);
    std::size_t d = 0;
    // A streamed derivation is one long step: the token is looked at every few thousand
    // expansions, often enough to stop within a millisecond, rarely enough to cost nothing.
    std::uint32_t expansions = 0;
    std::uint64_t emitted = 0;
    while (true) {
        if (cursor[d] == level[d].size()) {
            if (d == 0) break;
            --d;
            continue;
        }
        std::size_t i = cursor[d]++;
        const ModuleString& here = level[d];
        Symbol s = here.symbol(i);
        if (d == static_cast<std::size_t>(steps) || fixed[s]) {
            sink.module(s, here.params(i).doubles(scratch));
            // Progress: the modules of the last string out so far, every million.
            if ((++emitted & 0xFFFFFu) == 0 && options.progress)
                options.progress(steps, static_cast<std::size_t>(emitted));
            if (random)
                for (std::size_t k = d; k < level.size(); ++k) ++position[k];
            continue;
        }
        if ((++expansions & 0xFFFu) == 0) options.cancel.check();
        std::uint64_t pos = position[d]++;
        ModuleString& next = level[d + 1];
        next.clear();
        engine.expandOne(here, i, pos, static_cast<int>(d) + 1,
                         ls.tableForStep(static_cast<int>(d) + 1), next);
        cursor[d + 1] = 0;
        ++d;
    }
}

}  // namespace graftal
