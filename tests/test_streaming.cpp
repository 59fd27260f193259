// Streamed derivations give the materialised string, geometry and picture.
#include <gtest/gtest.h>

#include <cairo.h>

#include "graftal/output/streamed_picture.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseModel;

namespace {

using Collect = graftal::testing::ModuleCollector;

const char* kClasses[] = {
    "Lsystem: 1\nangle factor: 4\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n",
    "Lsystem: 1\nangle increment: 20\naxiom: X\nX --> F[+X]F[-X]+X\nF --> FF\nendlsystem\n",
    "Lsystem: 1\nseed: 9\nangle increment: 25\naxiom: F\nF --> F[+F]F[-F]F : 0.33\n"
    "F --> F[+F]F : 0.33\nF --> F[-F]F : 0.34\nendlsystem\n",
    "Lsystem: 1\naxiom: A(1,0)\nA(l,a) : l < 40 --> "
    "F(l)[+(a+30)A(l*0.7,a+5)]-(10)A(l*0.9,ran(20))\n"
    "endlsystem\n",
    "Lsystem: 1\naxiom: A\ntable: v\nA --> I[L]A\ntable: f\nA --> I[IF]A\nI --> FI\n"
    "table schedule: v 3, f\nendlsystem\n",
};

}  // namespace

TEST(Streaming, SameStringAsTheMaterialisedDerivation) {
    for (const char* text : kClasses) {
        Model ls = parseModel(text);
        for (int n : {0, 1, 4, 6}) {
            Collect c;
            streamDerivation(ls.lsystem, n, c);
            EXPECT_TRUE(c.s == derive(ls, n, {})) << text << " n=" << n;
        }
    }
}

TEST(Streaming, SameGeometryAsTheMaterialisedDerivation) {
    for (const char* text : kClasses) {
        Model ls = parseModel(text);
        Scene a = interpret(ls, derive(ls, 6));
        Scene b = interpretStreamed(ls, 6);
        ASSERT_EQ(a.segments.size(), b.segments.size()) << text;
        for (std::size_t i = 0; i < a.segments.size(); ++i) {
            ASSERT_EQ(a.segments[i].a, b.segments[i].a);
            ASSERT_EQ(a.segments[i].b, b.segments[i].b);
            ASSERT_EQ(a.segments[i].previous, b.segments[i].previous);
        }
        StreamedMeasure m = measureStreamed(ls, 6);
        EXPECT_EQ(m.segments, a.segments.size());
        EXPECT_EQ(m.bounds.min, a.bounds().min);
        EXPECT_EQ(m.bounds.max, a.bounds().max);
        EXPECT_EQ(m.modules, derive(ls, 6).size());
    }
}

TEST(Streaming, RefusesLSystemsWithContext) {
    Model ls = parseModel("Lsystem: 1\naxiom: ba\nb < a --> b\nendlsystem\n");
    EXPECT_NE(streamingObstacle(ls.lsystem).find("context"), std::string::npos);
    Collect c;
    EXPECT_THROW(streamDerivation(ls.lsystem, 2, c), Error);
}

TEST(Streaming, StreamedPngEqualsTheMaterialisedPng) {
    graftal::testing::TempDir t;
    Model ls = parseModel(kClasses[0]);
    RenderOptions o;
    o.width = 200;
    o.height = 150;
    auto a = t.path() / "a.png", b = t.path() / "b.png";
    writeImage(interpret(ls, derive(ls, 3)), o, a);
    renderStreamedPng(ls, 3, {}, o, Destination::file(b));
    cairo_surface_t* sa = cairo_image_surface_create_from_png(a.c_str());
    cairo_surface_t* sb = cairo_image_surface_create_from_png(b.c_str());
    ASSERT_EQ(cairo_image_surface_get_width(sb), 200);
    ASSERT_EQ(cairo_image_surface_get_height(sb), 150);
    int stride = cairo_image_surface_get_stride(sa);
    const unsigned char* pa = cairo_image_surface_get_data(sa);
    const unsigned char* pb = cairo_image_surface_get_data(sb);
    int differing = 0, dark = 0;
    for (int y = 0; y < 150; ++y)
        for (int x = 0; x < 200 * 4; ++x) {
            differing += pa[y * stride + x] != pb[y * stride + x];
            dark += x % 4 == 1 && pb[y * stride + x] < 128;
        }
    EXPECT_EQ(differing, 0);
    EXPECT_GT(dark, 100) << "the curve is drawn";
    cairo_surface_destroy(sa);
    cairo_surface_destroy(sb);
}

TEST(Streaming, MemoryLimitRefusesAndStreamSucceeds) {
    using graftal::testing::runGraftal;
    graftal::testing::TempDir t;
    auto f = t.write(
        "big.l", "Lsystem: 1\nangle factor: 4\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\nendlsystem\n");
    // A context-sensitive twin cannot stream: refused before allocating.
    auto g = t.write("ctx.l",
                     "Lsystem: 1\nignore: +-\naxiom: F+F+F+F\nF > F --> F+F-F-FF+F+F-F\n"
                     "endlsystem\n");
    auto r = runGraftal("stats " + g.string() + " -n 7 --memory-limit 8M");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("would make a string of"), std::string::npos) << r.err;
    // Over the limit, the context-free one streams by itself, with a note, and is right.
    r = runGraftal("stats " + f.string() + " -n 7 --memory-limit 8M --no-geometry");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("streaming it instead"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("\"modules\": 15578843"), std::string::npos) << r.out;
    r = runGraftal("stats " + f.string() + " -n 7 --memory-limit 8M --stream -q");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("\"segments\": 8388608"), std::string::npos) << r.out;
}

// Conditions hide the growth from the prediction, so the string is held until it meets
// the limit; the error then names --stream, which derives it in bounded memory (it is not
// taken by itself: without a prediction nothing bounds how long it would run). An L-system
// that cannot stream is not told to.
TEST(Streaming, AnUnpredictedStringOverTheLimitSuggestsTheStream) {
    using graftal::testing::runGraftal;
    graftal::testing::TempDir t;
    auto f = t.write("grow.l",
                     "Lsystem: 1\nderivation length: 22\naxiom: A(1)\n"
                     "A(x) : x < 20 --> A(x+1)[B(x)]A(x+1)\n"
                     "A(x) : x >= 20 --> A(x+1)C(x)\nendlsystem\n");
    for (const std::string command : {"derive", "stats", "stats --no-geometry"}) {
        auto r = runGraftal(command + " " + f.string() + " --memory-limit 8M -q");
        EXPECT_NE(r.status, 0) << command;
        EXPECT_NE(r.err.find("more than the memory limit"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("use --stream"), std::string::npos) << command << ": " << r.err;
    }
    auto r = runGraftal("stats " + f.string() + " --memory-limit 8M --stream --no-geometry -q");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"modules\": 3670013"), std::string::npos) << r.out;
    auto g = t.write("ctx.l",
                     "Lsystem: 1\nderivation length: 22\naxiom: A(1)\n"
                     "B(y) < A(x) : x < 20 --> A(x+1)[B(x)]A(x+1)\n"
                     "A(x) : x < 20 --> A(x+1)[B(x)]A(x+1)\nendlsystem\n");
    r = runGraftal("stats " + g.string() + " --memory-limit 8M --no-geometry -q");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(r.err.find("--stream"), std::string::npos) << r.err;
}

TEST(Streaming, AKochCurveWithManyStrokesPerPixelIsDrawnFromItsSummaries) {
    // fig2.5e at n = 9 has 7.8 million segments: over four per pixel of an 800x800 picture.
    // Held, derived and stroked one by one it took seconds and 700 MB; from its summaries
    // the time follows the image.
    const Model koch =
        loadExample(std::filesystem::path(GRAFTAL_EXAMPLES_DIR) / "fig2.5e-koch-curve.l");
    RenderOptions picture;  // 800x800
    const std::size_t limit = std::size_t(2) << 30;
    EXPECT_TRUE(streamedPictureIsSummarised(koch, 9, limit, picture));
    EXPECT_FALSE(streamedPictureIsSummarised(koch, 7, limit, picture)) << "312,500 segments";
    RenderOptions thumbnail;
    thumbnail.width = thumbnail.height = 100;
    EXPECT_TRUE(streamedPictureIsSummarised(koch, 7, limit, thumbnail)) << "31 per pixel";

    graftal::testing::TempDir t;
    RenderRequest request;
    request.steps = 9;
    request.output = t.path() / "koch.png";
    RenderResult r = render(koch, request);
    EXPECT_EQ(r.route, RenderRoute::StreamedPicture);
    EXPECT_TRUE(r.notes.empty()) << "the string fits; nothing to say";
    EXPECT_EQ(graftal::testing::readFile(request.output).substr(1, 3), "PNG");
    request.steps = 6;
    EXPECT_EQ(render(koch, request).route, RenderRoute::LineArt);
}

namespace {

const char* kWeed =
    "Lsystem: 1\nangle increment: 25.7\naxiom: X\nX --> F[+X][-X]FX\nF --> FF\nendlsystem\n";
const char* kStochasticWeed =
    "Lsystem: 1\nangle increment: 25.7\naxiom: X\nX --> F[+X][-X]FX : 0.5\n"
    "X --> F[-X]FX : 0.5\nF --> FF\nendlsystem\n";

}  // namespace

TEST(Streaming, TheStreamLimitCountsTheModulesARunExpandsOneByOne) {
    using graftal::testing::runGraftal;
    graftal::testing::TempDir t;
    auto weed = t.write("weed.l", kWeed);
    auto stochastic = t.write("stochastic.l", kStochasticWeed);
    const std::string png = (t.path() / "w.png").string();
    // Drawn from subtree summaries, the deterministic weed at n = 40 (10^12 segments)
    // expands a few modules per pixel: under the limit.
    auto r = runGraftal("render " + weed.string() + " -n 40 --size 200x200 -o " + png);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(graftal::testing::readFile(png).substr(1, 3), "PNG");
    // Random choices have no summaries: every module would be expanded, so the same count
    // refuses the stochastic weed at n = 30 ...
    const std::string refusal =
        "a streamed run would expand its modules one by one, more than the stream limit of "
        "100000000000 modules";
    r = runGraftal("render " + stochastic.string() + " -n 30 --size 200x200 -o " +
                   (t.path() / "s.png").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(refusal), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("subtree summaries"), std::string::npos) << r.err;
    // ... and the deterministic one too where it is printed or counted module by module
    // (at n = 24, 10^12 modules: at n = 40, 10^19, only a lower -n is suggested).
    r = runGraftal("stats --no-geometry " + weed.string() + " -n 24");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(refusal), std::string::npos) << r.err;
    // A lower limit refuses what a higher one lets through, by the same count.
    r = runGraftal("stats --no-geometry " + stochastic.string() +
                   " -n 12 --memory-limit 64K --stream-limit 1000");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("stream limit of 1000 modules"), std::string::npos) << r.err;
    r = runGraftal("stats --no-geometry " + stochastic.string() +
                   " -n 12 --memory-limit 64K --stream-limit 100000000");
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST(Streaming, MemoryMessagesSayTheSizeInWordsAndTheRealReason) {
    using graftal::testing::runGraftal;
    graftal::testing::TempDir t;
    // 10^19 modules: no memory holds them, so no larger limit is suggested.
    auto huge = t.write("huge.l", "Lsystem: 1\naxiom: F\nF --> FFFFFFFFFF\nendlsystem\n");
    auto r = runGraftal("render " + huge.string() + " -n 19 -o " + (t.path() / "h.svg").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("would make a string of about 10^19 modules, far more than any memory"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("; lower -n\n"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("EiB"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("--memory-limit"), std::string::npos) << r.err;
    // A coloured Koch island at n = 5: its string (238,000 modules) fits in 1 MiB, its
    // 131,072 segments do not. The note says so.
    auto koch = t.write("koch.l",
                        "Lsystem: 1\nangle factor: 4\naxiom: ;F+F+F+F\nF --> F+F-F-FF+F+F-F\n"
                        "endlsystem\n");
    r = runGraftal("render " + koch.string() + " -n 5 --memory-limit 1M -o " +
                   (t.path() / "k.png").string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("graftal: note: the picture's geometry would need about"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("(131072 segments"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("the string would have"), std::string::npos) << r.err;

    // The library words its advice by the request's fields, not by the command's flags.
    DeriveRequest request;
    request.steps = 19;
    std::vector<Diagnostic> notes;
    try {
        shouldStream(parseModel(graftal::testing::readFile(huge)), 19, request, false, true, false,
                     notes);
        ADD_FAILURE() << "not refused";
    } catch (const Error& e) {
        const std::string text = e.diagnostics().at(0).toString();
        EXPECT_NE(text.find("; lower steps"), std::string::npos) << text;
        EXPECT_EQ(text.find("-n"), std::string::npos) << text;
    }
}
