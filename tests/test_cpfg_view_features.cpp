// cpfg features its example models lean on: blocks that change a production's parameters,
// comments in view files, `_` and the elasticity increment, several `torque:` lines, the
// stems' sides, `light:` lines, material files (.mat) and labels (@L). What cpfg does is
// read from its source (the reasoning is stated in each test); the files are our own.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "graftal/geometry/material_file.hpp"
#include "graftal/graftal.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "process.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

std::string derivedString(const std::string& l) {
    LSystem ls = parseLSystem(l);
    return derive(ls, -1).toString(ls.symbols);
}

ParseResult loadWithView(const TempDir& dir, const std::string& l, const std::string& v) {
    ParseOptions o;
    o.viewFile = dir.write("m.v", v).string();
    return loadModel(dir.write("m.l", l), o);
}

Model withView(const TempDir& dir, const std::string& successor, const std::string& view) {
    return loadWithView(
               dir,
               "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> " + successor + "\nendlsystem\n",
               view)
        .orThrow();
}

std::string messages(const std::vector<Diagnostic>& ds) {
    std::string s;
    for (const auto& d : ds) s += d.toString() + "\n";
    return s;
}

void expectSameEnds(const Scene& a, const Scene& b, const char* what) {
    ASSERT_EQ(a.segments.size(), b.segments.size()) << what;
    for (std::size_t i = 0; i < a.segments.size(); ++i) {
        EXPECT_NEAR(a.segments[i].b.x, b.segments[i].b.x, 1e-6) << what << " segment " << i;
        EXPECT_NEAR(a.segments[i].b.y, b.segments[i].b.y, 1e-6) << what << " segment " << i;
        EXPECT_NEAR(a.segments[i].b.z, b.segments[i].b.z, 1e-6) << what << " segment " << i;
    }
}

}  // namespace

// cpfg's course models write `A(t) : {t=t-PL;} t>0 --> I(t)...`: in cpfg a production's
// parameters are variables of its blocks, so the block's new value is what the condition,
// the post block and the successor read.
TEST(CpfgBlocks, APreBlockMayChangeAParameter) {
    EXPECT_EQ(derivedString("Lsystem: 1\nderivation length: 1\nAxiom: A(3) A(0.5)\n"
                            "A(t) : {t = t - 1;} t > 0 {t = t * 10;} --> B(t)\n"
                            "endlsystem\n"),
              "B(20)A(0.5)");
}

TEST(CpfgBlocks, AChangedParameterStaysWithItsProduction) {
    // The first production's block runs (its condition fails); the second production binds
    // the module's own value again.
    EXPECT_EQ(derivedString("Lsystem: 1\nderivation length: 1\nAxiom: A(1)\n"
                            "A(t) : {t = t + 100;} t > 1000 --> X(t)\n"
                            "A(t) --> Y(t)\n"
                            "endlsystem\n"),
              "Y(1)");
}

TEST(CpfgBlocks, AStochasticGroupHandsOverTheChosenProductionsParameters) {
    // Both candidates change t in their pre blocks; whichever is chosen, its own value
    // reaches its successor.
    std::string s = derivedString(
        "Lsystem: 1\nderivation length: 1\nAxiom: A(1)\n"
        "A(t) : {t = t + 10;} 1 --> X(t) : 0.5\n"
        "A(t) : {t = t + 20;} 1 --> Y(t) : 0.5\n"
        "endlsystem\n");
    EXPECT_TRUE(s == "X(11)" || s == "Y(21)") << s;
}

// cpfg runs the view file through its preprocessor and skips /* */ where it looks for a
// name: models comment settings out and write notes after values.
TEST(CpfgViewFile, CommentsAreSkipped) {
    TempDir dir;
    ParseResult r = loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n",
                                 "angle increment: 30 /* degrees */\n"
                                 "/*\n"
                                 "angle increment: 90\n"
                                 "surface: l nowhere.s 1\n"
                                 "*/\n"
                                 "line style: pixel    /* pixel, polygon or cylinder */\n"
                                 "// viewpoint: 0,0,30\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_TRUE(r.warnings().empty()) << messages(r.diagnostics);
    EXPECT_DOUBLE_EQ(r.model.view.turtle.angleDegrees, 30);
    EXPECT_EQ(r.model.view.materials.lineStyle, LineStyle::Lines);
    EXPECT_TRUE(r.model.view.materials.surfaces.empty()) << "a commented-out surface is not read";
    EXPECT_FALSE(r.model.view.camera.viewpoint);
}

TEST(CpfgViewFile, AnErrorAfterAMultiLineCommentNamesItsOwnLine) {
    TempDir dir;
    ParseResult r = loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n",
                                 "/* one\ntwo */ angle increment: many\n");
    ASSERT_TRUE(r.ok()) << "cpfg forgives its view files";
    EXPECT_NE(messages(r.diagnostics).find("m.v:2:25: warning:"), std::string::npos)
        << messages(r.diagnostics);
}

// cpfg's interpreter: `_` adds the view file's `elasticity increment:` to the turtle's
// elasticity, `_(e)` sets it; the elasticity is part of the turtle, so `]` restores it.
TEST(CpfgTropism, UnderscoreAddsTheElasticityIncrementAndBranchesKeepTheirOwn) {
    TempDir dir;
    const std::string view =
        "tropism direction: 1,0,0\ninitial elasticity: 0\nelasticity increment: 0.2\n";
    Model incremented = withView(dir, "F _F [_F] F", view);
    Model set = withView(dir, "F _(0.2)F [_(0.4)F] F", view);
    Model stiff = withView(dir, "F F [F] F", view);
    Scene a = interpret(incremented, derive(incremented, -1));
    Scene b = interpret(set, derive(set, -1));
    Scene c = interpret(stiff, derive(stiff, -1));
    expectSameEnds(a, b, "_ adds 0.2 each time, _(e) sets e");
    ASSERT_EQ(c.segments.size(), 4u);
    EXPECT_NEAR(c.segments[3].b.x, 0, 1e-9) << "elasticity 0: straight up";
    EXPECT_GT(a.segments[3].b.x, 0.05) << "bent toward +x after _";
    EXPECT_NEAR(a.segments[0].b.x, 0, 1e-9) << "before _ the elasticity is 0";
}

// cpfg reads each `torque:` line as a movement and sums them, like the `tropism:` lines:
// two lines of E: 0.25 roll the turtle as one of E: 0.5 (coordinates of the single line's
// test, CpfgMovements.TorqueRollsTheTurtleBeforeEveryMove, from cpfg's v10_torque).
TEST(CpfgMovements, SeveralTorqueLinesAdd) {
    TempDir dir;
    Model m = withView(dir, "F+F+F+F", "torque: T: 1,0,0 E: 0.25\ntorque: T: 2,0,0 E: 0.25\n");
    ASSERT_EQ(m.view.turtle.torques.size(), 2u);
    Scene s = interpret(m, derive(m, -1));
    ASSERT_EQ(s.segments.size(), 4u);
    EXPECT_NEAR(s.segments[1].b.x, -0.620545, 1e-5);
    EXPECT_NEAR(s.segments[1].b.z, 0.339005, 1e-5);
    EXPECT_NEAR(s.segments[3].b.x, -1.84678, 1e-5);
    EXPECT_NEAR(s.segments[3].b.z, 1.55477, 1e-5);
}

// cpfg: `polygonization level: n` draws stems with 2^(n+1) sides (at least 3).
TEST(CpfgViewFile, PolygonizationLevelAndCylinderSidesGiveTheStemsSides) {
    TempDir dir;
    ParseResult r =
        loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n", "polygonization level: 3\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    ASSERT_TRUE(r.model.view.materials.tubeSides);
    EXPECT_EQ(*r.model.view.materials.tubeSides, 16);
    ParseResult five =
        loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n", "cylinder sides: 5\n");
    ASSERT_TRUE(five.ok()) << messages(five.diagnostics);
    EXPECT_EQ(five.model.view.materials.tubeSides.value_or(0), 5);
    ParseResult two =
        loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n", "cylinder sides: 2\n");
    ASSERT_TRUE(two.ok()) << "cpfg forgives its view files";
    EXPECT_NE(messages(two.diagnostics).find("m.v:1:17: warning:"), std::string::npos)
        << messages(two.diagnostics);
}

TEST(CpfgViewFile, CylinderSidesShapeTheMesh) {
    TempDir dir;
    auto vertices = [&](const std::string& view) {
        std::filesystem::path folder = dir.path() / ("m" + std::to_string(view.size()));
        std::filesystem::create_directories(folder);
        {
            std::ofstream(folder / "m.l") << "Lsystem: 1\nAxiom: F&F\nendlsystem\n";
            std::ofstream(folder / "m.v") << view;
        }
        RenderRequest request;
        request.output = folder / "m.obj";
        render(loadModel(folder).orThrow(), request);
        std::ifstream in(folder / "m.obj");
        int n = 0;
        for (std::string line; std::getline(in, line);) n += line.rfind("v ", 0) == 0;
        return n;
    };
    int three = vertices("cylinder sides: 3\n");
    int twelve = vertices("cylinder sides: 12\n");
    // Two rings of n corners and the two caps' centres.
    EXPECT_EQ(three, 3 * 3 + 2);
    EXPECT_EQ(twelve, 3 * 12 + 2);
}

// cpfg's `light:` lines: V: a direction, D: the diffuse (here the sun's strength), A: the
// ambient light (here the sky's). graftal's ray tracer has one sun: a second line warns.
TEST(CpfgViewFile, TheFirstLightGivesTheSun) {
    TempDir dir;
    ParseResult r = loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n",
                                 "light: V: 1,0.5,1 D: 0.5 0.5 0.5 A: 0.2 0.2 0.2\n"
                                 "light: V: -1 -0.5 -1\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_EQ(r.model.view.camera.lightDirection, (Vec3{1, 0.5, 1}));
    EXPECT_DOUBLE_EQ(r.model.view.camera.lightIntensity.value_or(-1), 0.5);
    EXPECT_DOUBLE_EQ(r.model.view.camera.skyIntensity.value_or(-1), 0.2);
    ASSERT_EQ(r.warnings().size(), 1u) << messages(r.diagnostics);
    EXPECT_NE(messages(r.diagnostics).find("m.v:2:"), std::string::npos);
    ParseResult bad = loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n", "light: Q: 1 2 3\n");
    ASSERT_TRUE(bad.ok()) << "cpfg forgives its view files";
    EXPECT_NE(messages(bad.diagnostics).find("m.v:1:8: warning:"), std::string::npos)
        << messages(bad.diagnostics);
}

// A material of cpfg's .mat: a byte cpfg skips, transparency, ambient, diffuse, emission,
// specular (three bytes each), shininess. Materials past the file's end keep cpfg's
// defaults (diffuse 0.8 grey).
TEST(CpfgMaterials, DiffuseColoursBecomeThePalette) {
    std::vector<std::uint8_t> bytes(30, 0);
    bytes[15 + 1] = 51;                                          // transparency 0.2
    bytes[15 + 5] = 255, bytes[15 + 6] = 0, bytes[15 + 7] = 51;  // diffuse of material 1
    bytes[15 + 11] = 255;                                        // specular red
    bytes[15 + 14] = 20;                                         // shininess
    std::vector<Material> m = parseMaterials(bytes, "plant.mat");
    ASSERT_EQ(m.size(), 256u);
    EXPECT_EQ(m[1].diffuse, (Rgb{1, 0, 0.2f}));
    EXPECT_FLOAT_EQ(m[1].transparency, 0.2f);
    EXPECT_FLOAT_EQ(m[1].specular.r, 1);
    EXPECT_FLOAT_EQ(m[1].shininess, 20);
    EXPECT_EQ(m[2].diffuse, (Rgb{0.8f, 0.8f, 0.8f}));
    std::vector<Rgb> palette = materialPalette(m);
    EXPECT_EQ(palette[1], (Rgb{1, 0, 0.2f}));
    EXPECT_EQ(palette[0], (Rgb{0, 0, 0}));
    try {
        parseMaterials(std::vector<std::uint8_t>(16, 0), "plant.mat");
        FAIL() << "16 bytes are not whole materials";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("plant.mat"), std::string::npos) << e.what();
    }
}

TEST(CpfgMaterials, AModelFolderUsesItsMaterialFile) {
    TempDir dir;
    std::filesystem::path folder = dir.path() / "plant";
    std::filesystem::create_directories(folder);
    // A 3D stem (ray traced): materials colour the 3D palette.
    std::ofstream(folder / "plant.l") << "Lsystem: 1\nAxiom: ;(1)#(0.3)&(30)F\nendlsystem\n";
    std::ofstream(folder / "plant.v") << "angle increment: 30\n";
    {
        std::ofstream mat(folder / "plant.mat", std::ios::binary);
        std::vector<char> bytes(30, 0);
        bytes[15 + 5] = static_cast<char>(255);  // material 1: diffuse pure red
        mat.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    Model m = loadModel(folder).orThrow();
    EXPECT_EQ(m.view.materials.materialFile, "plant.mat");
    RenderRequest request;
    request.output = folder / "plant.png";
    request.picture.width = request.picture.height = 96;
    request.samplesPerPixel = 1;
    render(m, request);
    const std::string png = (folder / "plant.png").string();
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> image(
        cairo_image_surface_create_from_png(png.c_str()), &cairo_surface_destroy);
    ASSERT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS);
    const unsigned char* data = cairo_image_surface_get_data(image.get());
    const int stride = cairo_image_surface_get_stride(image.get());
    int red = 0;
    for (int y = 0; y < cairo_image_surface_get_height(image.get()); ++y)
        for (int x = 0; x < cairo_image_surface_get_width(image.get()); ++x) {
            const unsigned char* p = data + y * stride + 4 * x;  // B, G, R, A
            red += p[2] > 2 * p[1] + 20 && p[2] > 2 * p[0] + 20;
        }
    EXPECT_GT(red, 5) << "the stem is drawn in material 1's diffuse red";
}

// cpfg's `scale factor: 0.9` makes the picture fill 90 % of the window; graftal's scale
// factor (pfg's) is in percent.
TEST(CpfgViewFile, ScaleFactorIsAShareOfTheWindow) {
    TempDir dir;
    ParseResult r = loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n", "scale factor: 0.9\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_DOUBLE_EQ(r.model.view.camera.scaleFactor, 90);
}

// cpfg's label @L("format", values): the text is a string, not an expression. graftal keeps
// the module (and its values) and drops the text, which it does not draw.
TEST(CpfgLabels, ALabelsTextIsRead) {
    EXPECT_EQ(derivedString("Lsystem: 1\nderivation length: 1\nAxiom: A(2)\n"
                            "A(c) --> F@L(\" %.f, (\", c)@L(\"x\")\nendlsystem\n"),
              "F@L(2)@L");
}

// cpfg draws the text of @L; graftal draws no text and says so once.
TEST(CpfgLabels, LabelsAreNotedOnce) {
    TempDir dir;
    Model m = loadModel(dir.write("m.l", "Lsystem: 1\nAxiom: F@L(\"a\")F@L(\"b\")\nendlsystem\n"))
                  .orThrow();
    RenderRequest request;
    request.output = dir.path() / "m.svg";
    RenderResult r = render(m, request);
    int labelNotes = 0;
    for (const auto& d : r.notes) labelNotes += d.message.find("@L") != std::string::npos;
    EXPECT_EQ(labelNotes, 1) << messages(r.notes);
}

// A model folder named without a trailing slash: its surfaces are beside its .l, not in
// the folder above it.
TEST(CpfgModelFolder, SurfacesAreFoundBesideTheLFile) {
    TempDir dir;
    std::filesystem::path folder = dir.path() / "plant";
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "plant.l") << "Lsystem: 1\nAxiom: F~s\nendlsystem\n";
    std::ofstream(folder / "plant.v") << "surface: s own.s 1 3 3\n";
    std::filesystem::copy_file(std::filesystem::path(GRAFTAL_SURFACES_DIR) / "leaf.s",
                               folder / "own.s");
    RunResult r =
        runGraftal("render " + folder.string() + " -o " + (dir.path() / "plant.obj").string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "plant.obj"));
}
