// The turtle fed by a streamed derivation: geometry for strings too large to hold.
#include "graftal/streaming.hpp"
#include "planar_measure.hpp"
#include "streamed_sinks.hpp"
#include "subtree_summaries.hpp"
#include "turtle_machine.hpp"

namespace graftal {

namespace {

// Adapts the turtle to the module stream.
template <class Sink>
class TurtleStream : public ModuleSink {
  public:
    TurtleStream(const Model& model, Sink& sink, StreamedMeasure* measure)
        : machine_(model, sink), measure_(measure) {}
    void module(Symbol s, std::span<const double> params) override {
        if (measure_) {
            ++measure_->modules;
            ++measure_->symbolCounts[s];
        }
        machine_.module(s, params, index_++);
    }
    void finish() { machine_.finish(); }

  private:
    turtle::TurtleMachine<Sink> machine_;
    StreamedMeasure* measure_;
    std::size_t index_ = 0;
};

class CountingSink : public ModuleSink {
  public:
    explicit CountingSink(StreamedMeasure& m) : m_(m) {}
    void module(Symbol s, std::span<const double>) override {
        ++m_.modules;
        ++m_.symbolCounts[s];
    }

  private:
    StreamedMeasure& m_;
};

}  // namespace

StreamedMeasure measureStreamed(const Model& model, int steps, const DerivationOptions& options,
                                bool geometry) {
    const LSystem& ls = model.lsystem;
    StreamedMeasure m;
    m.symbolCounts.assign(ls.symbols.size(), 0);
    if (!geometry) {
        CountingSink counter(m);
        streamDerivation(ls, steps, counter, options);
        return m;
    }
    MeasureSink sink(m);
    TurtleStream<MeasureSink> stream(model, sink, &m);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    return m;
}

StreamedMeasure measureModules(const Model& model, const ModuleString& modules) {
    // A flat L-system (most 2D figures) takes the planar walk, several times faster.
    if (turtle::staysPlanar(model))
        if (std::optional<StreamedMeasure> m = turtle::measurePlanar(model, modules))
            return std::move(*m);
    return turtle::measureGeneric(model, modules);
}

StreamedMeasure turtle::measureGeneric(const Model& model, const ModuleString& modules) {
    const LSystem& ls = model.lsystem;
    StreamedMeasure m;
    m.symbolCounts.assign(ls.symbols.size(), 0);
    for (Symbol s : modules.symbols()) ++m.symbolCounts[s];
    m.modules = modules.size();
    MeasureSink sink(m);
    turtle::TurtleMachine<MeasureSink> machine(model, sink);
    machine.run(modules);
    return m;
}

Scene interpretStreamed(const Model& model, int steps, const DerivationOptions& options) {
    const LSystem& ls = model.lsystem;
    Scene scene;
    turtle::SceneSink sink(scene);
    TurtleStream<turtle::SceneSink> stream(model, sink, nullptr);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    return scene;
}

namespace {
// Past this many segments a picture has far more strokes than pixels; subtrees smaller
// than a pixel are then drawn as one stroke each (subtree_summaries.hpp). Below it the
// picture is stroke for stroke the one the materialised path draws.
constexpr double kSummariseAbove = 2e7;
}  // namespace

bool streamedPictureIsSummarised(const Model& model, int steps, std::size_t memoryLimit) {
    SubtreeSummaries sums(model, steps, memoryLimit);
    return sums.available() && sums.segments() > kSummariseAbove;
}

void renderStreamedPng(const Model& model, int steps, const DerivationOptions& options,
                       const RenderOptions& render, const std::filesystem::path& path) {
    const LSystem& ls = model.lsystem;
    if (SubtreeSummaries sums(model, steps, options.memoryLimit);
        sums.available() && sums.segments() > kSummariseAbove) {
        renderSummarisedPng(model, sums, render, path);
        return;
    }
    StreamedMeasure m = measureStreamed(model, steps, options, true);
    StreamedPng png(render, m.bounds, m.ink, m.segments > 0, m.baseWidth, Scene::defaultPalette(),
                    path);
    PictureSink sink(png);
    TurtleStream<PictureSink> stream(model, sink, nullptr);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    png.finish();
}

}  // namespace graftal
