// What the command says while it works: warnings for settings a picture does not use.
#include <gtest/gtest.h>

#include "graftal/graftal.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using graftal::testing::readFile;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace {

const char* kKoch =
    "Lsystem: 1\nangle factor: 4\nderivation length: 2\naxiom: F+F+F+F\n"
    "F --> F+F-F-FF+F+F-F\nendlsystem\n";
const char* kTree3D =
    "Lsystem: 1\nangle increment: 30\nderivation length: 3\naxiom: A\n"
    "A --> F[&A]/[&A]/[&A]\nendlsystem\n";

}  // namespace

TEST(CliFeedback, SettingsTheSceneDoesNotUseAreWarned) {
    TempDir t;
    auto koch = t.write("koch.l", kKoch);
    auto tree = t.write("tree.l", kTree3D);
    const std::string png = (t.path() / "p.png").string();
    auto r = runGraftal("render " + koch.string() + " -o " + png +
                        " --viewpoint 1,2,3 --fov 30 --spp 8 --tube-sides 5");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err,
              "graftal: warning: the scene is 2D and drawn as line art; 3D settings are "
              "ignored: --viewpoint, --fov, --spp, --tube-sides\n");
    r = runGraftal("render " + koch.string() + " -o " + png + " --viewpoint 1,2,3 -q");
    EXPECT_EQ(r.err, "");
    r = runGraftal("render " + koch.string() + " -o " + png + " --line-width 2 --color red");
    EXPECT_EQ(r.err, "") << "line settings are for line art";

    r = runGraftal("render " + tree.string() + " -o " + png +
                   " --size 64x64 --spp 1 --line-width 2 --color red --margin 0.1");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err,
              "graftal: warning: the 3D scene is ray traced, without lines; line settings are "
              "ignored: --line-width, --color, --margin\n");
    r = runGraftal("render " + tree.string() + " -o " + (t.path() / "t.obj").string() +
                   " --viewpoint 0,0,9");
    EXPECT_NE(r.err.find("a 3D file holds no camera or light; these settings are ignored: "
                         "--viewpoint"),
              std::string::npos)
        << r.err;
    r = runGraftal("render " + tree.string() + " -o " + png + " --size 64x64 --viewpoint 0,0,9");
    EXPECT_EQ(r.err, "") << "the camera of a ray-traced picture";
    r = runGraftal("render " + tree.string() + " -o " + png + " --view front --viewpoint 0,0,9");
    EXPECT_EQ(r.err,
              "graftal: warning: the 3D scene is drawn as 2D line art; its 3D settings are "
              "ignored: --viewpoint\n");

    // The library names the request's fields.
    graftal::RenderRequest request;
    request.output = t.path() / "lib.png";
    request.fieldOfView = 30;
    graftal::RenderResult result = graftal::render(graftal::testing::parseModel(kKoch), request);
    ASSERT_EQ(result.notes.size(), 1u);
    EXPECT_EQ(result.notes[0].severity, graftal::Severity::Warning);
    EXPECT_EQ(result.notes[0].fields, std::vector<std::string>{"fieldOfView"});
    EXPECT_NE(result.notes[0].toString().find("ignored: fieldOfView"), std::string::npos);
}
