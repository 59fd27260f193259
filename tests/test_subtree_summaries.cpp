// Subtree summaries: the net motion and extent of what a module derives, and the pictures
// of strings far larger than their pixels that they make possible.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>

#include "graftal/output/streamed_picture.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"
#include "graftal/turtle/subtree_summaries.hpp"
#include "graftal/turtle/turtle.hpp"
#include "output/summarised_png.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseModel;

namespace {

const char* kKoch =
    "Lsystem: 1\nangle factor: 4\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n";
const char* kBush =
    "Lsystem: 1\nangle increment: 20\naxiom: XG\nX --> F[+X]F[-X]+X\nF --> FF\nendlsystem\n";

// Green channel of a PNG, row by row.
std::vector<int> greens(const std::filesystem::path& png, int& width, int& height) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
    width = cairo_image_surface_get_width(s);
    height = cairo_image_surface_get_height(s);
    int stride = cairo_image_surface_get_stride(s);
    const unsigned char* p = cairo_image_surface_get_data(s);
    std::vector<int> g;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) g.push_back(p[y * stride + x * 4 + 1]);
    cairo_surface_destroy(s);
    return g;
}

}  // namespace

TEST(SubtreeSummaries, KochCurveSideMovesFourToTheStepStraightOn) {
    Model ls = parseModel(kKoch);
    SubtreeSummaries sums(ls, 5);
    ASSERT_TRUE(sums.available());
    const SubtreeMotion& side = sums.motion('F', 0);
    EXPECT_EQ(side.segments, 32768);  // 8^5
    EXPECT_NEAR(side.length, 32768, 1e-9);
    EXPECT_NEAR(side.along, 1024, 1e-9);  // 4^5
    EXPECT_NEAR(side.aside, 0, 1e-9);
    EXPECT_NEAR(side.cos, 1, 1e-12);
    EXPECT_NEAR(side.sin, 0, 1e-12);
    const SubtreeMotion& last = sums.motion('F', 5);
    EXPECT_EQ(last.segments, 1);
    EXPECT_EQ(last.along, 1);
    const SubtreeMotion& plus = sums.motion('+', 0);  // + turns left: heading toward L
    EXPECT_NEAR(plus.cos, 0, 1e-12);
    EXPECT_NEAR(plus.sin, 1, 1e-12);
    EXPECT_EQ(sums.segments(), 4 * 32768);
}

TEST(SubtreeSummaries, MotionAndRadiusAgreeWithTheTurtle) {
    Model ls = parseModel(kBush);
    const int n = 6;
    SubtreeSummaries sums(ls, n);
    ASSERT_TRUE(sums.available());
    Scene scene = interpret(ls, derive(ls, n));
    ASSERT_FALSE(scene.segments.empty());
    // The G after X starts where X's subtree ends: start + along H + aside L, with the
    // turtle starting at the origin, H = (0, 1), L = (-1, 0).
    const SubtreeMotion& x = sums.motion('X', 0);
    const Segment& g = scene.segments.back();
    EXPECT_NEAR(g.a.x, -x.aside, 1e-9);
    EXPECT_NEAR(g.a.y, x.along, 1e-9);
    // ... heading turned by (cos, sin): the G points along cos H + sin L.
    EXPECT_NEAR(g.b.x - g.a.x, -x.sin, 1e-9);
    EXPECT_NEAR(g.b.y - g.a.y, x.cos, 1e-9);
    // Every point of X's subtree lies within the radius, and the radius is not loose.
    double farthest = 0;
    for (std::size_t i = 0; i + 1 < scene.segments.size(); ++i)
        for (const Vec3& p : {scene.segments[i].a, scene.segments[i].b})
            farthest = std::max(farthest, std::hypot(p.x, p.y));
    EXPECT_LE(farthest, x.radius + 1e-9);
    EXPECT_GE(farthest, 0.5 * x.radius);
    EXPECT_EQ(x.segments, static_cast<double>(scene.segments.size() - 1));
}

TEST(SubtreeSummaries, UnavailableWhereAModuleDoesMoreThanMove) {
    EXPECT_FALSE(SubtreeSummaries(parseModel("Lsystem: 1\naxiom: A(1)\nA(l) --> F(l)A(l*2)\n"
                                             "endlsystem\n"),
                                  4)
                     .available());
    EXPECT_FALSE(SubtreeSummaries(parseModel("Lsystem: 1\naxiom: F\nF --> FF : 0.5\nF --> F : 0.5\n"
                                             "endlsystem\n"),
                                  4)
                     .available());
    EXPECT_FALSE(
        SubtreeSummaries(parseModel("Lsystem: 1\naxiom: A\nA --> {F+F+F}A\nendlsystem\n"), 4)
            .available());
    // Modules that change the colour are kept out of summaries, not the whole system.
    Model coloured = parseModel("Lsystem: 1\naxiom: A;B\nA --> FA\nB --> F;B\nendlsystem\n");
    SubtreeSummaries sums(coloured, 3);
    ASSERT_TRUE(sums.available());
    EXPECT_TRUE(sums.motion('A', 0).summarised);
    EXPECT_FALSE(sums.motion('B', 0).summarised);
    // Tables are fine: the summary of a module depends on the step it is in.
    Model tables = parseModel(
        "Lsystem: 1\naxiom: A\ntable: v\nA --> F[+A]A\ntable: f\nA --> FF\n"
        "table schedule: v 2, f\nendlsystem\n");
    SubtreeSummaries t(tables, 3);
    ASSERT_TRUE(t.available());
    EXPECT_EQ(t.segments(), interpret(tables, derive(tables, 3)).segments.size());
}

TEST(SubtreeSummaries, SummarisedPictureMatchesTheStrokeByStrokeOne) {
    graftal::testing::TempDir t;
    for (const char* text : {kKoch, kBush}) {
        Model ls = parseModel(text);
        const int n = 5;
        RenderOptions o;
        o.width = 200;
        o.height = 160;
        SubtreeSummaries sums(ls, n);
        ASSERT_TRUE(sums.available());

        StreamedMeasure exact = measureStreamed(ls, n);
        StreamedMeasure quick = measureSummarised(ls, sums, std::max(o.width, o.height));
        EXPECT_EQ(quick.segments, exact.segments);
        EXPECT_NEAR(quick.ink, exact.ink, 1e-9 * exact.ink);
        double pixel = std::max(exact.bounds.max.x - exact.bounds.min.x,
                                exact.bounds.max.y - exact.bounds.min.y) /
                       160;
        EXPECT_NEAR(quick.bounds.min.x, exact.bounds.min.x, 0.02 * pixel);
        EXPECT_NEAR(quick.bounds.max.x, exact.bounds.max.x, 0.02 * pixel);
        EXPECT_NEAR(quick.bounds.min.y, exact.bounds.min.y, 0.02 * pixel);
        EXPECT_NEAR(quick.bounds.max.y, exact.bounds.max.y, 0.02 * pixel);

        auto a = t.path() / "exact.png", b = t.path() / "summarised.png";
        renderStreamedPng(ls, n, {}, o, Destination::file(a));  // few segments: stroke by stroke
        renderSummarisedPng(ls, sums, o, Destination::file(b));
        int w = 0, h = 0, w2 = 0, h2 = 0;
        std::vector<int> ga = greens(a, w, h), gb = greens(b, w2, h2);
        ASSERT_EQ(w2, 200);
        ASSERT_EQ(h2, 160);
        double inkA = 0, inkB = 0, diff = 0;
        for (std::size_t i = 0; i < ga.size(); ++i) {
            inkA += 255 - ga[i];
            inkB += 255 - gb[i];
            diff += std::abs(ga[i] - gb[i]);
        }
        EXPECT_GT(inkA, 255 * 200.0) << text;
        EXPECT_NEAR(inkB, inkA, 0.15 * inkA) << text;
        EXPECT_LT(diff, 0.3 * inkA) << text;
    }
}

TEST(SubtreeSummaries, StreamedRenderOfBillionsOfSegments) {
    using graftal::testing::runGraftal;
    graftal::testing::TempDir t;
    auto f = t.write("koch.l", kKoch);
    auto png = t.path() / "koch10.png";
    // n = 10: 4.3·10^9 segments, far past any string; drawn from about 10^5 strokes.
    auto r = runGraftal("render " + f.string() + " -n 10 --stream --size 160x160 -o " +
                        png.string() + " -q");
    ASSERT_EQ(r.status, 0) << r.err;
    int w = 0, h = 0;
    std::vector<int> g = greens(png, w, h);
    ASSERT_EQ(w, 160);
    int dark = 0;
    for (int v : g) dark += v < 200;
    EXPECT_GT(dark, 1000) << "the island's outline is drawn";
}

namespace {

// Counts what a summarised drawing hands over, drawing nothing.
class CountingDrawing : public StreamedDrawing {
  public:
    std::uint64_t segments = 0;
    void segment(const Segment&) override { ++segments; }
    void polygon(std::span<const Vec3>, std::uint16_t) override {}
};

}  // namespace

TEST(SubtreeSummaries, BacktrackingKochCurveDrawsAtMostFourStrokesPerPixel) {
    // ABOP Fig. 1.9e: each side turns back on itself (F-FF--F-F), so the path covers the
    // picture many times over; its strokes are bounded by the pixels, whatever n.
    Model ls = loadExample(GRAFTAL_EXAMPLES_DIR "/fig2.5e-koch-curve.l");
    RenderOptions o;
    const double budget = 4.0 * o.width * o.height;
    for (int n : {10, 14}) {
        SubtreeSummaries sums(ls, n);
        ASSERT_TRUE(sums.available());
        StreamedMeasure m = measureSummarised(ls, sums, std::max(o.width, o.height));
        if (n == 10) {
            EXPECT_EQ(m.segments, 4u * 9765625u);  // 4·5^10
        }
        const ImageTransform transform = ImageTransform::fit(m.bounds, o);
        EXPECT_GT(summarisedStrokeCount(sums, transform.scale, 0.25), budget) << n;
        double dot = dotRadiusWithin(sums, transform.scale, 0.25, budget, 4.0);
        EXPECT_LT(dot, 4.0) << n;
        CountingDrawing counting;
        drawSummarised(ls, sums, transform.scale, dot, counting);
        EXPECT_EQ(static_cast<double>(counting.segments),
                  summarisedStrokeCount(sums, transform.scale, dot));
        EXPECT_LE(static_cast<double>(counting.segments), budget) << n;
        EXPECT_GT(static_cast<double>(counting.segments), 0.1 * budget) << n;
    }
}
