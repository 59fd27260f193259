// The turtle fed by a streamed derivation: geometry for strings too large to hold.
#include "graftal/streamed_interpretation.hpp"

#include "graftal/streaming.hpp"
#include "planar_measure.hpp"
#include "streamed_sinks.hpp"
#include "turtle_machine.hpp"

namespace graftal {

namespace {

// Adapts the turtle to the module stream.
template <class Sink>
class TurtleStream : public ModuleSink {
  public:
    TurtleStream(const LSystem& ls, Sink& sink, StreamedMeasure* measure)
        : machine_(ls, sink), measure_(measure) {}
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

StreamedMeasure measureStreamed(const LSystem& ls, int steps, const DerivationOptions& options,
                                bool geometry) {
    StreamedMeasure m;
    m.symbolCounts.assign(ls.symbols.size(), 0);
    if (!geometry) {
        CountingSink counter(m);
        streamDerivation(ls, steps, counter, options);
        return m;
    }
    MeasureSink sink(m);
    TurtleStream<MeasureSink> stream(ls, sink, &m);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    return m;
}

StreamedMeasure measureModules(const LSystem& ls, const ModuleString& modules) {
    // A flat L-system (most 2D figures) takes the planar walk, several times faster.
    if (turtle::staysPlanar(ls))
        if (std::optional<StreamedMeasure> m = turtle::measurePlanar(ls, modules))
            return std::move(*m);
    return turtle::measureGeneric(ls, modules);
}

StreamedMeasure turtle::measureGeneric(const LSystem& ls, const ModuleString& modules) {
    StreamedMeasure m;
    m.symbolCounts.assign(ls.symbols.size(), 0);
    for (Symbol s : modules.symbols()) ++m.symbolCounts[s];
    m.modules = modules.size();
    MeasureSink sink(m);
    turtle::TurtleMachine<MeasureSink> machine(ls, sink);
    machine.run(modules);
    return m;
}

Scene interpretStreamed(const LSystem& ls, int steps, const DerivationOptions& options) {
    Scene scene;
    turtle::SceneSink sink(scene);
    TurtleStream<turtle::SceneSink> stream(ls, sink, nullptr);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    return scene;
}

void drawStreamed(const LSystem& ls, int steps, const DerivationOptions& options,
                  StreamedDrawing& drawing) {
    DrawingSink sink(drawing);
    TurtleStream<DrawingSink> stream(ls, sink, nullptr);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
}

}  // namespace graftal
