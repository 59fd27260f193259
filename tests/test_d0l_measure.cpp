// The D0L measuring walk (d0l_measure.hpp) against the turtle on the derived string: every
// count and every bit of both boxes must be the same, since `graftal stats` prints them.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "graftal/pipeline/statistics.hpp"
#include "graftal/turtle/d0l_measure.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parseModel;
namespace fs = std::filesystem;

namespace {

// The bits of a double: EXPECT_EQ on doubles would take 0 and -0 for the same.
std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

void expectSameBox(const Bounds& fast, const Bounds& plain, const std::string& what) {
    ASSERT_EQ(fast.empty(), plain.empty()) << what;
    if (plain.empty()) return;
    for (auto axis : {&Vec3::x, &Vec3::y, &Vec3::z}) {
        EXPECT_EQ(bits(fast.min.*axis), bits(plain.min.*axis))
            << what << ": min " << fast.min.*axis << " vs " << plain.min.*axis;
        EXPECT_EQ(bits(fast.max.*axis), bits(plain.max.*axis))
            << what << ": max " << fast.max.*axis << " vs " << plain.max.*axis;
    }
}

// Measures `model` at `steps` both ways; false when the walk does not apply.
bool expectSameMeasures(const Model& model, int steps, const std::string& name) {
    const std::string what = name + " n=" + std::to_string(steps);
    std::optional<StreamedMeasure> drawing = measureD0L(model, steps, MeasuredBox::Drawing);
    std::optional<StreamedMeasure> volume = measureD0L(model, steps, MeasuredBox::CpfgViewVolume);
    EXPECT_EQ(drawing.has_value(), volume.has_value()) << what;
    if (!drawing || !volume) return false;
    const ModuleString modules = derive(model, steps);
    const StreamedMeasure plain = measureModules(model, modules);
    for (const StreamedMeasure* fast : {&*drawing, &*volume}) {
        EXPECT_EQ(fast->modules, plain.modules) << what;
        EXPECT_EQ(fast->symbolCounts, plain.symbolCounts) << what;
        EXPECT_EQ(fast->segments, plain.segments) << what;
        EXPECT_EQ(fast->polygons, plain.polygons) << what;
    }
    expectSameBox(drawing->bounds, plain.bounds, what + " (drawing)");
    expectSameBox(volume->bounds, cpfgViewVolume(model, modules), what + " (view volume)");
    return true;
}

// A D0L example of the book, measured at every n from 0 up to `largest`.
void expectSameExample(const std::string& file, int largest) {
    const Model model = loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / file);
    for (int n = 0; n <= largest; ++n)
        EXPECT_TRUE(expectSameMeasures(model, n, file)) << file << " n=" << n << " not measured";
}

}  // namespace

TEST(D0LMeasure, QuadraticKochIslandAsThePlainTurtle) {
    // From n = 4 on the turtle turns more than 4096 times: the frame is orthonormalised on
    // the way, within replayed subtrees too.
    expectSameExample("fig2.2-quadratic-koch-island.l", 6);
    expectSameExample("fig2.3b-quadratic-snowflake.l", 4);
}

TEST(D0LMeasure, BracketedPlantsOfAbopFigure124AsThePlainTurtle) {
    // 1.24a-c turn by 25.7 and 22.5 degrees: no table of turns would be exact.
    expectSameExample("fig3.2a-bracketed-plant.l", 5);
    expectSameExample("fig3.2b-bracketed-plant.l", 5);
    expectSameExample("fig3.2c-bracketed-plant.l", 4);
    expectSameExample("fig3.2d-bracketed-plant.l", 9);
    expectSameExample("fig3.2e-bracketed-plant.l", 7);
    expectSameExample("fig3.2f-bracketed-plant.l", 5);
}

TEST(D0LMeasure, DragonHilbertAndGosperCurvesAsThePlainTurtle) {
    expectSameExample("fig2.6-dragon-curve-lr.l", 12);
    expectSameExample("fig2.7b-hilbert.l", 5);
    expectSameExample("fig2.8b-hexagonal-gosper.l", 4);
    expectSameExample("fig2.4-islands-and-lakes.l", 2);  // f moves without drawing
}

TEST(D0LMeasure, OddAngleMovesTurnAroundAndWidthsAsThePlainTurtle) {
    // 7.3 degrees does not divide 360; | and f, g, G, ! and a colour; an initial heading.
    const Model model = parseModel(
        "Lsystem: 1\nangle increment: 7.3\ninitial heading: 13\naxiom: X\n"
        "X --> G[+X]f[-X|gX]!;-X\nG --> GG\nendlsystem\n");
    for (int n = 0; n <= 6; ++n) EXPECT_TRUE(expectSameMeasures(model, n, "odd angle"));
}

TEST(D0LMeasure, EveryFlatD0LExampleAsThePlainTurtle) {
    int measured = 0;
    for (const auto& entry : fs::directory_iterator(GRAFTAL_EXAMPLES_DIR)) {
        if (entry.path().extension() != ".l") continue;
        Model model;
        try {
            model = loadExample(entry.path());
        } catch (const Error&) {
            continue;  // an example that needs files beside it
        }
        const std::string name = entry.path().filename().string();
        const int steps = std::min(model.lsystem.derivationLength, 4);
        if (!measureD0L(model, 0, MeasuredBox::Drawing)) continue;
        for (int n = 0; n <= steps; ++n) {
            if (derive(model, n).size() > 2'000'000) break;
            expectSameMeasures(model, n, name);
        }
        ++measured;
    }
    EXPECT_GE(measured, 20);
}

TEST(D0LMeasure, DeclinesWhatItCannotFollow) {
    const char* declined[] = {
        // parameters, a condition, context, a polygon, a pitch, a stochastic choice
        "Lsystem: 1\naxiom: F(1)\nF(x) --> F(x*2)+F(x)\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nA : 1 > 0 --> F+A\nendlsystem\n",
        "Lsystem: 1\naxiom: FAF\nF < A --> F+A\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nA --> {F+F+F}A\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nA --> F&A\nendlsystem\n",
        "Lsystem: 1\naxiom: A\nA --> F+A : 0.5\nA --> F-A : 0.5\nendlsystem\n",
    };
    for (const char* text : declined)
        EXPECT_FALSE(measureD0L(parseModel(text), 3, MeasuredBox::Drawing)) << text;
}

TEST(D0LMeasure, DeepBranchesAsThePlainTurtle) {
    // Branches within branches, 12 deep: subtrees replayed inside open brackets.
    const Model model = parseModel(
        "Lsystem: 1\nangle increment: 30\naxiom: A\nA --> F[+A][-A]FA\nF --> F\nendlsystem\n");
    for (int n = 0; n <= 9; ++n) EXPECT_TRUE(expectSameMeasures(model, n, "deep branches"));
}

TEST(D0LMeasure, StatsOfAD0LSystemAreThePlainTurtles) {
    // stats gives a cpfg file's view volume: for the kolam, which only moves (f), it is not
    // the drawing's box (which is empty); a pfg data file gets the drawing's box.
    for (const char* file : {"fig3.2d-bracketed-plant.l", "fig6.2-snake-kolam.l",
                             "fig2.4-islands-and-lakes.l", "appendixA-pfg-example.l"}) {
        const Model model = loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / file);
        DeriveRequest request;
        request.steps = 3;
        const ModelStatistics stats = measured(model, request, true);
        const ModuleString modules = derive(model, 3);
        const StreamedMeasure plain = measureModules(model, modules);
        EXPECT_EQ(stats.modules, modules.size()) << file;
        EXPECT_EQ(stats.segments, plain.segments) << file;
        expectSameBox(stats.bounds,
                      model.lsystem.legacyPfg ? plain.bounds : cpfgViewVolume(model, modules),
                      file);
    }
}

TEST(D0LMeasure, StopsWhenCancelled) {
    const Model model =
        loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig2.2-quadratic-koch-island.l");
    CancellationToken cancel;
    cancel.cancel();
    EXPECT_THROW(measureD0L(model, 6, MeasuredBox::Drawing, cancel), Cancelled);
}
