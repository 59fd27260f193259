// Tilings (LSFP ch. 6.1): the example tilings cover their region with the tiles their
// substitution promises, without gaps or overlaps (the tiles' areas add up to the region's).
#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.hpp"

namespace graftal {
namespace {

Model example(const std::string& name) {
    return graftal::testing::loadExample(std::string(GRAFTAL_EXAMPLES_DIR) + "/" + name);
}

Scene drawn(const Model& m, int steps) {
    ModuleString s = deriveWithQueries(m, steps);
    return interpret(m, applyHomomorphism(m.lsystem, s));
}

double area(std::span<const Vec3> polygon) {
    double twice = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec3& a = polygon[i];
        const Vec3& b = polygon[(i + 1) % polygon.size()];
        twice += a.x * b.y - b.x * a.y;
    }
    return std::abs(twice) / 2;
}

double totalArea(const Scene& s) {
    double sum = 0;
    for (std::size_t k = 0; k < s.polygonCount(); ++k) sum += area(s.polygon(k));
    return sum;
}

TEST(Tilings, PenroseTrianglesMultiplyAsTheDecompositionSays) {
    Model m = example("fig6.1-penrose-rhombs.l");
    // A thin half-rhomb gives one thin and one thick, a thick one two thick and one thin:
    // (thin, thick) = (10, 0), (10, 10), (20, 30), (50, 80), (130, 210), (340, 550).
    const int totals[] = {10, 20, 50, 130, 340, 890};
    const double sun = 10 * 0.5 * std::sin(36 * M_PI / 180);  // ten 36-degree triangles
    for (int n = 0; n <= 5; ++n) {
        SCOPED_TRACE(n);
        Scene s = drawn(m, n);
        EXPECT_EQ(s.polygonCount(), static_cast<std::size_t>(totals[n]));
        // Parameters are stored as 32-bit floats (as cpfg does): lengths carry a relative
        // error of about 1e-7, so areas and bounds are checked to 1e-6.
        EXPECT_NEAR(totalArea(s), sun, 1e-6);
        Bounds b = s.bounds();
        EXPECT_LE(std::max({-b.min.x, -b.min.y, b.max.x, b.max.y}), 1 + 1e-6);
    }
    // Thin halves are rose (3), thick ones blue (6): after 5 steps 340 and 550.
    Scene s = drawn(m, 5);
    int rose = 0, blue = 0;
    for (auto c : s.polygonColor) {
        if (c == 3) ++rose;
        if (c == 6) ++blue;
    }
    EXPECT_EQ(rose, 340);
    EXPECT_EQ(blue, 550);
}

TEST(Tilings, ChairsQuadrupleAndFillTheFirstChair) {
    Model m = example("fig6.1-chair-tiling.l");
    for (int n = 0; n <= 4; ++n) {
        SCOPED_TRACE(n);
        Scene s = drawn(m, n);
        EXPECT_EQ(s.polygonCount(), static_cast<std::size_t>(1) << (2 * n));
        EXPECT_NEAR(totalArea(s), 3 * 8 * 8, 1e-9);  // three cells of side 8
    }
}

TEST(Tilings, HexagonsGrowInRingsAndNeighboursDiffer) {
    Model m = example("fig6.1a-hexagonal-tiling.l");
    const double hexagon = 3 * std::sqrt(3.0) / 2;
    for (int n = 0; n <= 6; ++n) {
        SCOPED_TRACE(n);
        Scene s = drawn(m, n);
        const std::size_t count = 1 + 3 * static_cast<std::size_t>(n + 1) * (n + 2);
        ASSERT_EQ(s.polygonCount(), count);
        EXPECT_NEAR(totalArea(s), count * hexagon, 1e-6);
        // Centres one lattice step apart (sqrt 3) are neighbours: never the same colour,
        // and no two hexagons share a centre.
        std::vector<Vec3> centres;
        for (std::size_t k = 0; k < count; ++k) {
            Vec3 c{0, 0, 0};
            for (const Vec3& p : s.polygon(k)) c = c + p;
            centres.push_back(c * (1.0 / static_cast<double>(s.polygon(k).size())));
        }
        for (std::size_t i = 0; i < count; ++i)
            for (std::size_t j = i + 1; j < count; ++j) {
                double d = std::hypot(centres[i].x - centres[j].x, centres[i].y - centres[j].y);
                EXPECT_GT(d, 1.7) << i << " " << j;
                if (d < 1.8) {
                    EXPECT_NE(s.polygonColor[i], s.polygonColor[j]) << i << " " << j;
                }
            }
    }
}

}  // namespace
}  // namespace graftal
