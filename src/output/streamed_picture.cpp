// The streamed PNG: the turtle walks a streamed derivation (or its subtree summaries)
// twice, once to measure the picture and once to draw it into a StreamedPng.
#include "graftal/output/streamed_picture.hpp"

#include <algorithm>

#include "graftal/turtle/streamed_interpretation.hpp"
#include "streamed_png.hpp"
#include "summarised_png.hpp"

namespace graftal {

namespace {

// Strokes a summarised picture draws per pixel of its image at most, unless that would take
// subtrees wider than kLargestDotRadius pixels drawn as one stroke.
constexpr double kStrokesPerPixel = 4;
// Past this many segments a picture has far more strokes than pixels; subtrees smaller
// than a pixel are then drawn as one stroke each (subtree_summaries.hpp). Below it the
// picture is stroke for stroke the one the materialised path draws. The bound follows the
// image (a Koch curve of 8 million segments in 800x800 pixels would otherwise be derived,
// held and stroked segment by segment), and never exceeds kSummariseAbove.
constexpr double kSummariseAbove = 2e7;
double summariseAbove(const RenderOptions& picture) {
    return std::min(kSummariseAbove, kStrokesPerPixel * picture.width * picture.height);
}
constexpr double kLargestDotRadius = 4;

// What the turtle draws goes straight into the picture.
class PngDrawing : public StreamedDrawing {
  public:
    explicit PngDrawing(StreamedPng& png) : png_(png) {}
    void segment(const Segment& s) override { png_.segment(s); }
    void polygon(std::span<const Vec3> v, std::uint16_t c) override { png_.polygon(v, c); }

  private:
    StreamedPng& png_;
};

}  // namespace

// StreamedPng draws through the Cairo picture of streamed_png.cpp (openStreamedPng).
StreamedPng::StreamedPng(const RenderOptions& o, const Bounds& bounds, double ink, bool anySegments,
                         float baseWidth, std::vector<Rgb> palette, std::filesystem::path path)
    : StreamedPng(o, bounds, ink, anySegments, baseWidth, std::move(palette),
                  Destination::file(std::move(path))) {}

StreamedPng::StreamedPng(const RenderOptions& o, const Bounds& bounds, double ink, bool anySegments,
                         float baseWidth, std::vector<Rgb> palette, Destination destination)
    : impl_(openStreamedPng(o, bounds, ink, anySegments, baseWidth, std::move(palette),
                            std::move(destination))) {}

StreamedPng::~StreamedPng() = default;

void StreamedPng::segment(const Segment& s) {
    impl_->segment(s);
}

void StreamedPng::polygon(std::span<const Vec3> vertices, std::uint16_t color) {
    impl_->polygon(vertices, color);
}

void StreamedPng::finish() {
    impl_->finish();
}

bool streamedPictureIsSummarised(const Model& model, int steps, std::size_t memoryLimit,
                                 const RenderOptions& picture) {
    SubtreeSummaries sums(model, steps, memoryLimit);
    return sums.available() && sums.segments() > summariseAbove(picture);
}

void renderStreamedPng(const Model& model, int steps, const DerivationOptions& options,
                       const RenderOptions& render, const Destination& destination) {
    if (SubtreeSummaries sums(model, steps, options.memoryLimit);
        sums.available() && sums.segments() > summariseAbove(render)) {
        renderSummarisedPng(model, sums, render, destination);
        return;
    }
    StreamedMeasure m = measureStreamed(model, steps, options, true);
    StreamedPng png(render, m.bounds, m.ink, m.segments > 0, m.baseWidth, Scene::defaultPalette(),
                    destination);
    PngDrawing drawing(png);
    drawStreamed(model, steps, options, drawing);
    png.finish();
}

void renderSummarisedPng(const Model& model, const SubtreeSummaries& sums,
                         const RenderOptions& render, const Destination& destination,
                         double dotRadius, double pixelTolerance) {
    StreamedMeasure measure =
        measureSummarised(model, sums, std::max(render.width, render.height), pixelTolerance);
    StreamedPng png(render, measure.bounds, measure.ink, measure.segments > 0, measure.baseWidth,
                    Scene::defaultPalette(), destination);
    const ImageTransform transform = ImageTransform::fit(measure.bounds, render);
    // A path that covers its picture many times over (a Koch curve that turns back on
    // itself) would still give many strokes per pixel, each costing as much as any and only
    // darkening pixels already drawn: draw wider subtrees as one stroke instead.
    dotRadius = dotRadiusWithin(sums, transform.scale, dotRadius,
                                kStrokesPerPixel * render.width * render.height, kLargestDotRadius);
    PngDrawing drawing(png);
    drawSummarised(model, sums, transform.scale, dotRadius, drawing);
    png.finish();
}

}  // namespace graftal
