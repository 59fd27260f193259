// A model's view settings print as .l text (and, for what only a cpfg view file states, as
// a view file) that reads back to the same settings.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "graftal/lang/model.hpp"
#include "graftal/lang/view_settings.hpp"
#include "graftal/maps/map_lsystem.hpp"

namespace fs = std::filesystem;
using namespace graftal;

namespace {

std::string printed(const ViewSettings& v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

std::string messages(const std::vector<Diagnostic>& ds) {
    std::ostringstream os;
    for (const auto& d : ds) os << d << '\n';
    return os.str();
}

// The model printed as .l text and its view-file lines, read again beside `file` (so that
// the files settings name are found where the first reading found them).
ParseResult reparse(const Model& model, const fs::path& file) {
    std::ostringstream lText, viewText;
    lText << model;
    printViewFile(viewText, model.view);
    ParseOptions options;
    options.fileName = file.string();
    if (viewText.str().empty()) return parse(lText.str(), options);
    return parse(lText.str(), viewText.str(), (file.parent_path() / "printed.v").string(), options);
}

std::vector<fs::path> exampleFiles() {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(GRAFTAL_EXAMPLES_DIR))
        // Map L-systems (docs/maps.md) have a reader of their own and no view settings.
        if (e.path().extension() == ".l" && !isMapLSystemFile(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

TEST(ViewSettingsRoundTrip, EveryExamplePrintsAndReadsBackToTheSameSettings) {
    const std::vector<fs::path> files = exampleFiles();
    ASSERT_GT(files.size(), 50u);
    int withViewFile = 0;
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.filename().string());
        ParseOptions options;
        fs::path view = fs::path(file).replace_extension(".v");
        if (fs::exists(view)) {
            options.viewFile = view.string();
            ++withViewFile;
        }
        ParseResult first = loadModel(file, options);
        ASSERT_TRUE(first.ok()) << messages(first.diagnostics);
        ParseResult second = reparse(first.model, file);
        std::ostringstream lText;
        lText << first.model;
        ASSERT_TRUE(second.ok()) << messages(second.diagnostics) << lText.str();
        const ViewSettings& a = first.model.view;
        const ViewSettings& b = second.model.view;
        EXPECT_EQ(printed(a), printed(b));
        EXPECT_EQ(a.turtle.angleDegrees, b.turtle.angleDegrees);
        EXPECT_EQ(a.turtle.stepLength, b.turtle.stepLength);
        EXPECT_EQ(a.turtle.initialWidth, b.turtle.initialWidth);
        EXPECT_EQ(a.turtle.clockwisePlus, b.turtle.clockwisePlus);
        EXPECT_EQ(a.turtle.tropism.has_value(), b.turtle.tropism.has_value());
        EXPECT_EQ(a.turtle.elasticity, b.turtle.elasticity);
        EXPECT_EQ(a.camera.scaleFactor, b.camera.scaleFactor);
        EXPECT_EQ(a.camera.viewpoint, b.camera.viewpoint);
        EXPECT_EQ(a.kolam.splineSubdivisions, b.kolam.splineSubdivisions);
        EXPECT_EQ(a.kolam.splineMode, b.kolam.splineMode);
        EXPECT_EQ(a.music.tempo, b.music.tempo);
        EXPECT_EQ(a.music.scale, b.music.scale);
        EXPECT_EQ(a.materials.contourSides, b.materials.contourSides);
        EXPECT_EQ(a.materials.contours.size(), b.materials.contours.size());
    }
    EXPECT_GE(withViewFile, 1);
}

// The pfg data files turn clockwise on +; their printed .l says so.
TEST(ViewSettingsRoundTrip, APfgDataFileKeepsItsClockwiseTurns) {
    ParseResult pfg = loadModel(fs::path(GRAFTAL_EXAMPLES_DIR) / "fig2.6-dragon-curve-pfg.l");
    ASSERT_TRUE(pfg.ok()) << messages(pfg.diagnostics);
    ASSERT_TRUE(pfg.model.view.turtle.clockwisePlus);
    std::ostringstream text;
    text << pfg.model;
    EXPECT_NE(text.str().find("\nplus turns: clockwise\n"), std::string::npos) << text.str();
    ParseOptions options;
    EXPECT_TRUE(parse(text.str(), options).orThrow().view.turtle.clockwisePlus);
}

// What only a view file states (cpfg's tropism lines, torques, light, twist, colours, the
// stems' sides, widths in world units) comes back through the printed view file.
TEST(ViewSettingsRoundTrip, ViewFileSettingsPrintAsAViewFileAndReadBack) {
    const std::string lText =
        "Lsystem: 1\nangle increment: 30\nline width: 2\nsurface: l leaf.s 0.5\n"
        "music tempo: 90\nmusic axis: x\nspline: path\nkolam dots: on\naxiom: F\nendlsystem\n";
    const std::string viewText =
        "initial color: 3\ncolour increment: 2\nline width increment: 0.5\n"
        "initial line width: 2\ntwist: 450\nscale factor: 0.9\n"
        "tropism: T: 0,-2,0 E: 0.25\ntorque: T: 1,0,0 E: 0.5\ntropism direction: 0,0,1\n"
        "initial elasticity: 0.3\nelasticity increment: 0.1\nlight: V: 1,1,1 D: 0.5 0.5 0.5\n"
        "polygonization level: 3\ncontour sides: 12\nprojection: parallel\n";
    ParseOptions options;
    ParseResult first = parse(lText, viewText, "m.v", options);
    ASSERT_TRUE(first.ok()) << messages(first.diagnostics);
    const ViewSettings& a = first.model.view;
    std::ostringstream viewFile;
    printViewFile(viewFile, a);
    EXPECT_NE(viewFile.str().find("tropism: T: 0, -1, 0 E: 0.25\n"), std::string::npos)
        << viewFile.str();
    EXPECT_NE(viewFile.str().find("twist: 450\n"), std::string::npos) << viewFile.str();
    EXPECT_NE(printed(a).find("/* view file: cylinder sides: 16 */\n"), std::string::npos)
        << printed(a);
    ParseResult second = reparse(first.model, "m.l");
    ASSERT_TRUE(second.ok()) << messages(second.diagnostics);
    const ViewSettings& b = second.model.view;
    EXPECT_EQ(printed(a), printed(b));
    EXPECT_EQ(b.turtle.initialColor, 3);
    EXPECT_EQ(b.turtle.colorIncrement, 2);
    EXPECT_EQ(b.turtle.widthIncrement, 0.5);
    EXPECT_TRUE(b.materials.widthsInModelUnits);
    EXPECT_DOUBLE_EQ(b.camera.twistDegrees, 45);
    EXPECT_DOUBLE_EQ(b.camera.scaleFactor, 90);
    ASSERT_EQ(b.turtle.tropisms.size(), 1u);
    EXPECT_EQ(b.turtle.tropisms[0].direction, (Vec3{0, -1, 0}));
    ASSERT_EQ(b.turtle.torques.size(), 1u);
    EXPECT_TRUE(b.turtle.cpfgTropism);
    EXPECT_EQ(b.turtle.tropism, (Vec3{0, 0, 1}));
    EXPECT_DOUBLE_EQ(b.turtle.elasticity, 0.3);
    EXPECT_DOUBLE_EQ(b.turtle.elasticityIncrement, 0.1);
    EXPECT_DOUBLE_EQ(b.camera.lightIntensity.value_or(-1), 0.5);
    EXPECT_EQ(b.materials.tubeSides, 16);
    EXPECT_EQ(b.materials.contourSides, 12);
    EXPECT_TRUE(b.camera.parallelProjection);
    ASSERT_EQ(b.materials.surfaces.size(), 1u);
    EXPECT_EQ(b.materials.surfaces[0].file, "leaf.s");
    EXPECT_EQ(b.music.tempo, 90);
    EXPECT_EQ(b.music.pitchFromX, true);
    EXPECT_EQ(b.kolam.splineMode, SplineMode::Path);
    EXPECT_TRUE(b.kolam.dots);
}

// A .l file names each setting once: its value reads, prints and reads again unchanged.
TEST(ViewSettingsRoundTrip, LFileSettingsPrintInTheirOwnSyntax) {
    const std::string text =
        "Lsystem: 1\nangle factor: 8\nstep length: 2.5\ninitial heading: 10\n"
        "viewpoint: 0, 0, 10\nview reference point: 0,1,0\nup vector: 1 0 0\n"
        "field of view: 40\nlight direction: 1,2,3\nbackground: #102030\nline style: lines\n"
        "width factor: 0.5\ntropism direction: 0,-1,0\ntropism elasticity: 0.2\n"
        "colour map: plant.map\nmaterial file: plant.mat\nspline subdivisions: 4\n"
        "music scale: minor\nmusic root: C4\nmusic instrument: 5\nmusic unit: 0.5\n"
        "axiom: F\nendlsystem\n";
    ParseOptions options;
    Model m = parse(text, options).orThrow();
    const std::string once = printed(m.view);
    EXPECT_NE(once.find("angle increment: 45\n"), std::string::npos) << once;
    EXPECT_NE(once.find("background: #102030\n"), std::string::npos) << once;
    EXPECT_NE(once.find("color map: plant.map\n"), std::string::npos) << once;
    EXPECT_NE(once.find("music scale: 0 2 3 5 7 8 10\n"), std::string::npos) << once;
    EXPECT_EQ(once.find("view file"), std::string::npos) << once;
    std::string again = "Lsystem: 1\n" + once + "axiom: F\nendlsystem\n";
    EXPECT_EQ(printed(parse(again, options).orThrow().view), once);
}
