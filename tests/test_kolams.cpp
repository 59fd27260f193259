// Kolams (LSFP ch. 6.2) as the book writes and draws them: the strings are the printed
// productions with f, and the B-spline runs through every position of the turtle.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "graftal/geometry/kolam.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using graftal::testing::TempDir;

namespace graftal {
namespace {

Model example(const std::string& name, ParseOptions options = {}) {
    return graftal::testing::loadExample(std::string(GRAFTAL_EXAMPLES_DIR) + "/" + name,
                                         std::move(options));
}

// The book's productions applied by plain string replacement, independent of graftal:
// every letter with a production is replaced in parallel, everything else is copied.
std::string expand(std::string s, const std::map<char, std::string>& productions, int steps) {
    for (int i = 0; i < steps; ++i) {
        std::string next;
        for (char c : s) {
            auto p = productions.find(c);
            next += p == productions.end() ? std::string(1, c) : p->second;
        }
        s = next;
    }
    return s;
}

std::string derivedString(const Model& m, int steps) {
    return deriveWithQueries(m, steps).toString(m.lsystem.symbols);
}

std::size_t count(const std::string& s, char c) {
    return static_cast<std::size_t>(std::count(s.begin(), s.end(), c));
}

TEST(Kolams, SnakeIsTheBookProductionWithF) {
    Model m = example("fig6.2-snake-kolam.l");
    EXPECT_EQ(m.lsystem.derivationLength, 4);
    std::string book = expand("f+Xf+f+Xf", {{'X', "Xf-f-f+Xf+f+Xf-f-f+X"}}, 4);
    std::string got = derivedString(m, 4);
    EXPECT_EQ(got, book);
    EXPECT_EQ(count(got, 'F'), 0u);
    EXPECT_EQ(count(got, 'f'), 1364u);  // as tests/expected_examples.json counts the moves
    EXPECT_EQ(got.substr(0, 23), "f+Xf-f-f+Xf+f+Xf-f-f+Xf");
}

TEST(Kolams, AnkletsOfKrishnaIsTheBookProductionWithF) {
    Model m = example("fig6.4-anklets-of-krishna.l");
    EXPECT_DOUBLE_EQ(m.view.turtle.angleDegrees, 45);
    std::string got = derivedString(m, 5);
    EXPECT_EQ(got, expand("-X--X", {{'X', "XfX--XfX"}}, 5));
    EXPECT_EQ(got.size(), 4779u);
    EXPECT_EQ(count(got, 'f'), 1364u);
}

TEST(Kolams, BagOfCandiesFollowsTheTableSchedule) {
    Model m = example("fig6.5-bag-of-candies.l");
    // n = 3: table 1 in the first n - 2 = 1 step, then table 2 twice.
    std::string book = expand("-X--X", {{'X', "XfX--XfX"}}, 1);
    book = expand(book,
                  {{'X', "BfA--BfA"},
                   {'A', "f++ffff--f---ffff++f++ffff--f"},
                   {'B', "f--ffff++f++ffff--f---ffff++f"}},
                  2);
    std::string got = derivedString(m, 3);
    EXPECT_EQ(got, book);
    EXPECT_EQ(count(got, 'F'), 0u);
    EXPECT_EQ(count(got, 'A') + count(got, 'B') + count(got, 'X'), 0u);
    EXPECT_EQ(got.substr(0, 33), "-f--ffff++f++ffff--f---ffff++fff+");
}

TEST(Kolams, MangoLeavesIsTheBookProduction) {
    Model m = example("fig6.6-mango-leaves.l");
    EXPECT_DOUBLE_EQ(m.view.turtle.angleDegrees, 60);
    std::string got = derivedString(m, 7);
    EXPECT_EQ(got,
              expand("A---A", {{'A', "f-F+Z+F-fA"}, {'Z', "F-FF-F--[-Z]F-FF-F--F-FF-F--"}}, 7));
    EXPECT_EQ(got.size(), 1265u);
}

// The positions of a 2D turtle over F/f/+/- (turning `delta` degrees, '+' left), starting at
// the origin heading up: the control points the book's B-spline goes through.
std::vector<Vec3> turtlePath(const std::string& s, double delta) {
    std::vector<Vec3> points{{0, 0, 0}};
    double heading = 90, x = 0, y = 0;
    for (char c : s) {
        if (c == '+') heading += delta;
        if (c == '-') heading -= delta;
        if (c == 'f' || c == 'F') {
            x += std::cos(heading * M_PI / 180);
            y += std::sin(heading * M_PI / 180);
            points.push_back({x, y, 0});
        }
    }
    return points;
}

TEST(Kolams, SplinePathRunsNearEveryPositionAndThroughTheWholePath) {
    Model m = example("fig6.2-snake-kolam.l");
    EXPECT_EQ(m.view.kolam.splineMode, SplineMode::Path);
    const int n = 2;
    ModuleString s = deriveWithQueries(m, n);
    // Without the path mode the f-only string draws nothing at all.
    EXPECT_TRUE(interpret(m, s).segments.empty());

    RenderRequest request;
    request.spline = 8;
    Scene scene = sceneForRender(m, s, request);
    std::vector<Vec3> controls = turtlePath(s.toString(m.lsystem.symbols), 90);
    ASSERT_EQ(controls.size(), 85u);
    ASSERT_EQ(scene.segments.size(), (controls.size() - 1) * 8);
    // One curve: every piece starts where the one before ends.
    for (std::size_t i = 1; i < scene.segments.size(); ++i)
        ASSERT_EQ(scene.segments[i].a, scene.segments[i - 1].b) << i;
    // Clamped: it starts and ends at the turtle's first and last positions.
    EXPECT_NEAR(scene.segments.front().a.x, controls.front().x, 1e-9);
    EXPECT_NEAR(scene.segments.back().b.y, controls.back().y, 1e-9);
    // It cuts every corner by at most 1/6 of the corner's diagonal (sqrt 2 / 6 = 0.236).
    for (const Vec3& c : controls) {
        double nearest = 1e9;
        for (const Segment& seg : scene.segments)
            nearest = std::min(nearest, std::hypot(seg.b.x - c.x, seg.b.y - c.y));
        EXPECT_LT(nearest, 0.25) << c;
    }
}

TEST(Kolams, DotsSitInTheLoops) {
    // Anklets after one step: -f--f--f--f, a square on its corner: one loop, one dot.
    Model m = example("fig6.4-anklets-of-krishna.l");
    ModuleString s = deriveWithQueries(m, 1);
    for (Symbol& c : s.rawSymbols())
        if (c == 'f') c = 'F';
    std::vector<Vec3> dots = kolamDots(interpret(m, s), 1);
    ASSERT_EQ(dots.size(), 1u);
    EXPECT_NEAR(dots[0].x, std::sqrt(0.5), 1e-9);
    EXPECT_NEAR(dots[0].y, 0, 1e-9);

    // A U-turn (half a loop) has a dot; a zigzag has none.
    Model u =
        graftal::testing::parseModel("Lsystem: 1\nangle factor: 4\naxiom: F-F-F+F+F\nendlsystem\n");
    dots = kolamDots(interpret(u, deriveWithQueries(u, 0)), 1);
    ASSERT_EQ(dots.size(), 2u);
    EXPECT_NEAR(dots[0].x, 0.5, 1e-9);
    EXPECT_NEAR(dots[0].y, 0.5, 1e-9);
    Model zig =
        graftal::testing::parseModel("Lsystem: 1\nangle factor: 4\naxiom: F-F+F-F+F\nendlsystem\n");
    EXPECT_TRUE(kolamDots(interpret(zig, deriveWithQueries(zig, 0)), 1).empty());

    // The snake's scene with its file's `kolam dots: on` carries them as discs.
    Model snake = example("fig6.2-snake-kolam.l");
    EXPECT_TRUE(snake.view.kolam.dots);
    Scene scene = sceneForRender(snake, deriveWithQueries(snake, 1), RenderRequest{});
    // After one step the path loops round seven cells of a 3 x 3 block (worked out on
    // squared paper: the first loop turns right round the cell (-1..0, 1..2)).
    ASSERT_EQ(scene.discs.size(), 7u);
    EXPECT_NEAR(scene.discs[0].centre.x, -0.5, 1e-9);
    EXPECT_NEAR(scene.discs[0].centre.y, 1.5, 1e-9);
}

// Share of pixels of a PNG that are not the white background.
double inkedShare(const std::filesystem::path& png) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) return -1;
    int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    long inked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const unsigned char* p = data + y * stride + 4 * x;
            if (p[0] < 200 || p[1] < 200 || p[2] < 200) ++inked;
        }
    cairo_surface_destroy(s);
    return static_cast<double>(inked) / (static_cast<double>(w) * h);
}

TEST(Kolams, EveryKolamDrawsAPicture) {
    TempDir t;
    for (const char* name : {"fig6.2-snake-kolam.l", "fig6.4-anklets-of-krishna.l",
                             "fig6.5-bag-of-candies.l", "fig6.6-mango-leaves.l"}) {
        SCOPED_TRACE(name);
        RenderRequest r;
        r.output = t.path() / "k.png";
        r.picture.width = r.picture.height = 200;
        RenderResult result = render(example(name), r);
        EXPECT_EQ(result.route, RenderRoute::LineArt);
        double share = inkedShare(r.output);
        EXPECT_GT(share, 0.03);
        EXPECT_LT(share, 0.9);
    }
}

}  // namespace
}  // namespace graftal
