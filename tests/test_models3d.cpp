// The 3D example models of examples/: every one derives to a 3D scene that meshes;
// tropism bends the plants of Fig 3.5 as the caption says (e_b > e_a > 0 > e_c, T up);
// the 3D flower field holds 16 different plants on a 4 x 4 grid; a ray-traced picture
// of the SIGGRAPH bush shows the plant inside the frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/graftal.hpp"
#include "graftal/output/render3d.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parseModel;
namespace fs = std::filesystem;

namespace {

Model example3d(const std::string& name) {
    return loadExample(fs::path(GRAFTAL_EXAMPLES_DIR) / name);
}

Scene sceneOf(const Model& ls) {
    return interpret(ls, applyHomomorphism(ls.lsystem, derive(ls)));
}

Scene sceneOf(const std::string& name) {
    return sceneOf(example3d(name));
}

const std::vector<std::string> kExamples3d = {
    "fig2.13-paper-tape-koch.l",
    "fig3.3-fibonacci-bush.l",
    "fig3.4-plant.l",
    "fig3.5a-tropism.l",
    "fig3.5b-tropism.l",
    "fig3.5c-tropism.l",
    "siggraph-fig7-bush.l",
    "siggraph-fig8-without-tropism.l",
    "siggraph-fig8-with-tropism.l",
    "fig3.17-flower-field-3d.l",
    "fig3.8-fern-3d.l",
    "fig3.9-lychnis-3d.l",
    "fig3.10-capsella-3d.l",
    "fig4.1-generic-plant.l",
    "sec4.2-growing-leaf.l",
    "fig4.5-cordate-leaf.l",
    "viewer-bush.l",
    "viewer-herb.l",
    "viewer-bracketed-f.l",
    "viewer-bracketed-x.l",
    "viewer-plant.l",
};

// Mean unit direction of the segments that end no higher order (the twigs: every
// segment no later segment continues), and the highest point of the plant.
struct Shape {
    double meanTipHeadingY = 0;
    double topY = -1e300;
};

Shape shapeOf(const Scene& s) {
    std::vector<bool> continued(s.segments.size(), false);
    for (const Segment& seg : s.segments)
        if (seg.previous != kNoSegment && seg.previous < continued.size())
            continued[seg.previous] = true;
    Shape out;
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < s.segments.size(); ++i) {
        const Segment& seg = s.segments[i];
        out.topY = std::max({out.topY, seg.a.y, seg.b.y});
        if (continued[i]) continue;
        double dx = seg.b.x - seg.a.x, dy = seg.b.y - seg.a.y, dz = seg.b.z - seg.a.z;
        double len = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (len == 0) continue;
        sum += dy / len;
        ++n;
    }
    out.meanTipHeadingY = n ? sum / n : 0;
    return out;
}

}  // namespace

TEST(Models3d, EveryExampleIs3DAndMeshes) {
    SurfaceLibrary lib = SurfaceLibrary::builtin();
    for (const std::string& name : kExamples3d) {
        SCOPED_TRACE(name);
        Model ls = example3d(name);
        Scene scene = sceneOf(ls);
        EXPECT_TRUE(scene.is3D);
        EXPECT_LT(scene.segments.size(), 1000000u);
        Mesh mesh = buildMesh(scene, {}, &lib);
        EXPECT_GT(mesh.triangleCount(), 0u);
        EXPECT_FALSE(mesh.positions.empty());
    }
}

TEST(Models3d, TropismBendsAsInFig35) {
    Shape a = shapeOf(sceneOf("fig3.5a-tropism.l"));
    Shape b = shapeOf(sceneOf("fig3.5b-tropism.l"));
    Shape c = shapeOf(sceneOf("fig3.5c-tropism.l"));
    // The same plant without tropism, for reference.
    Model none = example3d("fig3.5a-tropism.l");
    none.view.turtle.elasticity = 0;
    Shape zero = shapeOf(sceneOf(none));
    // T points up: e_b > e_a > 0 bend the twigs up, b more than a; e_c < 0 bends them down.
    EXPECT_GT(b.meanTipHeadingY, a.meanTipHeadingY + 0.05);
    EXPECT_GT(a.meanTipHeadingY, zero.meanTipHeadingY + 0.05);
    EXPECT_LT(c.meanTipHeadingY, zero.meanTipHeadingY - 0.05);
    EXPECT_GT(b.topY, a.topY);
    EXPECT_GT(a.topY, c.topY);
}

TEST(Models3d, SiggraphFig8TropismBendsDown) {
    Shape without = shapeOf(sceneOf("siggraph-fig8-without-tropism.l"));
    Shape with = shapeOf(sceneOf("siggraph-fig8-with-tropism.l"));
    EXPECT_LT(with.meanTipHeadingY, without.meanTipHeadingY - 0.05);
}

TEST(Models3d, FlowerFieldHasSixteenDifferentPlants) {
    Scene s = sceneOf("fig3.17-flower-field-3d.l");
    // Plants start on the ground plane y = 0 at the grid points: the stems that start
    // at y = 0 (segments no earlier segment continues).
    std::set<std::pair<long, long>> roots;
    for (const Segment& seg : s.segments)
        if (seg.previous == kNoSegment && std::fabs(seg.a.y) < 1e-6 && seg.b.y > seg.a.y)
            roots.insert({std::lround(seg.a.x), std::lround(seg.a.z)});
    ASSERT_EQ(roots.size(), 16u);
    std::set<long> xs, zs;
    for (auto [x, z] : roots) xs.insert(x), zs.insert(z);
    EXPECT_EQ(xs.size(), 4u);
    EXPECT_EQ(zs.size(), 4u);

    // The plants differ: count the segments of each plant (nearest grid point).
    std::vector<std::pair<long, long>> grid(roots.begin(), roots.end());
    std::vector<int> count(grid.size(), 0);
    for (const Segment& seg : s.segments) {
        std::size_t best = 0;
        double bd = 1e300;
        for (std::size_t k = 0; k < grid.size(); ++k) {
            double dx = seg.a.x - static_cast<double>(grid[k].first);
            double dz = seg.a.z - static_cast<double>(grid[k].second);
            double d = dx * dx + dz * dz;
            if (d < bd) bd = d, best = k;
        }
        ++count[best];
    }
    std::set<int> distinct(count.begin(), count.end());
    EXPECT_GE(distinct.size(), 4u) << "the 16 plants should not all be alike";
}

TEST(Models3d, CordateLeafUsesDeclaredEdgeMarkers) {
    Model ls = example3d("fig4.5-cordate-leaf.l");
    EXPECT_GE(ls.lsystem.symbols.find("E1"), 0);
    EXPECT_GE(ls.lsystem.symbols.find("E2"), 0);
    Scene s = sceneOf(ls);
    EXPECT_EQ(s.polygonCount(), 10u);  // two halves for each of five leaves
}

TEST(Models3d, BushRenderIsInsideTheFrame) {
    SurfaceLibrary lib = SurfaceLibrary::builtin();
    Mesh mesh = buildMesh(sceneOf("siggraph-fig7-bush.l"), {}, &lib);
    RaytraceOptions o;
    o.width = o.height = 200;
    o.samplesPerPixel = 1;
    std::vector<unsigned char> px = renderRaytracedPixels(mesh, o);
    ASSERT_EQ(px.size(), 200u * 200u * 3u);
    auto isPlant = [&](int x, int y) {
        const unsigned char* p =
            &px[(static_cast<std::size_t>(y) * 200 + static_cast<std::size_t>(x)) * 3];
        return p[0] < 240 || p[1] < 240 || p[2] < 240;  // background is white
    };
    int inside = 0, border = 0;
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) {
            if (!isPlant(x, y)) continue;
            if (x == 0 || y == 0 || x == 199 || y == 199)
                ++border;
            else
                ++inside;
        }
    EXPECT_GT(inside, 200 * 200 / 50);  // the plant covers a good part of the picture
    EXPECT_EQ(border, 0);               // and does not touch the frame
}
