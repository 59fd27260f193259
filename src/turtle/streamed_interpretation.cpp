// The turtle fed by a streamed derivation: geometry for strings too large to hold.
#include "graftal/streaming.hpp"
#include "planar_length.hpp"
#include "planar_measure.hpp"
#include "subtree_summaries.hpp"
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

class MeasureSink {
  public:
    explicit MeasureSink(StreamedMeasure& m) : m_(m) {}
    std::uint32_t segment(const Segment& s) {
        // A segment that goes on from the last one starts at a point already in the box:
        // extending by it again would change nothing (a bound moves only on a strict <).
        if (!(s.a == lastEnd_)) extend(s.a);
        extend(s.b);
        lastEnd_ = s.b;
        m_.ink += turtle::inkTerm(length_(s.b.x - s.a.x, s.b.y - s.a.y),
                                  turtle::inkWeight(s.width, m_.baseWidth));
        return static_cast<std::uint32_t>(m_.segments++);
    }
    void polygon(std::span<const Vec3> v, std::uint16_t) {
        for (const auto& p : v) extend(p);
        ++m_.polygons;
    }
    void surface(const std::string&, const SurfaceInstance&) {}
    void baseWidth(float w) { m_.baseWidth = w; }
    void finish(bool is3D) { m_.is3D = is3D; }

  private:
    // Bounds::extend(), inline: it runs for every segment.
    void extend(const Vec3& p) {
        Bounds& b = m_.bounds;
        b.min = {std::min(b.min.x, p.x), std::min(b.min.y, p.y), std::min(b.min.z, p.z)};
        b.max = {std::max(b.max.x, p.x), std::max(b.max.y, p.y), std::max(b.max.z, p.z)};
    }

    StreamedMeasure& m_;
    Vec3 lastEnd_{kNaN, kNaN, kNaN};  // equal to no point
    turtle::PlanarLength length_;
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
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

class PictureSink {
  public:
    explicit PictureSink(StreamedPng& png) : png_(png) {}
    std::uint32_t segment(const Segment& s) {
        png_.segment(s);
        return kNoSegment;
    }
    void polygon(std::span<const Vec3> v, std::uint16_t c) { png_.polygon(v, c); }
    void surface(const std::string&, const SurfaceInstance&) {}
    void baseWidth(float) {}
    void finish(bool) {}

  private:
    StreamedPng& png_;
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

namespace {
// Past this many segments a picture has far more strokes than pixels; subtrees smaller
// than a pixel are then drawn as one stroke each (subtree_summaries.hpp). Below it the
// picture is stroke for stroke the one the materialised path draws.
constexpr double kSummariseAbove = 2e7;
}  // namespace

bool streamedPictureIsSummarised(const LSystem& ls, int steps) {
    SubtreeSummaries sums(ls, steps);
    return sums.available() && sums.segments() > kSummariseAbove;
}

void renderStreamedPng(const LSystem& ls, int steps, const DerivationOptions& options,
                       const RenderOptions& render, const std::filesystem::path& path) {
    if (SubtreeSummaries sums(ls, steps); sums.available() && sums.segments() > kSummariseAbove) {
        renderSummarisedPng(ls, sums, render, path);
        return;
    }
    StreamedMeasure m = measureStreamed(ls, steps, options, true);
    StreamedPng png(render, m.bounds, m.ink, m.segments > 0, m.baseWidth, Scene::defaultPalette(),
                    path);
    PictureSink sink(png);
    TurtleStream<PictureSink> stream(ls, sink, nullptr);
    streamDerivation(ls, steps, stream, options);
    stream.finish();
    png.finish();
}

}  // namespace graftal
