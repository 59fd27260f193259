// What the command says while it works: warnings for settings a picture does not use, and
// progress on a terminal.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

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

// The terminal output of `command` run under a pseudo-terminal (script(1)).
std::string underATerminal(const std::string& command, const TempDir& t) {
    const auto log = t.path() / "typescript";
    const std::string cmd =
        "script -qfec \"" + command + "\" " + log.string() + " > /dev/null 2>&1 < /dev/null";
    const int raw = std::system(cmd.c_str());
    EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << command;
    return readFile(log);
}

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
    r = runGraftal("render " + tree.string() + " -o " + (t.path() / "t.ply").string() +
                   " --compress --no-instancing");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("instancing and compression settings apply to .glb files only; "
                         "ignored: --no-instancing, --compress"),
              std::string::npos)
        << r.err;
    r = runGraftal("render " + tree.string() + " -o " + (t.path() / "t.glb").string() +
                   " --compress --no-instancing");
    EXPECT_EQ(r.err, "") << "a GLB uses both";
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

TEST(CliFeedback, ALongRunShowsItsProgressOnATerminal) {
    TempDir t;
    // 44 million modules of a stochastic bush, streamed module by module and counted: a
    // second or two (a D0L island is counted in runs, too fast for the line to show).
    const std::string island = std::string(GRAFTAL_EXAMPLES_DIR) +
                               "/fig3.16-stochastic-bush.l -n 13 --stream --no-geometry";
    const std::string exe = GRAFTAL_EXE;
    std::string said = underATerminal(exe + " stats " + island + " > /dev/null", t);
    EXPECT_NE(said.find("\rgraftal: "), std::string::npos) << said;
    EXPECT_NE(said.find("% (step 13 of 13)"), std::string::npos) << said;
    EXPECT_NE(said.find("modules/s"), std::string::npos) << said;
    EXPECT_NE(said.find(" left"), std::string::npos) << said;
    // Quiet, or not on a terminal: nothing.
    said = underATerminal(exe + " stats " + island + " -q > /dev/null", t);
    EXPECT_EQ(said.find("modules/s"), std::string::npos) << said;
    auto r = runGraftal("stats " + island);
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "");
}

namespace {

std::size_t objFaces(const std::filesystem::path& obj) {
    std::istringstream in(readFile(obj));
    std::size_t faces = 0;
    for (std::string line; std::getline(in, line);)
        if (line.rfind("f ", 0) == 0) ++faces;
    return faces;
}

}  // namespace

TEST(CliFeedback, QualitySetsTheMeshResolutionOfRenderAndAnimate) {
    TempDir t;
    auto tree = t.write("tree.l", kTree3D);
    std::map<std::string, std::size_t> faces;
    for (const std::string q : {"low", "medium", "high"}) {
        const auto obj = t.path() / (q + ".obj");
        auto r = runGraftal("render " + tree.string() + " -o " + obj.string() + " --quality " + q);
        ASSERT_EQ(r.status, 0) << r.err;
        faces[q] = objFaces(obj);
    }
    // Tubes of 5, 8 and 16 sides: more sides, more triangles.
    EXPECT_LT(faces["low"], faces["medium"]);
    EXPECT_LT(faces["medium"], faces["high"]);
    auto r = runGraftal("render " + tree.string() + " -o " + (t.path() / "d.obj").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(objFaces(t.path() / "d.obj"), faces["medium"]) << "medium is the default";

    for (const std::string command : {"render", "animate"}) {
        const std::string out = (t.path() / (command == "render" ? "x.png" : "x.gif")).string();
        r = runGraftal(command + " " + tree.string() + " -o " + out + " --quality ultra");
        EXPECT_EQ(r.status, 1) << command;
        EXPECT_NE(r.err.find("--quality 'ultra': expected low, medium, high or a number"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << command;
    }
    r = runGraftal("animate " + tree.string() + " -o " + (t.path() / "a.gif").string() +
                   " --quality low --size 64x64 --spp 1");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_GT(std::filesystem::file_size(t.path() / "a.gif"), 0u);
}
