// The ray tracer on instanced scenes (MeshScenes built by hand: a prototype placed by
// transforms, curves), its framing and its light: instanced and flattened scenes give the
// same picture, curves show the stems tubes would, the scene fills the frame, the ground
// takes the plant's shadow, and the threads never change a pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/render3d.hpp"

namespace graftal {
namespace {

constexpr Rgb kGreen{0.2f, 0.6f, 0.2f};
constexpr Rgb kBrown{0.45f, 0.3f, 0.15f};

// A leaf-like prototype: a flat diamond in its own xy plane, tip at +y, both sides facing
// +z (the normals), two triangles.
Mesh leaf() {
    Mesh m;
    m.palette = {kGreen, kBrown};
    m.positions = {{0, 0, 0}, {0.3f, 0.5f, 0}, {0, 1, 0}, {-0.3f, 0.5f, 0}};
    m.normals.assign(4, Vec3f{0, 0, 1});
    m.indices = {0, 1, 2, 0, 2, 3};
    m.triangleColor = {0, 0};
    return m;
}

// The transform rotating by `degrees` about y, scaling by s, then moving by t; mirrored
// in x when asked.
Affine3f placement(double degrees, float s, Vec3f t, bool mirrored = false) {
    const double a = degrees * 3.14159265358979 / 180;
    const float c = static_cast<float>(std::cos(a)) * s, n = static_cast<float>(std::sin(a)) * s;
    Affine3f f;
    f.columns[0] = {mirrored ? -c : c, 0, mirrored ? n : -n};
    f.columns[1] = {0, s, 0};
    f.columns[2] = {n, 0, c};
    f.columns[3] = t;
    return f;
}

// A plant of 60 leaves on a spiral around a stem (a box in the mesh), some mirrored.
MeshScene leafyPlant() {
    MeshScene s;
    s.mesh.palette = {kGreen, kBrown};
    // The stem: a thin box from y = 0 to 4.
    const float h = 0.05f;
    const Vec3f lo{-h, 0, -h}, hi{h, 4, h};
    const Vec3f corners[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z},
                              {hi.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                              {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}};
    for (const Vec3f& c : corners) {
        s.mesh.positions.push_back(c);
        s.mesh.normals.push_back(c);  // any outward-ish direction; normalised by the tracer
    }
    const std::uint32_t faces[] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                   2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    s.mesh.indices.assign(std::begin(faces), std::end(faces));
    s.mesh.triangleColor.assign(12, 1);
    s.prototypes.push_back(leaf());
    for (int k = 0; k < 60; ++k) {
        const float y = 0.3f + 0.06f * k;
        const double turn = 137.5 * k;
        const double a = turn * 3.14159265358979 / 180;
        const Vec3f at{0.05f * static_cast<float>(std::cos(a)), y,
                       0.05f * static_cast<float>(-std::sin(a))};
        s.placements.push_back({0, placement(turn, 0.8f - 0.008f * k, at, k % 3 == 0)});
    }
    return s;
}

RaytraceOptions options(int width = 120, int height = 120) {
    RaytraceOptions o;
    o.width = width;
    o.height = height;
    o.samplesPerPixel = 4;
    o.threads = 2;
    return o;
}

struct Difference {
    int differing = 0;  // pixels with a channel off by more than the tolerance
    double meanAbsolute = 0;
};

Difference compare(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b,
                   int tolerance) {
    Difference d;
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); i += 3) {
        int worst = 0;
        for (int k = 0; k < 3; ++k) {
            const int e = std::abs(int(a[i + k]) - int(b[i + k]));
            worst = std::max(worst, e);
            sum += e;
        }
        if (worst > tolerance) ++d.differing;
    }
    d.meanAbsolute = sum / static_cast<double>(a.size());
    return d;
}

struct Box {
    int x0, y0, x1, y1;
};

Box drawnBox(const std::vector<unsigned char>& px, int width, int height, const Rgb& bg) {
    const int b[3] = {int(std::lround(bg.r * 255)), int(std::lround(bg.g * 255)),
                      int(std::lround(bg.b * 255))};
    Box box{width, height, -1, -1};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = &px[(std::size_t(y) * width + x) * 3];
            if (p[0] == b[0] && p[1] == b[1] && p[2] == b[2]) continue;
            box.x0 = std::min(box.x0, x);
            box.y0 = std::min(box.y0, y);
            box.x1 = std::max(box.x1, x);
            box.y1 = std::max(box.y1, y);
        }
    return box;
}

TEST(RaytraceInstances, InstancedAndFlattenedScenesGiveTheSamePicture) {
    const MeshScene instanced = leafyPlant();
    const MeshScene flat{instanced.flattened(), {}, {}, {}};
    // The same drawing, the same box.
    const Bounds a = instanced.bounds(), b = flat.bounds();
    EXPECT_NEAR(a.min.x, b.min.x, 1e-6);
    EXPECT_NEAR(a.max.y, b.max.y, 1e-6);
    EXPECT_NEAR(a.min.z, b.min.z, 1e-6);
    EXPECT_NEAR(a.max.z, b.max.z, 1e-6);

    const RaytraceOptions o = options(160, 160);
    const std::vector<unsigned char> one = renderRaytracedPixels(instanced, o);
    const std::vector<unsigned char> two = renderRaytracedPixels(flat, o);
    const Box box = drawnBox(one, o.width, o.height, o.background);
    ASSERT_LT(box.x0, box.x1) << "nothing drawn";
    // Embree intersects an instance in its own coordinates, so a ray grazing an edge may
    // round the other way: at most 0.5% of the pixels may differ by more than 8 levels,
    // and the mean difference stays under half a level.
    const Difference d = compare(one, two, 8);
    EXPECT_LE(d.differing, o.width * o.height / 200) << d.differing << " pixels differ";
    EXPECT_LT(d.meanAbsolute, 0.5);
}

TEST(RaytraceInstances, MirroredPlacementsAreLitLikeTheirFlattenedCopies) {
    MeshScene s;
    s.mesh.palette = {kGreen};
    s.prototypes.push_back(leaf());
    s.placements.push_back({0, placement(20, 2, {-1.2f, 0, 0})});
    s.placements.push_back({0, placement(20, 2, {1.2f, 0, 0}, true)});
    const MeshScene flat{s.flattened(), {}, {}, {}};
    RaytraceOptions o = options(100, 60);
    o.lighting.sunDirection = {0.3, 0.5, 1};
    const Difference d = compare(renderRaytracedPixels(s, o), renderRaytracedPixels(flat, o), 8);
    EXPECT_LE(d.differing, 30);
    EXPECT_LT(d.meanAbsolute, 0.5);
}

TEST(RaytraceInstances, APlacementOfAMissingPrototypeIsAnError) {
    MeshScene s;
    s.prototypes.push_back(leaf());
    s.placements.push_back({3, Affine3f{}});
    EXPECT_THROW(renderRaytracedPixels(s, options()), Error);
}

// A vertical stem from (0,0,0) to (0,4,0) of radius r, as one curve or as a square tube.
MeshScene curveStem(float r) {
    MeshScene s;
    s.mesh.palette = {kBrown};
    for (int k = 0; k < 4; ++k)
        s.curves.push_back({{0, float(k), 0}, {0, float(k + 1), 0}, r, r, 0});
    return s;
}

// The frame's box around the stem, so that curve and tube are seen from the same camera.
Camera stemCamera() {
    Camera c;
    c.viewpoint = Vec3{0, 2, 9};
    c.target = Vec3{0, 2, 0};
    return c;
}

TEST(RaytraceCurves, AThinCurveShowsTheStemAlongItsWholeLength) {
    // 0.001 units across is a twentieth of a pixel here: widened to a pixel, not lost.
    RaytraceOptions o = options(100, 100);
    o.camera = stemCamera();
    const std::vector<unsigned char> px = renderRaytracedPixels(curveStem(0.0005f), o);
    auto drawnInRow = [&](int y) {
        for (int x = 45; x <= 55; ++x) {
            const unsigned char* p = &px[(std::size_t(y) * o.width + x) * 3];
            if (p[0] < 250 || p[1] < 250 || p[2] < 250) return true;
        }
        return false;
    };
    // The stem runs from y = 0 to 4, i.e. rows ~ 26 to 74 of the picture.
    for (int y = 30; y <= 70; ++y) EXPECT_TRUE(drawnInRow(y)) << "row " << y;
    EXPECT_FALSE(drawnInRow(10));
    EXPECT_FALSE(drawnInRow(90));
}

TEST(RaytraceCurves, ACurveCoversWhatATubeOfItsRadiusCovers) {
    const float r = 0.08f;  // about two pixels across
    MeshScene tube;
    tube.mesh.palette = {kBrown};
    // A 16-sided tube along y from 0 to 4.
    const int sides = 16;
    for (int ring = 0; ring < 2; ++ring)
        for (int k = 0; k < sides; ++k) {
            const double a = 2 * 3.14159265358979 * k / sides;
            const Vec3f n{float(std::cos(a)), 0, float(std::sin(a))};
            tube.mesh.positions.push_back({r * n.x, 4.0f * ring, r * n.z});
            tube.mesh.normals.push_back(n);
        }
    for (std::uint32_t k = 0; k < sides; ++k) {
        const std::uint32_t k1 = (k + 1) % sides;
        tube.mesh.indices.insert(tube.mesh.indices.end(),
                                 {k, sides + k, k1, k1, sides + k, sides + k1});
        tube.mesh.triangleColor.insert(tube.mesh.triangleColor.end(), 2, 0);
    }
    RaytraceOptions o = options(100, 100);
    o.camera = stemCamera();
    const std::vector<unsigned char> a = renderRaytracedPixels(curveStem(r), o);
    const std::vector<unsigned char> b = renderRaytracedPixels(tube, o);
    const Box ca = drawnBox(a, o.width, o.height, o.background);
    const Box cb = drawnBox(b, o.width, o.height, o.background);
    EXPECT_NEAR(ca.x0, cb.x0, 1);
    EXPECT_NEAR(ca.x1, cb.x1, 1);
    // The curve's round ends stick out by its radius: a pixel at most.
    EXPECT_NEAR(ca.y0, cb.y0, 2);
    EXPECT_NEAR(ca.y1, cb.y1, 2);
}

TEST(RaytraceCurves, CurvesCountInTheBoundsAndTheFraming) {
    MeshScene s = curveStem(0.01f);
    const Bounds b = s.bounds();
    EXPECT_NEAR(b.max.y, 4.01, 1e-6);
    const RaytraceOptions o = options(100, 100);
    const std::vector<unsigned char> px = renderRaytracedPixels(s, o);
    const Box box = drawnBox(px, o.width, o.height, o.background);
    EXPECT_GE(box.y1 - box.y0 + 1, 88) << "a stem alone fills the picture's height";
}

// The framing: the drawing's outline touches two opposite edges within the margin (3% of
// the side: 3 pixels of 100) and is centred between the other two.
void expectFills(const MeshScene& s, const RaytraceOptions& o, const char* what) {
    const std::vector<unsigned char> px = renderRaytracedPixels(s, o);
    const Box b = drawnBox(px, o.width, o.height, o.background);
    ASSERT_LT(b.x0, b.x1) << what;
    const int left = b.x0, right = o.width - 1 - b.x1, top = b.y0, bottom = o.height - 1 - b.y1;
    const bool fillsWidth = left <= 4 && right <= 4;
    const bool fillsHeight = top <= 4 && bottom <= 4;
    EXPECT_TRUE(fillsWidth || fillsHeight) << what << ": margins left " << left << " right "
                                           << right << " top " << top << " bottom " << bottom;
    EXPECT_GE(std::min({left, right, top, bottom}), 1) << what << ": touches the edge";
    EXPECT_NEAR(left, right, 3) << what;
    EXPECT_NEAR(top, bottom, 3) << what;
}

TEST(RaytraceFraming, TheSceneFillsTheFrame) {
    expectFills(leafyPlant(), options(100, 100), "plant, square");
    expectFills(leafyPlant(), options(160, 90), "plant, landscape");
    RaytraceOptions ortho = options(100, 100);
    ortho.camera.orthographic = true;
    expectFills(leafyPlant(), ortho, "plant, orthographic");
    MeshScene wide;
    wide.mesh.palette = {kGreen};
    wide.prototypes.push_back(leaf());
    for (int k = 0; k < 9; ++k)
        wide.placements.push_back({0, placement(30, 1, {float(k) - 4, 0, 0})});
    expectFills(wide, options(100, 100), "a row of leaves");
    expectFills(wide, ortho, "a row of leaves, orthographic");
}

TEST(RaytraceFraming, ACpfgParallelViewTakesOnlyItsDirectionAndFitsTheScene) {
    // cpfg fits its parallel view volume to the model: a view file's `viewpoint: 0,0,1` and
    // `view reference point: 0,0,0` say only "look along -z". Taken as a camera 1 unit from
    // the origin, the window would be under a unit across and the row of leaves, 8 units
    // wide, would not fit (vlab's Tropisms model drew a blank picture so).
    MeshScene wide;
    wide.mesh.palette = {kGreen};
    wide.prototypes.push_back(leaf());
    for (int k = 0; k < 9; ++k)
        wide.placements.push_back({0, placement(30, 1, {float(k) - 4, 0, 0})});
    RaytraceOptions o = options(100, 100);
    o.camera.orthographic = true;
    o.camera.viewpoint = Vec3{0, 0, 1};
    o.camera.target = Vec3{0, 0, 0};
    o.camera.fitWindow = true;
    expectFills(wide, o, "a row of leaves, cpfg's parallel view");
    const Box fitted = drawnBox(renderRaytracedPixels(wide, o), o.width, o.height, o.background);
    // Without the flag (a --viewpoint and --target given on the command line) the camera is
    // taken as it is: the window, 0.7 units high, shows the middle leaf and nothing else.
    o.camera.fitWindow = false;
    const Box b = drawnBox(renderRaytracedPixels(wide, o), o.width, o.height, o.background);
    EXPECT_GE(fitted.x1 - fitted.x0, 90);
    EXPECT_TRUE(b.x0 >= b.x1 || std::abs((b.x1 - b.x0) - (fitted.x1 - fitted.x0)) > 10)
        << "the unfitted window drew " << b.x0 << ".." << b.x1 << ", the fitted one " << fitted.x0
        << ".." << fitted.x1;
}

TEST(RaytraceFraming, FramedCameraFillsBetterThanTheBoundingSphere) {
    // A tall thin plant seen from the front: the old sphere left most of the height empty.
    const MeshScene s = curveStem(0.02f);
    const Camera c = framedCamera(Camera{}, s, 100, 100);
    ASSERT_TRUE(c.viewpoint && c.target);
    const double distance = length(*c.viewpoint - *c.target);
    // A 4-unit stem in a 40-degree field: about 4 / (0.94 * 2 tan 20) = 5.8 units away.
    EXPECT_LT(distance, 7);
    EXPECT_GT(distance, 4.5);
}

TEST(RaytraceLight, TheGroundTakesThePlantsShadow) {
    MeshScene s = leafyPlant();
    RaytraceOptions o = options(120, 120);
    o.camera.viewpoint = Vec3{0, 6, 8};  // from above, so that the floor shows
    o.camera.target = Vec3{0, 1, 0};
    o.lighting.sunDirection = {0, 1, -1};  // behind the plant: its shadow falls forward
    o.ground = true;
    const std::vector<unsigned char> with = renderRaytracedPixels(s, o);
    o.ground = false;
    const std::vector<unsigned char> without = renderRaytracedPixels(s, o);
    // The floor shows where the picture was background.
    long floorPixels = 0;
    for (std::size_t i = 0; i < with.size(); i += 3)
        if (without[i] == 255 && without[i + 1] == 255 && without[i + 2] == 255 &&
            with[i] + with[i + 1] + with[i + 2] < 700)
            ++floorPixels;
    EXPECT_GT(floorPixels, 1000);
    // The same floor without the sun's shadows is brighter: the plant's shadow is on it.
    o.ground = true;
    o.lighting.shadows = false;
    const std::vector<unsigned char> unshadowed = renderRaytracedPixels(s, o);
    long shadowed = 0, lit = 0;
    for (std::size_t i = 0; i < with.size(); ++i) {
        shadowed += with[i];
        lit += unshadowed[i];
    }
    EXPECT_LT(shadowed + 2000, lit);
}

TEST(RaytraceLight, AmbientOcclusionDarkensTheInsideOfAStack) {
    // Ten leaves stacked closely: the middle ones see little sky.
    MeshScene s;
    s.mesh.palette = {kGreen};
    s.prototypes.push_back(leaf());
    Affine3f lying;  // the leaf turned to lie flat, facing up
    lying.columns[1] = {0, 0, -1};
    lying.columns[2] = {0, 1, 0};
    for (int k = 0; k < 10; ++k) {
        Affine3f t = lying;
        t.columns[3] = {0, 0.02f * k, 0};
        s.placements.push_back({0, t});
    }
    RaytraceOptions o = options(80, 80);
    o.lighting.sunIntensity = 0;
    o.camera.viewpoint = Vec3{0, 0.5, 3};  // from the side, slightly above
    o.camera.target = Vec3{0, 0.1, -0.5};
    const std::vector<unsigned char> occluded = renderRaytracedPixels(s, o);
    o.lighting.skyRays = 0;
    const std::vector<unsigned char> open = renderRaytracedPixels(s, o);
    double a = 0, b = 0;
    for (std::size_t i = 0; i < occluded.size(); ++i) {
        a += occluded[i];
        b += open[i];
    }
    EXPECT_LT(a, b - 1000) << "sky rays find the leaves above";
}

TEST(RaytraceLight, PixelsDoNotDependOnTheThreadCount) {
    const MeshScene s = leafyPlant();
    RaytraceOptions o = options(123, 77);  // tiles do not divide the picture
    o.ground = true;
    o.threads = 1;
    const std::vector<unsigned char> one = renderRaytracedPixels(s, o);
    o.threads = 3;
    EXPECT_EQ(renderRaytracedPixels(s, o), one);
    o.threads = 0;
    EXPECT_EQ(renderRaytracedPixels(s, o), one);
}

}  // namespace
}  // namespace graftal
