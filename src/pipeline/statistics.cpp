// measured(): the statistics of a derivation (statistics.hpp), by the cheapest road that
// gives them exactly.
#include "graftal/pipeline/statistics.hpp"

#include "graftal/pipeline/stages.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/rewrite/parallel_stream.hpp"
#include "graftal/rewrite/streamed_runs.hpp"
#include "graftal/turtle/d0l_measure.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"

namespace graftal {

namespace {

// The symbols of the string derived in runs (streamed_runs.hpp), every module counted as
// its run goes by.
std::vector<std::uint64_t> countRuns(const Model& model, int steps,
                                     const DerivationOptions& options) {
    const std::size_t symbols = model.lsystem.symbols.size();
    std::vector<std::uint64_t> tallies(4 * symbols, 0);
    streamDerivationRuns(
        model.lsystem, steps,
        [&](std::span<const Symbol> run) { tallySymbols(run, tallies.data(), symbols); },
        options);
    std::vector<std::uint64_t> counts(symbols, 0);
    for (std::size_t k = 0; k < tallies.size(); ++k) counts[k % symbols] += tallies[k];
    return counts;
}

}  // namespace

ModelStatistics measured(const Model& model, const DeriveRequest& request, bool geometry) {
    ModelStatistics stats;
    stats.steps = requestedSteps(model, request);
    const int steps = stats.steps;
    const DerivationOptions options = derivationOptions(model, request);
    std::vector<Diagnostic> notes;
    const bool streamed = shouldStream(model, steps, request, true, false, false, notes);
    if (geometry) {
        // A flat D0-L system is measured from its productions, without writing the string:
        // the same numbers (the box is the one the road below would take), in a fraction of
        // the time and memory.
        const bool viewVolume = !streamed && !model.lsystem.legacyPfg;
        request.cancel.check();
        if (std::optional<StreamedMeasure> m = measureD0L(
                model, steps, viewVolume ? MeasuredBox::CpfgViewVolume : MeasuredBox::Drawing,
                request.cancel)) {
            stats.streamed = streamed;
            stats.modules = m->modules;
            stats.symbolCounts = std::move(m->symbolCounts);
            stats.measured = true;
            stats.segments = m->segments;
            stats.polygons = m->polygons;
            stats.bounds = m->bounds;
            return stats;
        }
    }
    const LSystem& ls = model.lsystem;
    if (!geometry && streamsInRuns(ls)) {
        // A D0-L string counted as it streams in runs: nothing is held.
        stats.streamed = true;
        stats.symbolCounts = countRuns(model, steps, options);
        for (std::uint64_t c : stats.symbolCounts) stats.modules += c;
        return stats;
    }
    // A parametric string streamed by parallel workers is not held at all, and is counted
    // or drawn about as fast as a held one: taken whenever it pays.
    const bool parallel = streamsInParallel(ls) && parallelThreads(request.threads) > 1 &&
                          (streamed || (request.stream == StreamPolicy::Auto &&
                                        parallelStreamPays(ls, steps, request.threads)));
    if (!geometry && parallel) {
        stats.streamed = true;
        stats.symbolCounts = countStreamedParallel(ls, steps, options);
        for (std::uint64_t c : stats.symbolCounts) stats.modules += c;
        return stats;
    }
    if (streamed || (parallel && ls.homomorphism.empty())) {
        // The box a held string reports: cpfg's view volume for a cpfg file.
        const bool viewVolume = !streamed && !ls.legacyPfg;
        const StreamedMeasure m = measureStreamed(model, steps, options, geometry, viewVolume);
        stats.streamed = true;
        stats.modules = m.modules;
        stats.symbolCounts = m.symbolCounts;
        stats.measured = geometry;
        stats.segments = m.segments;
        stats.polygons = m.polygons;
        stats.bounds = m.bounds;
        return stats;
    }
    if (!geometry && steps > 0) {
        // Symbol counts alone: the last step is counted without being written, which
        // halves the memory (and the fresh pages) the derivation needs.
        std::vector<std::uint64_t> counts = suggestingStream(model, request, true, [&] {
            Derivation d(model, options);
            d.run(steps - 1);
            std::vector<std::uint64_t> next = d.countNextStep();
            if (next.empty()) {
                d.step();
                d.finish();
                next = countSymbols(d.current(), model.lsystem.symbols.size(), request.threads);
            }
            return next;
        });
        for (std::uint64_t c : counts) stats.modules += c;
        stats.symbolCounts = std::move(counts);
        return stats;
    }
    DeriveRequest exact = request;
    exact.steps = steps;
    const Derived derivedModel =
        suggestingStream(model, request, true, [&] { return derived(model, exact); });
    const ModuleString& modules = derivedModel.modules;
    stats.modules = modules.size();
    const bool homomorphism = !model.lsystem.homomorphism.empty();
    if (geometry) {
        // Counts and bounds only: the turtle walks without storing any geometry. Without a
        // homomorphism that walk also counts the symbols, so the string is read once.
        const ModuleString shown =
            homomorphism ? applyHomomorphism(model.lsystem, modules, options) : ModuleString();
        const ModuleString& seen = homomorphism ? shown : modules;
        const StreamedMeasure m = measureModules(model, seen);
        stats.measured = true;
        stats.segments = m.segments;
        stats.polygons = m.polygons;
        stats.bounds = model.lsystem.legacyPfg ? m.bounds : cpfgViewVolume(model, seen);
        if (!homomorphism) stats.symbolCounts = m.symbolCounts;
    }
    if (stats.symbolCounts.empty())
        stats.symbolCounts = countSymbols(modules, model.lsystem.symbols.size(), request.threads);
    return stats;
}

}  // namespace graftal
