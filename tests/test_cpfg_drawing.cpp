// How cpfg draws what its view file and string name: line widths in world units (cpfg's
// `initial line width:` without `pixels`), and a surface `~X` that no `surface:` line
// declares. What cpfg does is read from its source (interpret.c, tsurfaces.c); the reasoning
// is stated in each test, the files are our own.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <string>
#include <vector>

#include "graftal/graftal.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using namespace graftal::testing;

namespace {

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

// The stroke widths of an SVG's paths, narrowest first.
std::vector<double> strokeWidths(const std::string& svg) {
    std::vector<double> widths;
    const std::regex width("stroke-width=\"([0-9.]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), width);
         it != std::sregex_iterator(); ++it)
        widths.push_back(std::stod((*it)[1]));
    std::sort(widths.begin(), widths.end());
    return widths;
}

std::vector<double> svgStrokes(const TempDir& dir, const Model& m, int size) {
    RenderRequest request;
    request.output = dir.path() / ("m" + std::to_string(size) + ".svg");
    request.picture.width = request.picture.height = size;
    render(m, request);
    return strokeWidths(readFile(request.output));
}

int objVertices(const std::filesystem::path& obj) {
    const std::string text = readFile(obj);
    int n = 0;
    for (std::size_t at = text.find("\nv "); at != std::string::npos;
         at = text.find("\nv ", at + 1))
        ++n;
    return n;
}

}  // namespace

// cpfg's view-file reader: `initial line width: W` sets the polygon line style (widths in
// world units) unless a word starting with p follows (`pixels`); `line style:` sets it
// again, so the later line wins.
TEST(CpfgLineWidth, TheViewFileSaysWhetherWidthsAreWorldUnits) {
    TempDir dir;
    const std::string l = "Lsystem: 1\nAxiom: F\nendlsystem\n";
    auto unit = [&](const std::string& v) {
        ParseResult r = loadWithView(dir, l, v);
        EXPECT_TRUE(r.ok()) << messages(r.diagnostics);
        return r.model.view.materials.widthsInModelUnits;
    };
    EXPECT_TRUE(unit("initial line width: 1\n"));
    EXPECT_TRUE(unit("initial line width: 0.1 s\n"));
    EXPECT_FALSE(unit("initial line width: 3 pixels\n"));
    EXPECT_FALSE(unit("angle increment: 30\n"));  // cpfg's default: one-pixel lines
    EXPECT_FALSE(unit("initial line width: 1\nline style: pixel\n"));
    EXPECT_TRUE(unit("initial line width: 2 pixels\nline style: cylinder\n"));
}

// World-unit widths are drawn as wide as the picture makes them: `F#(0.05)F` is 2 units
// high, so in a 200-pixel picture (5 % margins: 180 pixels for the height) one unit is 90
// pixels, the first segment (width 0.1) 9 pixels wide and the second 4.5; twice the
// picture, twice the widths. Without world units (`pixels`) the widths do not follow the
// picture's scale: the first stays near the default line width.
TEST(CpfgLineWidth, WorldUnitWidthsScaleWithThePicture) {
    TempDir dir;
    const std::string l = "Lsystem: 1\nAxiom: F#(0.05)F\nendlsystem\n";
    Model world = loadWithView(dir, l, "initial line width: 0.1\n").orThrow();
    std::vector<double> small = svgStrokes(dir, world, 200), large = svgStrokes(dir, world, 400);
    ASSERT_EQ(small.size(), 2u);
    ASSERT_EQ(large.size(), 2u);
    EXPECT_NEAR(small[0], 4.5, 0.01);
    EXPECT_NEAR(small[1], 9, 0.01);
    EXPECT_NEAR(large[0], 9, 0.01);
    EXPECT_NEAR(large[1], 18, 0.01);

    Model pixels = loadWithView(dir, l, "initial line width: 0.1 pixels\n").orThrow();
    std::vector<double> thin = svgStrokes(dir, pixels, 400);
    ASSERT_EQ(thin.size(), 2u);
    EXPECT_LT(thin[1], 3);
    EXPECT_NEAR(thin[0], thin[1] / 2, 0.01);
}

// cpfg's `~X` looks X up among the surfaces the view file declared and, when none is
// called X, draws nothing and leaves the turtle where it is (tsurfaces.c:
// determine_end_point returns when FindSurfaceIndex finds none). graftal warns, naming
// the production that places it, and draws the rest.
TEST(CpfgSurfaces, AnUndeclaredSurfaceIsAWarningAndDrawsNothing) {
    TempDir dir;
    dir.write("m.l", "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> F~b F\nendlsystem\n");
    dir.write("plain.l", "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> FF\nendlsystem\n");
    RunResult r = runGraftal("render " + (dir.path() / "m.l").string() + " -o " +
                             (dir.path() / "m.obj").string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("m.l:4:1: warning: '~b' places surface 'b'"), std::string::npos) << r.err;
    RunResult plain = runGraftal("render " + (dir.path() / "plain.l").string() + " -o " +
                                 (dir.path() / "plain.obj").string());
    ASSERT_EQ(plain.status, 0) << plain.err;
    EXPECT_GT(objVertices(dir.path() / "m.obj"), 0);
    EXPECT_EQ(objVertices(dir.path() / "m.obj"), objVertices(dir.path() / "plain.obj"));
}

// cpfg's view-file reader (interpret.c, ReadViewData) has no `material` line: cpfg takes
// materials from a .mat file on its command line (-M), which graftal finds in a model
// folder or by the .l file's `material file:`. The line is warned at its place, saying so.
TEST(CpfgMaterials, AMaterialLineInAViewFileIsWarnedWithWhereMaterialsComeFrom) {
    TempDir dir;
    ParseResult r = loadWithView(dir, "Lsystem: 1\nAxiom: F\nendlsystem\n",
                                 "angle increment: 30\nmaterial: 1 2 3\n");
    ASSERT_TRUE(r.ok()) << messages(r.diagnostics);
    const std::string said = messages(r.diagnostics);
    EXPECT_NE(said.find("m.v:2:1: warning: 'material:' is ignored"), std::string::npos) << said;
    EXPECT_NE(said.find(".mat"), std::string::npos) << said;
}

// cpfg's .l lexer (lsys_input.l) has no `contour sides:`: it belongs to the view file.
// graftal refuses it in the .l too, at its line.
TEST(CpfgViewFile, ContourSidesBelongsToTheViewFile) {
    try {
        parseModel("Lsystem: 1\ncontour sides: 5\nAxiom: F\nendlsystem\n");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("test.l:2:1: error: unknown keyword 'contour sides:'"),
                  std::string::npos)
            << e.what();
    }
}
