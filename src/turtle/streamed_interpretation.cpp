// The turtle fed by a streamed derivation: geometry for strings too large to hold.
#include "graftal/turtle/streamed_interpretation.hpp"

#include "graftal/rewrite/streaming.hpp"
#include "planar_measure.hpp"
#include "streamed_sinks.hpp"
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
    turtle::TurtleMachine<Sink>& machine() { return machine_; }

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
                                bool geometry, bool viewVolume) {
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
    if (viewVolume) stream.machine().trackViewVolume();
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    if (viewVolume) m.bounds = stream.machine().viewVolume();
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

Bounds cpfgViewVolume(const Model& model, const ModuleString& modules) {
    turtle::NullSink sink;
    turtle::TurtleMachine<turtle::NullSink> machine(model, sink);
    machine.trackViewVolume();
    machine.run(modules);
    return machine.viewVolume();
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

void drawStreamed(const Model& model, int steps, const DerivationOptions& options,
                  StreamedDrawing& drawing) {
    DrawingSink sink(drawing);
    TurtleStream<DrawingSink> stream(model, sink, nullptr);
    streamDerivation(model.lsystem, steps, stream, options);
    stream.finish();
}

}  // namespace graftal
