// graftal derive, stats and render on map L-system files: picked by their first line.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "graftal/maps/plane_map.hpp"
#include "process.hpp"

using graftal::testing::runGraftal;
using graftal::testing::TempDir;
namespace fs = std::filesystem;

namespace {

std::string example(const std::string& name) {
    return (fs::path(GRAFTAL_EXAMPLES_DIR) / name).string();
}

}  // namespace

TEST(MapCli, StatsCountsTheLayer) {
    auto r = runGraftal("stats " + example("fig5.2-cell-layer.l"));
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["steps"], 5);
    EXPECT_EQ(j["vertices"], 78);
    EXPECT_EQ(j["edges"], 109);
    EXPECT_EQ(j["cells"], 32);
    int cells = 0, sides = 0;
    for (auto& [k, n] : j["cell sides"].items()) {
        cells += n.get<int>();
        sides += std::stoi(k) * n.get<int>();
    }
    EXPECT_EQ(cells, 32);
    // Every wall but the outline's bounds two cells.
    EXPECT_GT(sides, 109);
    EXPECT_EQ(j["branches"]["discarded"], 0) << "in Fig 5.2 every branch finds its partner";
    EXPECT_NEAR(j["bbox"]["max"][1].get<double>(), 1.0, 1e-12) << "the triangle's top corner";
}

TEST(MapCli, DerivePrintsTheCellsAndTakesStepsAndDefines) {
    auto r = runGraftal("derive " + example("fig5.1-square-map.l") + " -n 1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out,
              "map: step 1, 6 vertices, 7 edges, 2 cells\n"
              "cell 1: w5 x6 ~w1 ~e0\n"
              "cell 2: ~x6 w4 e3 ~w2\n"
              "outside: e0 w1 w2 ~e3 ~w4 ~w5\n");
    std::istringstream text(r.out);
    EXPECT_EQ(graftal::readMapText(text).size(), 3u);
    TempDir t;
    auto f = t.write("d.l",
                     "#define N 1\nmap L-system:\nderivation length: N\naxiom: abcd\n"
                     "a --> a[-x]a\nb --> b\nc --> c[-~x]c\nd --> d\nx --> x\n");
    r = runGraftal("derive " + f.string() + " -D N=0");
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "map: step 0, 4 vertices, 4 edges, 1 cells");
    r = runGraftal("derive " + f.string());
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "map: step 1, 6 vertices, 7 edges, 2 cells");
}

TEST(MapCli, RenderWritesEachPictureFormatInEachGeometry) {
    TempDir t;
    for (const char* geometry : {"siero", "relaxed", "spline"})
        for (const char* ext : {"svg", "png", "pdf"}) {
            const fs::path out = t.path() / (std::string(geometry) + "." + ext);
            auto r = runGraftal("render " + example("fig5.3-phascum-leaf.l") + " --map-geometry " +
                                geometry + " --map-fill age -o " + out.string());
            EXPECT_EQ(r.status, 0) << r.err;
            EXPECT_GT(fs::file_size(out), 500u) << out;
        }
    // The SVG has the walls as lines, wider for older walls.
    auto r = runGraftal("render " + example("fig5.2-cell-layer.l") + " -o " +
                        (t.path() / "walls.svg").string());
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string svg = graftal::testing::readFile(t.path() / "walls.svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
}

TEST(MapCli, BadInputNamesFileLineAndColumnAndWritesNothing) {
    TempDir t;
    auto f = t.write("bad.l", "map L-system:\naxiom: ab\na --> a[+bb]a\nb --> b\n");
    const fs::path out = t.path() / "bad.png";
    auto r = runGraftal("render " + f.string() + " -o " + out.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(f.string() + ":3:11: error: a branch is one edge"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out));
    r = runGraftal("render " + example("fig5.1-square-map.l") + " -o " +
                   (t.path() / "m.obj").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("a map L-system is drawn as a picture"), std::string::npos) << r.err;
    r = runGraftal("stats " + example("fig5.1-square-map.l") + " --map-geometry round");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--map-geometry 'round': expected siero, relaxed or spline"),
              std::string::npos)
        << r.err;
}

TEST(MapCli, DashReadsAMapFromStandardInputAndWritesToStandardOutput) {
    TempDir t;
    const fs::path square = example("fig5.1-square-map.l");
    auto fromFile = runGraftal("derive " + square.string() + " -n 2");
    auto r = runGraftal("derive - -n 2", square);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, fromFile.out);
    r = runGraftal("stats - --map-geometry relaxed", square);
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["file"], "<stdin>");
    EXPECT_EQ(j["cells"], 16);
    const fs::path svg = t.path() / "square.svg";
    r = runGraftal("render - -o " + svg.string(), square);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string picture = graftal::testing::readFile(svg);
    EXPECT_NE(picture.find("<svg"), std::string::npos);
    // -o -: the same picture on standard output.
    r = runGraftal("render " + square.string() + " -o -");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, picture);
    r = runGraftal("render - -o - --format png", square);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.substr(1, 3), "PNG");
    auto bad = t.write("bad.l", "map L-system:\naxiom: ab\na --> a[+bb]a\nb --> b\n");
    r = runGraftal("derive -", bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err.rfind("<stdin>:3:11: error: a branch is one edge", 0), 0u) << r.err;
}

TEST(MapCli, TheOutlineRuleIsChosenByName) {
    auto growing = runGraftal("stats " + example("fig5.2-cell-layer.l") +
                              " --map-geometry relaxed --map-outline growing");
    auto polygon = runGraftal("stats " + example("fig5.2-cell-layer.l") +
                              " --map-geometry relaxed --map-outline polygon");
    ASSERT_EQ(growing.status, 0) << growing.err;
    ASSERT_EQ(polygon.status, 0) << polygon.err;
    // The polygon keeps the axiom's triangle, its top corner at (0, 1).
    EXPECT_NEAR(nlohmann::json::parse(polygon.out)["bbox"]["max"][1].get<double>(), 1.0, 1e-12);
    EXPECT_NE(nlohmann::json::parse(growing.out)["bbox"],
              nlohmann::json::parse(polygon.out)["bbox"]);
    auto r = runGraftal("stats " + example("fig5.2-cell-layer.l") + " --map-outline round");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--map-outline 'round': expected growing or polygon"), std::string::npos)
        << r.err;
}
