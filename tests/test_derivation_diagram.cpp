// Derivation diagrams (one row of labelled cells per step), the 3D default palette, and
// the gallery's promise that no example renders as a blank picture.
#include <cairo.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "graftal/graftal.hpp"
#include "process.hpp"

using namespace graftal;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;
namespace fs = std::filesystem;

namespace {

std::vector<ModuleString> stepsOf(const LSystem& ls, int n) {
    std::vector<ModuleString> steps;
    Derivation d(ls);
    steps.push_back(d.current());
    for (int k = 0; k < n; ++k) {
        d.step();
        steps.push_back(d.current());
    }
    return steps;
}

LSystem anabaena() {
    return parseLSystem(
        "module ar, al, br, bl;\nLsystem: 1\nderivation length: 6\naxiom: ar\n"
        "ar --> al br\nal --> bl ar\nbr --> ar\nbl --> al\nendlsystem\n");
}

RenderOptions frame(int w, int h) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    return o;
}

// A decoded PNG: its pixels as 0xRRGGBB.
struct Picture {
    int width = 0, height = 0;
    std::vector<std::uint32_t> pixels;

    explicit Picture(const fs::path& path) {
        std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(
            cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
        if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS) return;
        cairo_surface_flush(s.get());
        width = cairo_image_surface_get_width(s.get());
        height = cairo_image_surface_get_height(s.get());
        const int stride = cairo_image_surface_get_stride(s.get());
        const unsigned char* data = cairo_image_surface_get_data(s.get());
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                pixels.push_back(reinterpret_cast<const std::uint32_t*>(data + y * stride)[x] &
                                 0xffffff);
    }

    // Pixels that differ from the background (the most common colour) by more than a
    // faint antialiasing fringe in some channel.
    std::size_t ink() const {
        std::map<std::uint32_t, std::size_t> counts;
        for (std::uint32_t p : pixels) ++counts[p];
        std::uint32_t background = 0;
        std::size_t most = 0;
        for (auto [c, n] : counts)
            if (n > most) most = n, background = c;
        return static_cast<std::size_t>(std::count_if(
            pixels.begin(), pixels.end(), [&](std::uint32_t p) { return differs(p, background); }));
    }

    static int channel(std::uint32_t p, int k) { return static_cast<int>((p >> (8 * k)) & 0xff); }
    static bool differs(std::uint32_t a, std::uint32_t b) {
        for (int k = 0; k < 3; ++k)
            if (std::abs(channel(a, k) - channel(b, k)) > 32) return true;
        return false;
    }
};

}  // namespace

TEST(DerivationDiagram, OneRowPerStepAndOneCellPerModule) {
    LSystem ls = anabaena();
    auto steps = stepsOf(ls, 6);
    DerivationDiagram d = layoutDerivationDiagram(steps, ls.symbols, frame(800, 800));
    ASSERT_EQ(d.rows.size(), 7u);                            // the axiom and six steps
    const std::size_t expected[] = {1, 2, 3, 5, 8, 13, 21};  // Fibonacci, as in the book
    for (std::size_t r = 0; r < d.rows.size(); ++r) {
        EXPECT_EQ(d.rows[r].step, static_cast<int>(r));
        EXPECT_EQ(d.rows[r].cells.size(), expected[r]) << "row " << r;
    }
    EXPECT_EQ(d.rows[0].cells[0].label, "ar");
    EXPECT_EQ(d.rows[2].cells[0].label, "bl");
    // Step 0 at the top, rows going down; cells left to right, inside the frame.
    for (std::size_t r = 1; r < d.rows.size(); ++r)
        EXPECT_GT(d.rows[r].cells[0].y, d.rows[r - 1].cells[0].y);
    for (const auto& row : d.rows)
        for (const auto& c : row.cells) {
            EXPECT_GE(c.x, 0);
            EXPECT_LE(c.x + c.width, 800);
            EXPECT_GE(c.y, 0);
            EXPECT_LE(c.y + c.height, 800);
        }
    // Rows are aligned left: every row's first cell starts at the same x.
    for (const auto& row : d.rows) EXPECT_DOUBLE_EQ(row.cells[0].x, d.rows[0].cells[0].x);
}

TEST(DerivationDiagram, EachSymbolHasOneColourAndSymbolsDiffer) {
    LSystem ls = anabaena();
    auto steps = stepsOf(ls, 6);
    DerivationDiagram d = layoutDerivationDiagram(steps, ls.symbols, frame(800, 800));
    std::map<std::string, Rgb> colourOf;
    for (const auto& row : d.rows)
        for (const auto& c : row.cells) {
            auto [it, inserted] = colourOf.emplace(c.label, c.fill);
            if (!inserted) {
                EXPECT_EQ(it->second, c.fill) << c.label;
            }
        }
    ASSERT_EQ(colourOf.size(), 4u);
    std::set<std::tuple<float, float, float>> distinct;
    for (auto& [label, c] : colourOf) distinct.insert({c.r, c.g, c.b});
    EXPECT_EQ(distinct.size(), 4u) << "ar, al, br, bl get four colours";
}

TEST(DerivationDiagram, LongRowsEndInAnEllipsisCountingTheHiddenModules) {
    LSystem ls = anabaena();
    auto steps = stepsOf(ls, 12);  // the last row has 233 cells
    DerivationDiagram d = layoutDerivationDiagram(steps, ls.symbols, frame(400, 400));
    ASSERT_EQ(d.rows.size(), 13u);
    const DiagramRow& last = d.rows.back();
    ASSERT_FALSE(last.cells.empty());
    const DiagramCell& end = last.cells.back();
    ASSERT_TRUE(end.ellipsis);
    EXPECT_EQ(end.hidden + (last.cells.size() - 1), steps.back().size());
    EXPECT_NE(end.parameters.find(std::to_string(end.hidden)), std::string::npos);
    EXPECT_LE(end.x + end.width, 400);
    // Short rows are whole.
    EXPECT_EQ(d.rows[3].cells.size(), 5u);
    EXPECT_FALSE(d.rows[3].cells.back().ellipsis);
}

TEST(DerivationDiagram, TooManyStepsLeaveOutTheMiddleOnes) {
    LSystem ls = parseLSystem("Lsystem: 1\naxiom: a\na --> a\nendlsystem\n");
    auto steps = stepsOf(ls, 60);
    DerivationDiagram d = layoutDerivationDiagram(steps, ls.symbols, frame(300, 300));
    ASSERT_LT(d.rows.size(), 61u);
    EXPECT_EQ(d.rows.front().step, 0);
    EXPECT_EQ(d.rows.back().step, 60);
    auto gap = std::find_if(d.rows.begin(), d.rows.end(), [](auto& r) { return r.gap; });
    ASSERT_NE(gap, d.rows.end());
    EXPECT_EQ(gap->cells.at(0).hidden + (d.rows.size() - 1), 61u);
}

TEST(DerivationDiagram, SvgHoldsTheLabelsAndParameters) {
    LSystem ls = parseLSystem("Lsystem: 1\naxiom: F(0,0)A(1)\nA(n) --> F(0,n)A(n+1)\nendlsystem\n");
    auto steps = stepsOf(ls, 2);
    std::ostringstream svg;
    writeDerivationDiagramSvg(layoutDerivationDiagram(steps, ls.symbols, frame(600, 400)), svg);
    const std::string s = svg.str();
    EXPECT_NE(s.find("<svg"), std::string::npos);
    EXPECT_NE(s.find(">F</text>"), std::string::npos);
    EXPECT_NE(s.find(">A</text>"), std::string::npos);
    EXPECT_NE(s.find(">0,1</text>"), std::string::npos);
    EXPECT_NE(s.find(">3</text>"), std::string::npos);  // A(3) after two steps
    // Labels that are XML are escaped.
    LSystem lt = parseLSystem("Lsystem: 1\naxiom: F&\nendlsystem\n");
    std::ostringstream svg2;
    writeDerivationDiagramSvg(layoutDerivationDiagram(stepsOf(lt, 0), lt.symbols, frame(200, 200)),
                              svg2);
    EXPECT_NE(svg2.str().find(">&amp;</text>"), std::string::npos);
}

TEST(DerivationDiagram, CliDrawsTheDerivationWhenTheStringDrawsNothing) {
    TempDir dir;
    auto png = dir.path() / "anabaena.png";
    auto r =
        runGraftal("render " + (fs::path(GRAFTAL_EXAMPLES_DIR) / "fig1.4-anabaena.l").string() +
                   " --size 400x400 -o " + png.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("the string draws nothing; drawing its derivation instead"),
              std::string::npos);
    Picture p(png);
    ASSERT_EQ(p.width, 400);
    EXPECT_GT(p.ink(), 5000u);

    // Asked for, on a file that draws: an SVG of its steps, no note.
    auto svg = dir.path() / "plant.svg";
    r = runGraftal("render " +
                   (fs::path(GRAFTAL_EXAMPLES_DIR) / "fig3.2a-bracketed-plant.l").string() +
                   " -n 2 --derivation -o " + svg.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("draws nothing"), std::string::npos);
    const std::string text = graftal::testing::readFile(svg);
    EXPECT_NE(text.find(">F</text>"), std::string::npos);
    EXPECT_NE(text.find(">[</text>"), std::string::npos);

    // Not a picture format: refused, nothing written.
    auto obj = dir.path() / "a.obj";
    r = runGraftal("render " + (fs::path(GRAFTAL_EXAMPLES_DIR) / "fig1.4-anabaena.l").string() +
                   " --derivation -o " + obj.string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("--derivation"), std::string::npos);
    EXPECT_FALSE(fs::exists(obj));
}

TEST(DefaultPalette3D, IndexZeroIsALightBarkBrownNotInk) {
    auto p = defaultPalette3D();
    ASSERT_EQ(p.size(), Scene::defaultPalette().size());
    EXPECT_GT(p[0].r, 0.4f);
    EXPECT_GT(p[0].r, p[0].b);  // warm: brown
    for (std::size_t k = 1; k < p.size(); ++k) EXPECT_EQ(p[k], Scene::defaultPalette()[k]);
}

TEST(DefaultPalette3D, AnUncolouredStemIsShadedNotASilhouette) {
    TempDir dir;
    auto l = dir.write("stem.l", "Lsystem: 1\naxiom: !(1)&(10)F(6)\nendlsystem\n");
    auto png = dir.path() / "stem.png";
    auto r = runGraftal("render " + l.string() + " --size 64x64 --spp 1 -o " + png.string());
    ASSERT_EQ(r.status, 0) << r.err;
    Picture p(png);
    ASSERT_EQ(p.width, 64);
    const std::uint32_t centre = p.pixels[32 * 64 + 32];
    const int red = Picture::channel(centre, 2), blue = Picture::channel(centre, 0);
    EXPECT_GT(red, 90) << "the stem's middle is lit brown, not near-black ink";
    EXPECT_GT(red, blue);
    // Line art of the same stem stays black.
    auto flat = dir.path() / "stem-front.png";
    r = runGraftal("render " + l.string() + " --view front --size 64x64 -o " + flat.string());
    ASSERT_EQ(r.status, 0) << r.err;
    Picture q(flat);
    EXPECT_LT(Picture::channel(q.pixels[32 * 64 + 32], 2), 60);
}

// Every example renders to a picture with something in it: a few hundred pixels of ink
// at 400x400 at least. 3D examples are ray traced with one sample per pixel.
TEST(Gallery, NoExampleRendersBlank) {
    std::vector<fs::path> files;
    for (auto& e : fs::directory_iterator(GRAFTAL_EXAMPLES_DIR))
        if (e.path().extension() == ".l") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_GE(files.size(), 90u);
    TempDir dir;
    std::vector<std::string> problems(files.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i; (i = next++) < files.size();) {
            const fs::path out = dir.path() / (files[i].stem().string() + ".png");
            const std::string cmd = std::string(GRAFTAL_EXE) + " render '" + files[i].string() +
                                    "' -q --threads 1 --size 400x400 --spp 1 -o '" + out.string() +
                                    "' > /dev/null 2>&1 < /dev/null";
            int raw = std::system(cmd.c_str());
            if (!WIFEXITED(raw) || WEXITSTATUS(raw) != 0) {
                problems[i] = "render failed";
                continue;
            }
            Picture p(out);
            if (p.width != 400) {
                problems[i] = "not a 400x400 PNG";
                continue;
            }
            if (std::size_t ink = p.ink(); ink < 300)
                problems[i] = "blank: " + std::to_string(ink) + " ink pixels";
        }
    };
    std::vector<std::thread> workers;
    for (int k = 0; k < 2; ++k) workers.emplace_back(work);
    for (auto& t : workers) t.join();
    for (std::size_t i = 0; i < files.size(); ++i)
        EXPECT_TRUE(problems[i].empty()) << files[i].filename().string() << ": " << problems[i];
}

// ABOP's trees had widths in pixels; in model units they must stay slender.
TEST(GalleryModels, AbopTreesHaveSlenderTrunks) {
    for (const char* name : {"honda-monopodial-tree.l", "aono-kunii-sympodial-tree.l"}) {
        SCOPED_TRACE(name);
        Model m = loadModel(fs::path(GRAFTAL_EXAMPLES_DIR) / name).orThrow();
        Scene scene = interpret(m, applyHomomorphism(m.lsystem, derive(m)));
        ASSERT_FALSE(scene.segments.empty());
        float widest = 0;
        for (const Segment& s : scene.segments) widest = std::max(widest, s.width);
        const Bounds b = scene.bounds();
        EXPECT_LT(widest, 0.05 * (b.max.y - b.min.y))
            << "the trunk is a twentieth of the height at most";
    }
}

// To the turtle Fl and Fr are both F: the Fl/Fr dragon is the same curve as the l/r one.
TEST(GalleryModels, FlFrDragonDrawsTheDragon) {
    auto sceneOf = [](const char* name) {
        Model m = loadModel(fs::path(GRAFTAL_EXAMPLES_DIR) / name).orThrow();
        return interpret(m, applyHomomorphism(m.lsystem, derive(m)));
    };
    Scene flfr = sceneOf("fig2.6-dragon-curve-fl-fr.l"), lr = sceneOf("fig2.6-dragon-curve-lr.l");
    EXPECT_EQ(flfr.segments.size(), 1024u);
    ASSERT_EQ(flfr.segments.size(), lr.segments.size());
    for (std::size_t i = 0; i < lr.segments.size(); ++i) {
        EXPECT_NEAR(flfr.segments[i].b.x, lr.segments[i].b.x, 1e-9);
        EXPECT_NEAR(flfr.segments[i].b.y, lr.segments[i].b.y, 1e-9);
    }
}
