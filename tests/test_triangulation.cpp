// triangulatePolygon: concave outlines, collinear and repeated vertices, both windings,
// outlines in 3D. A triangulation is right when it has n - 2 triangles, they all face the
// same way, their areas add up to the polygon's and none of them pokes outside.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "graftal/core/vec3.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/graftal.hpp"

namespace {

using graftal::triangulatePolygon;
using graftal::Vec3;

struct P2 {
    double x, y;
};

// The mesher's own vector arithmetic (a private header): these tests are about triangles.

// Twice the vector area of the triangle a, b, c.
Vec3 doubleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
    return cross(Vec3(b) - Vec3(a), Vec3(c) - Vec3(a));
}

// Twice the vector area of an outline: its length is twice the area of a planar outline,
// its direction the normal the outline winds counter-clockwise around.
Vec3 newell(const std::vector<Vec3>& v) {
    Vec3 n;
    for (std::size_t i = 0; i < v.size(); ++i)
        n = n + cross(Vec3(v[i]), Vec3(v[(i + 1) % v.size()]));
    return n;
}

// Even-odd rule; the points tested are strictly inside triangles, never on the outline.
bool inside(const std::vector<P2>& poly, P2 p) {
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const P2 a = poly[i], b = poly[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            in = !in;
    }
    return in;
}

// Places a 2D outline in 3D: rotated about a tilted axis and moved away from the origin, so
// that the triangulator cannot rely on the outline lying in z = 0.
std::vector<Vec3> placed(const std::vector<P2>& outline, bool rotate) {
    std::vector<Vec3> out;
    const double a = 0.7, b = -1.1;  // rotations about x, then z
    for (const P2& p : outline) {
        Vec3 v{p.x, p.y, 0};
        if (rotate) {
            v = {v.x, v.y * std::cos(a) - v.z * std::sin(a), v.y * std::sin(a) + v.z * std::cos(a)};
            v = {v.x * std::cos(b) - v.y * std::sin(b), v.x * std::sin(b) + v.y * std::cos(b), v.z};
            v = {v.x + 10, v.y - 3, v.z + 7};
        }
        out.push_back(v);
    }
    return out;
}

// Checks everything a user would about the triangulation of `outline` (distinct vertices)
// and returns the triangles.
std::vector<std::uint32_t> checkTriangulation(const std::vector<P2>& outline, bool rotate) {
    const std::vector<Vec3> v = placed(outline, rotate);
    const std::vector<std::uint32_t> t = triangulatePolygon(v);
    EXPECT_EQ(t.size(), 3 * (outline.size() - 2));
    const Vec3 n = newell(v);
    const double polygonArea = length(n) / 2;
    const Vec3 unit = (1 / length(n)) * n;
    double sum = 0;
    for (std::size_t k = 0; k + 2 < t.size(); k += 3) {
        for (int i = 0; i < 3; ++i) EXPECT_LT(t[k + i], v.size());
        if (t[k] >= v.size() || t[k + 1] >= v.size() || t[k + 2] >= v.size()) continue;
        const double signedArea = dot(doubleArea(v[t[k]], v[t[k + 1]], v[t[k + 2]]), unit) / 2;
        // Every triangle winds the way the outline does, and none is a sliver of nothing.
        EXPECT_GT(signedArea, 1e-9 * polygonArea) << "triangle " << k / 3;
        sum += signedArea;
        const P2 a = outline[t[k]], b = outline[t[k + 1]], c2 = outline[t[k + 2]];
        for (auto [wa, wb, wc] : {std::array{1.0 / 3, 1.0 / 3, 1.0 / 3}, std::array{0.8, 0.1, 0.1},
                                  std::array{0.1, 0.8, 0.1}, std::array{0.1, 0.1, 0.8}}) {
            const P2 p{wa * a.x + wb * b.x + wc * c2.x, wa * a.y + wb * b.y + wc * c2.y};
            EXPECT_TRUE(inside(outline, p)) << "triangle " << k / 3 << " leaves the outline near ("
                                            << p.x << ", " << p.y << ")";
        }
    }
    EXPECT_NEAR(sum, polygonArea, 1e-9 * polygonArea);
    return t;
}

std::vector<P2> reversed(std::vector<P2> v) {
    std::reverse(v.begin(), v.end());
    return v;
}

const std::vector<P2> kLShape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};

std::vector<P2> star(int points, double outer, double inner) {
    std::vector<P2> v;
    for (int i = 0; i < 2 * points; ++i) {
        const double r = i % 2 ? inner : outer;
        const double a = std::numbers::pi * i / points;
        v.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return v;
}

// A comb: a spine along the bottom with `teeth` narrow teeth standing on it.
std::vector<P2> comb(int teeth) {
    std::vector<P2> v = {{0, 0}, {2.0 * teeth - 1, 0}};
    for (int i = teeth - 1; i >= 0; --i) {
        v.push_back({2.0 * i + 1, 5});
        v.push_back({2.0 * i, 5});
        if (i > 0) {
            v.push_back({2.0 * i, 1});
            v.push_back({2.0 * i - 1, 1});
        }
    }
    return v;
}

TEST(Triangulation, Triangle) {
    EXPECT_EQ(triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}),
              (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(Triangulation, ConvexSquare) {
    checkTriangulation({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, false);
}

TEST(Triangulation, LShape) {
    checkTriangulation(kLShape, false);
    checkTriangulation(kLShape, true);
}

TEST(Triangulation, Star) {
    checkTriangulation(star(5, 2, 0.7), false);
    checkTriangulation(star(12, 3, 1), true);
}

TEST(Triangulation, Comb) {
    checkTriangulation(comb(2), false);
    checkTriangulation(comb(7), true);
}

TEST(Triangulation, ClockwiseOutlinesFaceTheOtherWay) {
    for (const auto& outline : {kLShape, star(5, 2, 0.7), comb(4)}) {
        checkTriangulation(reversed(outline), false);
        checkTriangulation(reversed(outline), true);
    }
    // In z = 0, a clockwise outline's triangles are clockwise too: they face -z.
    const auto t = triangulatePolygon(placed(reversed(kLShape), false));
    const auto v = placed(reversed(kLShape), false);
    ASSERT_EQ(t.size(), 12u);
    EXPECT_LT(doubleArea(v[t[0]], v[t[1]], v[t[2]]).z, 0);
}

TEST(Triangulation, CollinearVerticesAreKeptWithoutSlivers) {
    // A square with a vertex in the middle of every side, and one with a whole row of
    // vertices along one side: n - 2 triangles, none of them flat.
    checkTriangulation({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}, false);
    checkTriangulation({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {4, 1}, {0, 1}}, true);
    // An L with collinear vertices along its inner corner's sides.
    checkTriangulation(
        {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1.5, 1}, {1, 1}, {1, 2}, {1, 3}, {0, 3}, {0, 1.5}},
        false);
}

TEST(Triangulation, RepeatedVerticesCountOnce) {
    // The first vertex repeated at the end (a closed outline) and a vertex doubled in the
    // middle: the triangles use the distinct ones.
    std::vector<Vec3> v = placed(kLShape, true);
    v.insert(v.begin() + 3, v[3]);
    v.push_back(v.front());
    const auto t = triangulatePolygon(v);
    ASSERT_EQ(t.size(), 3u * 4);
    double sum = 0;
    for (std::size_t k = 0; k < t.size(); k += 3) {
        ASSERT_LT(t[k + 2], v.size());
        sum += length(doubleArea(v[t[k]], v[t[k + 1]], v[t[k + 2]])) / 2;
    }
    EXPECT_NEAR(sum, 4.0, 1e-9);  // the L covers four unit squares
}

TEST(Triangulation, OutlineTouchingItselfAtAVertex) {
    // Two squares meeting at the corner (1, 1), drawn as one outline that passes through
    // that corner twice.
    const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0},
                                 {2, 2, 0}, {1, 2, 0}, {1, 1, 0}, {0, 1, 0}};
    const auto t = triangulatePolygon(v);
    ASSERT_EQ(t.size(), 3u * 6);
    double sum = 0;
    for (std::size_t k = 0; k < t.size(); k += 3)
        sum += doubleArea(v[t[k]], v[t[k + 1]], v[t[k + 2]]).z / 2;
    EXPECT_NEAR(sum, 2.0, 1e-12);
}

TEST(Triangulation, SlightlyNonPlanarOutline) {
    // A leaf whose outline bends a little out of its plane still triangulates completely.
    std::vector<P2> outline = star(6, 2, 1.2);
    std::vector<Vec3> v = placed(outline, false);
    for (std::size_t i = 0; i < v.size(); ++i) v[i].z = 0.05 * std::sin(3.0 * i);
    EXPECT_EQ(triangulatePolygon(v).size(), 3 * (v.size() - 2));
}

TEST(Triangulation, RandomStarShapedOutlines) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> radius(0.2, 3);
    for (int trial = 0; trial < 50; ++trial) {
        const int n = 5 + trial * 4;
        std::vector<P2> outline;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * std::numbers::pi * i / n, r = radius(rng);
            outline.push_back({r * std::cos(a), r * std::sin(a)});
        }
        checkTriangulation(outline, trial % 2 == 1);
        if (::testing::Test::HasFailure()) {
            ADD_FAILURE() << "trial " << trial;
            break;
        }
    }
}

TEST(Triangulation, DegenerateOutlinesGiveNothing) {
    EXPECT_TRUE(triangulatePolygon({}).empty());
    EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}}).empty());
    EXPECT_TRUE(triangulatePolygon({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}).empty());
    EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}}).empty());
    // All on one line.
    EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}).empty());
    EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {NAN, 1, 0}}).empty());
}

}  // namespace
