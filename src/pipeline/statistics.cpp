// measured(): the statistics of a derivation (statistics.hpp), by the cheapest road that
// gives them exactly.
#include "graftal/pipeline/statistics.hpp"

#include "graftal/pipeline/stages.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/turtle/d0l_measure.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"

namespace graftal {

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
    if (streamed) {
        const StreamedMeasure m = measureStreamed(model, steps, options, geometry);
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
        Derivation d(model, options);
        d.run(steps - 1);
        std::vector<std::uint64_t> counts = d.countNextStep();
        if (counts.empty()) {
            d.step();
            d.finish();
            counts = countSymbols(d.current(), model.lsystem.symbols.size(), request.threads);
        }
        for (std::uint64_t c : counts) stats.modules += c;
        stats.symbolCounts = std::move(counts);
        return stats;
    }
    DeriveRequest exact = request;
    exact.steps = steps;
    Derived derivedModel = derived(model, exact);
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
