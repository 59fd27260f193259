// cpfg view files (.v): each setting's effect on the model and the drawing, errors located
// at file:line:column, unknown lines warned, model folders, and the cpfg oracle's cases.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "graftal/graftal.hpp"
#include "graftal/lang/view_file.hpp"
#include "process.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

const char* kPlant = "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> F#F!F;F,F\nendlsystem\n";

ParseResult loadWithView(const TempDir& dir, const std::string& l, const std::string& v) {
    ParseOptions o;
    o.viewFile = dir.write("m.v", v).string();
    return loadModel(dir.write("m.l", l), o);
}

std::string messages(const std::vector<Diagnostic>& ds) {
    std::string s;
    for (const auto& d : ds) s += d.toString() + "\n";
    return s;
}

}  // namespace

TEST(ViewFile, EachSettingReachesTheView) {
    TempDir dir;
    ParseResult r = loadWithView(dir, kPlant,
                                 "angle increment: 30\n"
                                 "initial line width: 2 pixels\n"
                                 "line width increment: 0.5\n"
                                 "initial color: 3\n"
                                 "color increment: 2\n"
                                 "viewpoint: 0,0,10\n"
                                 "view reference point: 0 1 0\n"
                                 "up vector: 1,0,0\n"
                                 "projection: parallel\n"
                                 "twist: 450\n"
                                 "tropism: T: 0,-2,0 E: 0.25\n"
                                 "torque: T: 1,0,0 E: 0.5\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_TRUE(r.warnings().empty()) << messages(r.diagnostics);
    const ViewSettings& v = r.model.view;
    EXPECT_DOUBLE_EQ(v.turtle.angleDegrees, 30);
    EXPECT_DOUBLE_EQ(v.turtle.initialWidth, 2);
    ASSERT_TRUE(v.turtle.widthIncrement);
    EXPECT_DOUBLE_EQ(*v.turtle.widthIncrement, 0.5);
    EXPECT_EQ(v.turtle.initialColor, 3);
    EXPECT_EQ(v.turtle.colorIncrement, 2);
    EXPECT_EQ(v.camera.viewpoint, (Vec3{0, 0, 10}));
    EXPECT_EQ(v.camera.referencePoint, (Vec3{0, 1, 0}));
    EXPECT_EQ(v.camera.upVector, (Vec3{1, 0, 0}));
    EXPECT_TRUE(v.camera.parallelProjection);
    EXPECT_DOUBLE_EQ(v.camera.twistDegrees, 45) << "cpfg's twist is in tenths of a degree";
    ASSERT_EQ(v.turtle.tropisms.size(), 1u) << "a `tropism:` line acts before every move";
    EXPECT_EQ(v.turtle.tropisms[0].direction, (Vec3{0, -1, 0})) << "normalised";
    EXPECT_DOUBLE_EQ(v.turtle.tropisms[0].elasticity, 0.25);
    EXPECT_FALSE(v.turtle.tropism) << "not the book's tropism after each segment";
    ASSERT_EQ(v.turtle.torques.size(), 1u) << "`torque:` lines add up, like `tropism:` lines";
    EXPECT_EQ(v.turtle.torques[0].direction, (Vec3{1, 0, 0}));
    EXPECT_DOUBLE_EQ(v.turtle.torques[0].elasticity, 0.5);
}

TEST(ViewFile, TheViewFileWinsOverTheLFile) {
    TempDir dir;
    ParseResult r =
        loadWithView(dir, "Lsystem: 1\nangle increment: 90\nline width: 3\nAxiom: F\nendlsystem\n",
                     "angle increment: 15\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    EXPECT_DOUBLE_EQ(r.model.view.turtle.angleDegrees, 15);
    EXPECT_DOUBLE_EQ(r.model.view.turtle.initialWidth, 3) << "what the .v leaves alone stays";
}

TEST(ViewFile, WidthAndColourIncrementsDrawTheSegments) {
    TempDir dir;
    ParseResult r = loadWithView(dir, kPlant,
                                 "initial line width: 2\nline width increment: 0.5\n"
                                 "initial color: 3\ncolor increment: 2\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    Scene s = interpret(r.model, derive(r.model, 1));
    ASSERT_EQ(s.segments.size(), 5u);
    EXPECT_FLOAT_EQ(s.segments[0].width, 2);
    EXPECT_FLOAT_EQ(s.segments[1].width, 2.5) << "# adds the increment";
    EXPECT_FLOAT_EQ(s.segments[2].width, 2) << "! subtracts it";
    EXPECT_EQ(s.segments[0].color, 3);
    EXPECT_EQ(s.segments[3].color, 5) << "; adds the colour increment";
    EXPECT_EQ(s.segments[4].color, 3) << ", subtracts it";
}

// cpfg forgives its view files: a value it cannot use leaves the setting at its default and
// the model runs. graftal warns at the value's file:line:column and goes on.
TEST(ViewFile, ABadValueIsAWarningAtItsColumnAndTheSettingKeepsItsDefault) {
    TempDir dir;
    ParseResult r = loadWithView(dir, kPlant, "angle increment: 30\ninitial line width: thick\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    ASSERT_EQ(r.warnings().size(), 1u) << messages(r.diagnostics);
    const Diagnostic e = r.warnings()[0];
    EXPECT_EQ(e.location.file, (dir.path() / "m.v").string());
    EXPECT_EQ(e.location.line, 2);
    EXPECT_EQ(e.location.column, 21);
    EXPECT_EQ(e.location.endColumn, 26);
    EXPECT_NE(e.message.find("line width"), std::string::npos) << e.message;
    EXPECT_NE(e.message.find("expected a number"), std::string::npos) << e.message;
    EXPECT_DOUBLE_EQ(r.model.view.turtle.angleDegrees, 30) << "the good line before still counts";

    r = loadWithView(dir, kPlant, "viewpoint: 1, 2\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    ASSERT_EQ(r.warnings().size(), 1u) << messages(r.diagnostics);
    EXPECT_NE(r.warnings()[0].message.find("three numbers"), std::string::npos);

    r = loadWithView(dir, kPlant,
                     "projection: fisheye\nangle increment: ?\nline style: wireframe\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    ASSERT_GE(r.warnings().size(), 2u) << messages(r.diagnostics);
    EXPECT_EQ(r.warnings()[0].location.line, 1);
    EXPECT_EQ(r.warnings()[0].location.column, 13);
    EXPECT_EQ(r.warnings()[1].location.line, 2);
    const double defaultTurn = loadWithView(dir, kPlant, "\n").model.view.turtle.angleDegrees;
    EXPECT_DOUBLE_EQ(r.model.view.turtle.angleDegrees, defaultTurn)
        << "'angle increment: ?' leaves the default turn";
    const Model m = std::move(r).orThrow();
    EXPECT_EQ(derive(m.lsystem).size(), 9u) << "the model derives all the same";

    // The .l file's own errors still stop the run.
    r = loadWithView(dir, "Lsystem: 1\nAxiom: A(\nendlsystem\n", "angle increment: ?\n");
    EXPECT_FALSE(r.ok());
}

TEST(ViewFile, AnUnknownLineIsWarnedOnceWithItsLine) {
    TempDir dir;
    ParseResult r = loadWithView(dir, kPlant, "angle increment: 30\nsparkle: 3\n\n");
    ASSERT_TRUE(r.ok());
    ASSERT_EQ(r.warnings().size(), 1u) << messages(r.diagnostics);
    EXPECT_EQ(r.warnings()[0].location.line, 2);
    EXPECT_NE(r.warnings()[0].message.find("sparkle"), std::string::npos);
    EXPECT_DOUBLE_EQ(r.model.view.turtle.angleDegrees, 30);
}

TEST(ViewFile, TheCommandLineTakesTheViewFileSecond) {
    TempDir dir;
    auto l = dir.write("m.l", "Lsystem: 1\nAxiom: F+F\nendlsystem\n");
    auto v = dir.write("m.v", "angle increment: 90\n");
    auto r = runGraftal("stats '" + l.string() + "' '" + v.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"max\": [\n      0.0,\n      1.0"), std::string::npos) << r.out;
    auto bad = dir.write("bad.v", "angle increment: x\n");
    r = runGraftal("derive '" + l.string() + "' '" + bad.string() + "'");
    EXPECT_EQ(r.status, 0) << "cpfg forgives its view files: " << r.err;
    EXPECT_EQ(r.out, "F+F\n");
    EXPECT_NE(r.err.find("bad.v:1:18"), std::string::npos) << r.err;
}

TEST(ViewFile, AModelFolderAloneRendersWithItsViewFile) {
    TempDir dir;
    dir.write("plant.l",
              "Lsystem: 1\nderivation length: 3\nAxiom: A\nA --> F[+A][-A]FA\nendlsystem\n");
    dir.write("plant.v", "angle increment: 25\ninitial line width: 0.2\n");
    auto png = dir.path() / "plant.png";
    auto r = runGraftal("render '" + dir.path().string() + "' -q --size 200x200 --spp 1 -o '" +
                        png.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    cairo_surface_t* img = cairo_image_surface_create_from_png(png.string().c_str());
    ASSERT_EQ(cairo_surface_status(img), CAIRO_STATUS_SUCCESS);
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    int stride = cairo_image_surface_get_stride(img);
    const unsigned char* data = cairo_image_surface_get_data(img);
    std::uint32_t corner = *reinterpret_cast<const std::uint32_t*>(data);
    int ink = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (*reinterpret_cast<const std::uint32_t*>(data + y * stride + x * 4) != corner) ++ink;
    cairo_surface_destroy(img);
    EXPECT_GT(ink, 100) << "a blank picture";

    r = runGraftal("derive '" + dir.path().string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("F[+"), std::string::npos);
}

TEST(ViewFile, AFolderWithoutAnLFileIsAnError) {
    TempDir dir;
    auto r = runGraftal("derive '" + dir.path().string() + "'");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("no .l file"), std::string::npos) << r.err;
}
