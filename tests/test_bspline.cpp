// B-spline smoothing of turtle paths (Figures 2.10 and 2.11 of the book).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "graftal/geometry/bspline.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parse;
using graftal::testing::parseModel;

namespace {

void expectNear(const Vec3& a, const Vec3& b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

// Segments a0 -> a1 -> ... in one 2D chain, without `previous` (as the 2D turtle draws).
Scene path(const std::vector<Vec3>& points) {
    Scene s;
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
        s.segments.push_back({points[i], points[i + 1]});
    return s;
}

// Every piece starts where the one before it ended.
void expectConnected(const Scene& s) {
    for (std::size_t i = 1; i < s.segments.size(); ++i)
        EXPECT_EQ(s.segments[i].a, s.segments[i - 1].b) << "piece " << i;
}

bool insideUnitSquare(const Vec3& p) {
    const double eps = 1e-12;
    return p.x >= -eps && p.x <= 1 + eps && p.y >= -eps && p.y <= 1 + eps && std::abs(p.z) <= eps;
}

Scene draw(const std::string& text, int steps) {
    Model ls = parseModel(text);
    return interpret(ls, derive(ls, steps));
}

}  // namespace

TEST(BSplineCurve, StraightControlPolygonStaysOnTheLine) {
    // Unevenly spaced points on one line through 3D.
    std::vector<Vec3> cps;
    for (double u : {0.0, 0.3, 1.0, 1.2, 2.5, 4.0}) cps.push_back({1 + u, 2 - 2 * u, 0.5 * u});
    std::vector<Vec3> curve = bsplineCurve(cps, 7);
    ASSERT_EQ(curve.size(), 5u * 7 + 1);
    for (const Vec3& p : curve) {
        double u = p.x - 1;
        expectNear(p, {1 + u, 2 - 2 * u, 0.5 * u}, 1e-12);
        EXPECT_GE(u, -1e-12);
        EXPECT_LE(u, 4 + 1e-12);
    }
}

TEST(BSplineCurve, EndsAreTheFirstAndLastControlPoints) {
    std::vector<Vec3> cps{{0.1, 0.2, 0}, {1, 3, 0}, {2, -1, 1}, {4, 0.5, 2}};
    std::vector<Vec3> curve = bsplineCurve(cps, 5);
    EXPECT_EQ(curve.front(), cps.front());
    EXPECT_EQ(curve.back(), cps.back());
    // Tangent to the control polygon at the ends.
    Vec3 d{curve[1].x - curve[0].x, curve[1].y - curve[0].y, curve[1].z - curve[0].z};
    Vec3 e{cps[1].x - cps[0].x, cps[1].y - cps[0].y, cps[1].z - cps[0].z};
    double crossLength =
        std::hypot(d.y * e.z - d.z * e.y, d.z * e.x - d.x * e.z, d.x * e.y - d.y * e.x);
    EXPECT_LT(crossLength / (std::hypot(d.x, d.y, d.z) * std::hypot(e.x, e.y, e.z)), 0.05);
}

TEST(BSplineCurve, InteriorKnotsAreTheUniformBSplinePoints) {
    std::vector<Vec3> cps{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<Vec3> curve = bsplineCurve(cps, 4);
    // At the knot of P1: (P0 + 4 P1 + P2) / 6.
    expectNear(curve[4], {5.0 / 6, 1.0 / 6, 0});
    expectNear(curve[8], {5.0 / 6, 5.0 / 6, 0});
}

TEST(BSplineCurve, SquareStaysInsideItsHull) {
    std::vector<Vec3> open{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
    for (const Vec3& p : bsplineCurve(open, 16)) EXPECT_TRUE(insideUnitSquare(p)) << p;
    std::vector<Vec3> loop{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<Vec3> closed = bsplineCurve(loop, 16, true);
    ASSERT_EQ(closed.size(), 4u * 16 + 1);
    EXPECT_EQ(closed.front(), closed.back());
    for (const Vec3& p : closed) EXPECT_TRUE(insideUnitSquare(p)) << p;
    // The closed curve cuts the corners: it never reaches one.
    for (const Vec3& p : closed) EXPECT_GT(std::hypot(p.x, p.y), 0.1);
}

TEST(BSplineCurve, DegenerateInputs) {
    EXPECT_TRUE(bsplineCurve({}, 4).empty());
    std::vector<Vec3> one{{1, 2, 3}};
    EXPECT_EQ(bsplineCurve(one, 4), one);
    std::vector<Vec3> two{{0, 0, 0}, {2, 0, 0}};
    std::vector<Vec3> line = bsplineCurve(two, 4);
    ASSERT_EQ(line.size(), 5u);
    for (std::size_t i = 0; i < line.size(); ++i) expectNear(line[i], {0.5 * i, 0, 0});
    EXPECT_THROW(bsplineCurve(two, 0), Error);
}

TEST(SmoothSegments, CountsAndEndsOfAnOpenChain) {
    Scene s = path({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}, {2, 3, 0}});
    Scene smooth = smoothSegments(s, 6);
    ASSERT_EQ(smooth.segments.size(), 4u * 6);
    EXPECT_EQ(smooth.segments.front().a, (Vec3{0, 0, 0}));
    EXPECT_EQ(smooth.segments.back().b, (Vec3{2, 3, 0}));
    expectConnected(smooth);
}

TEST(SmoothSegments, StraightChainStaysOnTheLine) {
    Scene s = path({{0, 0, 0}, {0, 1, 0}, {0, 3, 0}, {0, 3.5, 0}});
    Scene smooth = smoothSegments(s, 5);
    ASSERT_EQ(smooth.segments.size(), 15u);
    for (const Segment& seg : smooth.segments) {
        EXPECT_NEAR(seg.a.x, 0, 1e-12);
        EXPECT_NEAR(seg.b.x, 0, 1e-12);
        EXPECT_LE(seg.a.y, seg.b.y);  // monotone: no overshoot at the ends
    }
}

TEST(SmoothSegments, ClosedSquareClampedAndPeriodic) {
    Scene square = path({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}});
    Scene clamped = smoothSegments(square, 8);
    ASSERT_EQ(clamped.segments.size(), 32u);
    EXPECT_EQ(clamped.segments.front().a, (Vec3{0, 0, 0}));
    EXPECT_EQ(clamped.segments.back().b, (Vec3{0, 0, 0}));
    for (const Segment& seg : clamped.segments) {
        EXPECT_TRUE(insideUnitSquare(seg.a)) << seg.a;
        EXPECT_TRUE(insideUnitSquare(seg.b)) << seg.b;
    }
    expectConnected(clamped);

    Scene periodic = smoothSegments(square, 8, ClosedChains::Periodic);
    ASSERT_EQ(periodic.segments.size(), 32u);
    EXPECT_EQ(periodic.segments.front().a, periodic.segments.back().b);
    for (const Segment& seg : periodic.segments) EXPECT_TRUE(insideUnitSquare(seg.a));
    expectNear(periodic.segments.front().a, {1.0 / 6, 1.0 / 6, 0});
    expectConnected(periodic);
}

TEST(SmoothSegments, PiecesKeepWidthColourAndUp) {
    Scene s = path({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
    s.segments[0].width = 3;
    s.segments[0].color = 2;
    s.segments[1].width = 0.5f;
    s.segments[1].color = 5;
    s.segments[1].up = {1, 0, 0};
    s.addPolygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 4);
    Scene smooth = smoothSegments(s, 3);
    ASSERT_EQ(smooth.segments.size(), 6u);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(smooth.segments[k].width, 3);
        EXPECT_EQ(smooth.segments[k].color, 2);
        EXPECT_EQ(smooth.segments[3 + k].width, 0.5f);
        EXPECT_EQ(smooth.segments[3 + k].color, 5);
        EXPECT_EQ(smooth.segments[3 + k].up, (Vec3{1, 0, 0}));
    }
    EXPECT_EQ(smooth.polygonCount(), 1u);
    EXPECT_EQ(smooth.polygonColor, s.polygonColor);
}

TEST(SmoothSegments, PreviousLinksFollowThePieces) {
    // A 3D axis with `previous` set, and a branch off its second segment.
    Scene s;
    s.segments.push_back({{0, 0, 0}, {0, 1, 0}});
    s.segments.push_back({{0, 1, 0}, {0, 2, 0.5}, 1, 0, 0});
    s.segments.push_back({{0, 2, 0.5}, {1, 3, 0.5}, 1, 0, 1});  // branch
    s.segments.push_back({{0, 2, 0.5}, {0, 3, 0.5}, 1, 0, 1});  // main axis, after it
    Scene smooth = smoothSegments(s, 4);
    ASSERT_EQ(smooth.segments.size(), 16u);
    EXPECT_EQ(smooth.segments[0].previous, kNoSegment);
    for (std::size_t i = 0; i < 16; ++i) {
        if (i % 4 == 0) continue;  // first pieces: checked below
        EXPECT_EQ(smooth.segments[i].previous, i - 1) << i;
    }
    EXPECT_EQ(smooth.segments[4].previous, 3u);
    EXPECT_EQ(smooth.segments[8].previous, 7u);
    EXPECT_EQ(smooth.segments[12].previous, 7u);

    // The main axis (segments 0, 1, 3) is one smooth chain: it runs on from segment 1
    // straight into segment 3; the branch starts where the smoothed axis passes.
    EXPECT_EQ(smooth.segments[12].a, smooth.segments[7].b);
    EXPECT_EQ(smooth.segments[8].a, smooth.segments[7].b);
    EXPECT_NE(smooth.segments[7].b, (Vec3{0, 2, 0.5}));  // the knot moved onto the curve
    EXPECT_EQ(smooth.segments[15].b, (Vec3{0, 3, 0.5}));
    EXPECT_EQ(smooth.segments[11].b, (Vec3{1, 3, 0.5}));
}

TEST(SmoothSegments, TwoDimensionalBranchesStayAttached) {
    // F[+F]-F drawn in 2D: the F after the bracket continues the axis, which bends there,
    // so the smoothed axis passes beside the turtle's branch point.
    Scene s = draw("Lsystem: 1\nangle increment: 45\naxiom: F[+F]-F\nendlsystem\n", 0);
    ASSERT_EQ(s.segments.size(), 3u);
    Scene smooth = smoothSegments(s, 5);
    ASSERT_EQ(smooth.segments.size(), 15u);
    const Vec3& joint = smooth.segments[4].b;
    EXPECT_GT(std::hypot(joint.x - s.segments[0].b.x, joint.y - s.segments[0].b.y), 0.01);
    EXPECT_EQ(smooth.segments[5].a, joint);   // the branch
    EXPECT_EQ(smooth.segments[10].a, joint);  // the axis continues
    EXPECT_EQ(smooth.segments.front().a, s.segments.front().a);
    EXPECT_EQ(smooth.segments[9].b, s.segments[1].b);
    EXPECT_EQ(smooth.segments.back().b, s.segments.back().b);
}

TEST(SmoothSegments, SeparateChainsStaySeparate) {
    Scene s = path({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
    s.segments.push_back({{5, 5, 0}, {6, 5, 0}});  // after a move: a chain of its own
    Scene smooth = smoothSegments(s, 2);
    ASSERT_EQ(smooth.segments.size(), 6u);
    EXPECT_EQ(smooth.segments[3].b, (Vec3{1, 1, 0}));
    EXPECT_EQ(smooth.segments[4].a, (Vec3{5, 5, 0}));
    expectNear(smooth.segments[4].b, {5.5, 5, 0});
    EXPECT_EQ(smooth.segments[5].b, (Vec3{6, 5, 0}));
}

TEST(SmoothSegments, KochIslandFromTheTurtle) {
    Scene s = draw(
        "Lsystem: 1\nangle factor: 4\naxiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\n"
        "endlsystem\n",
        1);
    ASSERT_EQ(s.segments.size(), 32u);
    Scene clamped = smoothSegments(s, 4);
    ASSERT_EQ(clamped.segments.size(), 128u);
    EXPECT_EQ(clamped.segments.front().a, s.segments.front().a);
    EXPECT_EQ(clamped.segments.back().b, s.segments.back().b);
    expectConnected(clamped);

    // Periodic: the island closes smoothly; its bounds shrink inside the original's.
    Scene periodic = smoothSegments(s, 4, ClosedChains::Periodic);
    ASSERT_EQ(periodic.segments.size(), 128u);
    expectConnected(periodic);
    EXPECT_EQ(periodic.segments.front().a, periodic.segments.back().b);
    Bounds before = s.bounds(), after = periodic.bounds();
    EXPECT_GE(after.min.x, before.min.x - 1e-9);
    EXPECT_LE(after.max.x, before.max.x + 1e-9);
    EXPECT_LT(after.max.x - after.min.x, before.max.x - before.min.x);
}

TEST(SmoothSegments, EmptySceneAndBadSubdivisions) {
    Scene empty;
    EXPECT_TRUE(smoothSegments(empty, 4).segments.empty());
    Scene s = path({{0, 0, 0}, {1, 0, 0}});
    EXPECT_THROW(smoothSegments(s, 0), Error);
    EXPECT_THROW(smoothSegments(s, -3), Error);
    // One subdivision keeps the segment count: a straight single segment is unchanged.
    Scene one = smoothSegments(s, 1);
    ASSERT_EQ(one.segments.size(), 1u);
    EXPECT_EQ(one.segments[0].a, (Vec3{0, 0, 0}));
    EXPECT_EQ(one.segments[0].b, (Vec3{1, 0, 0}));
}
