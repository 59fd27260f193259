// The studio's line buffer made straight from the turtle's polylines is the one made from
// the Scene, byte for byte: joined paths, branches (jumps), moves, widths, colours,
// polygons, 3D and generalized cylinders.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "graftal/geometry/bspline.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/studio/line_buffer.hpp"
#include "graftal/studio/studio_model.hpp"
#include "graftal/turtle/polyline_scene.hpp"
#include "graftal/turtle/turtle.hpp"

namespace fs = std::filesystem;
using namespace graftal;

namespace {

std::uint32_t word(const std::string& bytes, std::size_t k) {
    std::uint32_t w = 0;
    std::memcpy(&w, bytes.data() + 4 * k, 4);
    return w;
}

void expectSameLines(const Model& model, const std::string& what) {
    const ModuleString modules = deriveWithQueries(model);
    const Scene scene = interpret(model, modules);
    PolylineScene lines;
    interpretPolylines(model, modules, lines);
    EXPECT_EQ(lines.segments, scene.segments.size()) << what;
    EXPECT_EQ(lines.rest.polygonCount(), scene.polygonCount()) << what;
    EXPECT_EQ(lines.rest.is3D, scene.is3D) << what;
    const std::string fromScene = studio::encodeLines(scene);
    const std::string fromPolylines = studio::encodeLines(lines);
    ASSERT_GE(fromScene.size(), 64u) << what;
    EXPECT_EQ(word(fromScene, 1), scene.segments.size()) << what;
    EXPECT_TRUE(fromPolylines == fromScene)
        << what << ": " << fromPolylines.size() << " bytes against " << fromScene.size();
}

TEST(StudioLines, PolylinesEncodeAsTheSceneDoesForExamples) {
    for (const char* name :
         {"fig2.6-dragon-curve-lr.l", "fig2.4-islands-and-lakes.l", "fig3.2a-bracketed-plant.l",
          "fig2.9-filled-polygon-fractal.l", "fig3.8-fern-3d.l", "fig4.5-cordate-leaf.l",
          "honda-monopodial-tree.l", "fig3.10-capsella-3d.l", "cpfg-generalized-cylinder.l"}) {
        const fs::path file = fs::path(GRAFTAL_EXAMPLES_DIR) / name;
        ParseOptions options;
        if (fs::path view = fs::path(file).replace_extension(".v"); fs::exists(view))
            options.viewFile = view.string();
        ParseResult parsed = loadModel(file, options);
        ASSERT_TRUE(parsed.ok()) << name;
        expectSameLines(parsed.model, name);
    }
}

// Colours and widths change along a path, a move leaves a gap, a step of zero length and
// a jump back onto the last point keep the path joined.
TEST(StudioLines, PolylinesEncodeColoursWidthsAndJumpsAsTheSceneDoes) {
    const char* text = R"(Lsystem: 1
derivation length: 4
angle factor: 6
axiom: F;F!F#F
F --> F[+F;F]f[-!F]F(0)F
endlsystem
)";
    ParseResult parsed = parse(text, ParseOptions{});
    ASSERT_TRUE(parsed.ok());
    expectSameLines(parsed.model, "inline model");

    PolylineScene lines;
    interpretPolylines(parsed.model, deriveWithQueries(parsed.model), lines);
    std::size_t jumps = 0, colours = 0;
    for (const PolylineScene::Run& r : lines.runs) {
        jumps += r.jump;
        colours += !r.jump && r.color != 0;
    }
    EXPECT_GT(jumps, 10u);
    EXPECT_GT(colours, 10u);
    // Reused: a second walk into the same buffers gives the same lines.
    const std::string first = studio::encodeLines(lines);
    interpretPolylines(parsed.model, deriveWithQueries(parsed.model), lines);
    EXPECT_TRUE(studio::encodeLines(lines) == first);
}

// The studio's picture: the lines of the interpreted scene, smoothed when the model asks
// for B-splines (which keep the Scene's path), and its 3D scene made again from the kept
// string; a homomorphism applied before the turtle.
TEST(StudioLines, ThePictureSendsTheLinesOfItsScene) {
    for (const char* name :
         {"fig2.11b-bspline.l", "fig2.11a-straight-lines.l", "fig3.8-fern-3d.l"}) {
        const fs::path file = fs::path(GRAFTAL_EXAMPLES_DIR) / name;
        studio::ModelInput input;
        input.file = file;
        std::ifstream in(file);
        input.text.assign(std::istreambuf_iterator<char>(in), {});
        const studio::StudioPicture picture = studio::derivePicture(
            input, studio::StudioLimits{}, CancellationToken{}, fs::temp_directory_path());
        ParseResult parsed = loadModel(file);
        ASSERT_TRUE(parsed.ok()) << name;
        ModuleString modules = deriveWithQueries(parsed.model);
        if (!parsed.model.lsystem.homomorphism.empty())  // the fern draws through one
            modules = applyHomomorphism(parsed.model.lsystem, modules);
        Scene scene = interpret(parsed.model, modules);
        if (int n = parsed.model.view.kolam.splineSubdivisions; n > 0)
            scene = smoothSegments(scene, n);
        EXPECT_EQ(picture.segments, scene.segments.size()) << name;
        EXPECT_EQ(picture.stats["segments"], scene.segments.size()) << name;
        EXPECT_TRUE(picture.lines == studio::encodeLines(scene)) << name;
        EXPECT_EQ(studio::pictureScene(picture).segments.size(), scene.segments.size()) << name;
    }
}

}  // namespace
