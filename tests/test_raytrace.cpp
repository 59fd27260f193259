// The ray tracer, judged by its pictures: meshes are built by hand (boxes, quads, a stem),
// rendered small, and the pixels are inspected where the geometry says something must be
// (in frame, lit, shadowed, coloured) or must not be (anything but the background).
#include <cairo.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/output/render3d.hpp"

namespace graftal {
namespace {

namespace fs = std::filesystem;

constexpr Rgb kGreen{0.2f, 0.6f, 0.2f};
constexpr Rgb kRed{0.9f, 0.05f, 0.05f};
constexpr Rgb kGrey{0.7f, 0.7f, 0.7f};

Vec3f operator+(Vec3f a, Vec3f b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3f operator-(Vec3f a, Vec3f b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3f operator*(Vec3f a, float s) {
    return {a.x * s, a.y * s, a.z * s};
}

Vec3f normalOf(Vec3f s, Vec3f t) {
    const Vec3f n{s.y * t.z - s.z * t.y, s.z * t.x - s.x * t.z, s.x * t.y - s.y * t.x};
    const float l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    return n * (1 / l);
}

// Meshes made by hand, the way the mesher makes them: flat-shaded faces with their own
// vertices, counter-clockwise seen from the front.
class MeshBuilder {
  public:
    MeshBuilder() { mesh_.palette = {kGreen, kRed, kGrey}; }

    // The quad centre ± s ± t; its front faces along s x t.
    MeshBuilder& quad(Vec3f centre, Vec3f s, Vec3f t, std::uint16_t color) {
        const auto base = static_cast<std::uint32_t>(mesh_.positions.size());
        const Vec3f n = normalOf(s, t);
        for (Vec3f p : {centre - s - t, centre + s - t, centre + s + t, centre - s + t}) {
            mesh_.positions.push_back(p);
            mesh_.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh_.indices.push_back(base + i);
        mesh_.triangleColor.insert(mesh_.triangleColor.end(), 2, color);
        return *this;
    }

    // An axis-aligned box with outward-facing sides.
    MeshBuilder& box(Vec3f lo, Vec3f hi, std::uint16_t color) {
        const Vec3f c = (lo + hi) * 0.5f, h = (hi - lo) * 0.5f;
        const Vec3f x{h.x, 0, 0}, y{0, h.y, 0}, z{0, 0, h.z};
        quad(c + x, y, z, color);
        quad(c - x, z, y, color);
        quad(c + y, z, x, color);
        quad(c - y, x, z, color);
        quad(c + z, x, y, color);
        quad(c - z, y, x, color);
        return *this;
    }

    Mesh build() const { return mesh_; }

  private:
    Mesh mesh_;
};

Mesh unitCube(std::uint16_t color = 0) {
    return MeshBuilder().box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, color).build();
}

struct Pixel {
    int r = 0, g = 0, b = 0;
    int sum() const { return r + g + b; }
    friend bool operator==(const Pixel&, const Pixel&) = default;
};

struct Box {
    int x0, y0, x1, y1;  // inclusive; x0 > x1 when empty
};

class Image {
  public:
    Image(const Mesh& mesh, const RaytraceOptions& o)
        : width_(o.width),
          height_(o.height),
          pixels_(renderRaytracedPixels(mesh, o)),
          background_{byteOf(o.background.r), byteOf(o.background.g), byteOf(o.background.b)} {}

    static int byteOf(float c) { return static_cast<int>(std::lround(c * 255)); }

    Pixel at(int x, int y) const {
        const unsigned char* p = &pixels_[(static_cast<std::size_t>(y) * width_ + x) * 3];
        return {p[0], p[1], p[2]};
    }
    bool isBackground(int x, int y) const { return at(x, y) == background_; }
    const std::vector<unsigned char>& pixels() const { return pixels_; }

    Box objectBox() const {
        Box b{width_, height_, -1, -1};
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x)
                if (!isBackground(x, y)) {
                    b.x0 = std::min(b.x0, x);
                    b.y0 = std::min(b.y0, y);
                    b.x1 = std::max(b.x1, x);
                    b.y1 = std::max(b.y1, y);
                }
        return b;
    }

    // Inside the frame with a free border all round, and big enough to be looked at.
    void expectFramed(const char* what, double minimumFraction = 0.5) const {
        const Box b = objectBox();
        ASSERT_LE(b.x0, b.x1) << what << ": nothing drawn";
        EXPECT_GT(b.x0, 0) << what;
        EXPECT_GT(b.y0, 0) << what;
        EXPECT_LT(b.x1, width_ - 1) << what;
        EXPECT_LT(b.y1, height_ - 1) << what;
        const double fx = static_cast<double>(b.x1 - b.x0 + 1) / width_;
        const double fy = static_cast<double>(b.y1 - b.y0 + 1) / height_;
        EXPECT_GE(std::max(fx, fy), minimumFraction)
            << what << ": the object is too small in the frame";
    }

  private:
    int width_, height_;
    std::vector<unsigned char> pixels_;
    Pixel background_;
};

RaytraceOptions smallOptions(int width = 96, int height = 96) {
    RaytraceOptions o;
    o.width = width;
    o.height = height;
    o.samplesPerPixel = 4;
    o.threads = 2;
    return o;
}

// Where a perspective camera puts a world point, worked out independently of the renderer.
struct Projection {
    double x, y;
};

Projection project(const Vec3& eye, const Vec3& target, const Vec3& point,
                   const RaytraceOptions& o) {
    auto sub = [](Vec3 a, Vec3 b) { return Vec3{a.x - b.x, a.y - b.y, a.z - b.z}; };
    auto dot = [](Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    auto cross = [](Vec3 a, Vec3 b) {
        return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    };
    auto unit = [&](Vec3 a) {
        const double l = std::sqrt(dot(a, a));
        return Vec3{a.x / l, a.y / l, a.z / l};
    };
    const Vec3 f = unit(sub(target, eye));
    const Vec3 r = unit(cross(f, o.camera.up));
    const Vec3 u = cross(r, f);
    const Vec3 d = sub(point, eye);
    const double t = std::tan(o.camera.fieldOfView * std::numbers::pi / 360);
    const double aspect = static_cast<double>(o.width) / o.height;
    const double nx = dot(d, r) / (dot(d, f) * t * aspect), ny = dot(d, u) / (dot(d, f) * t);
    return {(nx + 1) / 2 * o.width, (1 - ny) / 2 * o.height};
}

TEST(Raytrace, ImageHasTheRequestedSize) {
    const RaytraceOptions o = smallOptions(64, 40);
    EXPECT_EQ(renderRaytracedPixels(unitCube(), o).size(), 64u * 40u * 3u);
}

TEST(Raytrace, EmptyMeshIsABackgroundPicture) {
    RaytraceOptions o = smallOptions(20, 10);
    o.background = {0.2f, 0.4f, 0.6f};
    const Image image(Mesh{}, o);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 20; ++x) ASSERT_TRUE(image.isBackground(x, y)) << x << "," << y;
    EXPECT_EQ(image.at(0, 0), (Pixel{51, 102, 153}));
}

TEST(Raytrace, MissedPixelsHaveExactlyTheBackground) {
    RaytraceOptions o = smallOptions();
    o.background = {0.13f, 0.31f, 0.77f};  // not a colour any shading would produce
    const Image image(unitCube(), o);
    const Pixel bg{Image::byteOf(0.13f), Image::byteOf(0.31f), Image::byteOf(0.77f)};
    for (auto [x, y] : {std::pair{0, 0}, {95, 0}, {0, 95}, {95, 95}, {48, 1}, {1, 48}})
        EXPECT_EQ(image.at(x, y), bg) << x << "," << y;
    EXPECT_NE(image.at(48, 48), bg);  // the cube is in the middle
}

TEST(Raytrace, AutoFramingShowsTheWholeCube) {
    Image(unitCube(), smallOptions()).expectFramed("cube, square");
    Image(unitCube(), smallOptions(160, 90)).expectFramed("cube, landscape");
    Image(unitCube(), smallOptions(90, 160)).expectFramed("cube, portrait");
}

TEST(Raytrace, AutoFramingShowsAWideFlatObject) {
    const Mesh wide = MeshBuilder().box({-5, 0, -0.5f}, {5, 0.2f, 0.5f}, 0).build();
    Image(wide, smallOptions()).expectFramed("wide, square");
    Image(wide, smallOptions(90, 160)).expectFramed("wide, portrait");
    RaytraceOptions ortho = smallOptions();
    ortho.camera.orthographic = true;
    Image(wide, ortho).expectFramed("wide, orthographic");
}

TEST(Raytrace, AutoFramingShowsATallThinStem) {
    const Mesh stem = MeshBuilder().box({-0.05f, 0, -0.05f}, {0.05f, 6, 0.05f}, 0).build();
    Image(stem, smallOptions()).expectFramed("stem, square");
    Image(stem, smallOptions(160, 90)).expectFramed("stem, landscape");
    const Box b = Image(stem, smallOptions()).objectBox();
    EXPECT_GT(b.y1 - b.y0, 3 * (b.x1 - b.x0));  // seen upright, not lying down
}

TEST(Raytrace, AutoFramingAroundAGivenTarget) {
    RaytraceOptions o = smallOptions();
    o.camera.target = Vec3{0.3, 0.2, 0};
    // The sphere around an off-centre target is larger than the cube's own.
    Image(unitCube(), o).expectFramed("target only", 0.4);
}

TEST(Raytrace, LitFaceIsBrighterThanFaceTurnedAway) {
    // Looking at the +z and +x faces from their diagonal; +z shows on the left half.
    RaytraceOptions o = smallOptions();
    o.camera.viewpoint = Vec3{4, 0, 4};
    o.camera.target = Vec3{0, 0, 0};
    o.lighting.sunDirection = {1, 0, 0};
    const Image image(unitCube(2), o);
    const Pixel front = image.at(o.width * 2 / 5, o.height / 2);
    const Pixel side = image.at(o.width * 3 / 5, o.height / 2);
    EXPECT_GT(side.sum(), front.sum() + 60) << "lit +x face vs +z face turned away";

    // The same face, with the sun in front of it and then behind it.
    RaytraceOptions facing = smallOptions(), away = smallOptions();
    facing.lighting.sunDirection = {0, 0, 1};
    away.lighting.sunDirection = {0, 0, -1};
    // The ray through the middle of the auto-framed picture enters the cube's front face.
    const Pixel lit = Image(unitCube(2), facing).at(48, 48);
    const Pixel unlit = Image(unitCube(2), away).at(48, 48);
    EXPECT_GT(lit.sum(), unlit.sum() + 60);
}

TEST(Raytrace, BoxCastsAShadowOnTheFloor) {
    const Mesh scene = MeshBuilder()
                           .quad({0, 0, 0}, {0, 0, 5}, {5, 0, 0}, 2)  // floor, facing up
                           .box({-0.5f, 1, -0.5f}, {0.5f, 2, 0.5f}, 1)
                           .build();
    RaytraceOptions o = smallOptions(160, 160);
    o.camera.viewpoint = Vec3{0, 8, 10};
    o.camera.target = Vec3{0, 0, 0};
    o.lighting.sunDirection = {0, 1, 0};
    const Image image(scene, o);
    const Projection under = project(*o.camera.viewpoint, *o.camera.target, {0, 0, 0}, o);
    const Projection far = project(*o.camera.viewpoint, *o.camera.target, {3, 0, 2}, o);
    const Pixel shadowed = image.at(static_cast<int>(under.x), static_cast<int>(under.y));
    const Pixel sunny = image.at(static_cast<int>(far.x), static_cast<int>(far.y));
    EXPECT_LT(shadowed.sum() * 10, sunny.sum() * 6)
        << "under the box " << shadowed.sum() << ", away from it " << sunny.sum();

    o.lighting.shadows = false;  // the darkening is the shadow, not the floor
    const Image noShadows(scene, o);
    const Pixel plain = noShadows.at(static_cast<int>(under.x), static_cast<int>(under.y));
    EXPECT_GT(plain.sum(), shadowed.sum() + 100);
}

TEST(Raytrace, TriangleColourShows) {
    const Image red(unitCube(1), smallOptions());
    const Pixel p = red.at(48, 48);
    EXPECT_GT(p.r, 2 * p.g);
    EXPECT_GT(p.r, 2 * p.b);
    const Pixel q = Image(unitCube(0), smallOptions()).at(48, 48);
    EXPECT_GT(q.g, q.r);
    EXPECT_GT(q.g, q.b);
}

TEST(Raytrace, PixelsDoNotDependOnTheThreadCount) {
    const Mesh scene = MeshBuilder()
                           .quad({0, 0, 0}, {0, 0, 3}, {3, 0, 0}, 2)
                           .box({-0.5f, 0.5f, -0.5f}, {0.5f, 1.5f, 0.5f}, 1)
                           .box({1, 0, 1}, {1.1f, 3, 1.1f}, 0)
                           .build();
    RaytraceOptions o = smallOptions(123, 77);  // tiles do not divide the picture
    o.threads = 1;
    const std::vector<unsigned char> one = renderRaytracedPixels(scene, o);
    o.threads = 4;
    EXPECT_EQ(renderRaytracedPixels(scene, o), one);
    o.threads = 0;
    EXPECT_EQ(renderRaytracedPixels(scene, o), one);
}

TEST(Raytrace, ExplicitSideViewDiffersFromTheFront) {
    const Mesh wide = MeshBuilder().box({-2, -0.5f, -0.25f}, {2, 0.5f, 0.25f}, 0).build();
    const RaytraceOptions front = smallOptions();
    RaytraceOptions side = smallOptions();
    side.camera.viewpoint = Vec3{12, 0, 0};
    side.camera.target = Vec3{0, 0, 0};
    const Image a(wide, front), b(wide, side);
    EXPECT_NE(a.pixels(), b.pixels());
    const Box fa = a.objectBox(), fb = b.objectBox();
    EXPECT_GT(fa.x1 - fa.x0, 3 * (fb.x1 - fb.x0));  // long from the front, short from the side
}

TEST(Raytrace, ErrorsAreErrors) {
    RaytraceOptions o = smallOptions();
    o.width = 0;
    EXPECT_THROW(renderRaytracedPixels(unitCube(), o), Error);
    o = smallOptions();
    o.samplesPerPixel = 0;
    EXPECT_THROW(renderRaytracedPixels(unitCube(), o), Error);
    o = smallOptions();
    o.camera.viewpoint = o.camera.target = Vec3{1, 2, 3};
    EXPECT_THROW(renderRaytracedPixels(unitCube(), o), Error);
    Mesh bad = unitCube();
    bad.indices[4] = 1000;
    EXPECT_THROW(renderRaytracedPixels(bad, smallOptions()), Error);
    bad = unitCube();
    bad.triangleColor.pop_back();
    EXPECT_THROW(renderRaytracedPixels(bad, smallOptions()), Error);
}

// Thin sticks scattered through a crown, like the twigs of a tree: 12 triangles each.
Mesh millionTriangles() {
    MeshBuilder builder;
    std::uint64_t state = 12345;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<float>(state >> 40) / static_cast<float>(1 << 24);
    };
    for (int i = 0; i < 83334; ++i) {
        const Vec3f c{next() * 8 - 4, next() * 8 + 2, next() * 8 - 4};
        Vec3f h{0.02f, 0.02f, 0.02f};
        (i % 3 == 0 ? h.x : i % 3 == 1 ? h.y : h.z) = 0.1f + 0.2f * next();
        builder.box(c - h, c + h, static_cast<std::uint16_t>(i % 3));
    }
    builder.box({-0.2f, 0, -0.2f}, {0.2f, 6, 0.2f}, 2);
    return builder.build();
}

TEST(Raytrace, MillionTrianglesAt800x800) {
    const Mesh mesh = millionTriangles();
    ASSERT_GE(mesh.triangleCount(), 1000000u);
    RaytraceOptions o;  // 800x800, 4 samples, all cores
    const auto start = std::chrono::steady_clock::now();
    const Image image(mesh, o);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Reported, not asserted: the machine's speed is not the renderer's correctness.
    std::cout << "[ timing   ] " << mesh.triangleCount()
              << " triangles, 800x800, 4 spp: " << seconds << " s\n";
    RecordProperty("seconds", std::to_string(seconds));
    image.expectFramed("million triangles");
}

class RaytraceFile : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("graftal-" + std::string(info->test_suite_name()) +
                                            "-" + info->name() + "-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path dir_;
};

TEST_F(RaytraceFile, WritesAPngCairoReadsBack) {
    RaytraceOptions o = smallOptions(70, 50);
    const fs::path path = dir_ / "cube.png";
    renderRaytraced(unitCube(1), o, path);

    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> png(
        cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
    ASSERT_EQ(cairo_surface_status(png.get()), CAIRO_STATUS_SUCCESS);
    ASSERT_EQ(cairo_image_surface_get_width(png.get()), 70);
    ASSERT_EQ(cairo_image_surface_get_height(png.get()), 50);

    // The file holds exactly the in-memory picture.
    const std::vector<unsigned char> expected = renderRaytracedPixels(unitCube(1), o);
    const unsigned char* data = cairo_image_surface_get_data(png.get());
    const int stride = cairo_image_surface_get_stride(png.get());
    for (int y = 0; y < 50; ++y)
        for (int x = 0; x < 70; ++x) {
            std::uint32_t word;
            std::memcpy(&word, data + y * stride + 4 * x, 4);
            const unsigned char* e = &expected[(static_cast<std::size_t>(y) * 70 + x) * 3];
            ASSERT_EQ(word, 0xFF000000u | (e[0] << 16) | (e[1] << 8) | e[2]) << x << "," << y;
        }

    // Atomic: only the picture is left behind, no temporary beside it.
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
        names.push_back(entry.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"cube.png"});
}

TEST_F(RaytraceFile, ReplacesAnExistingPictureAndWritesEmptyMeshes) {
    const fs::path path = dir_ / "plant.png";
    renderRaytraced(unitCube(), smallOptions(30, 30), path);
    renderRaytraced(Mesh{}, smallOptions(40, 20), path);
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> png(
        cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
    ASSERT_EQ(cairo_surface_status(png.get()), CAIRO_STATUS_SUCCESS);
    EXPECT_EQ(cairo_image_surface_get_width(png.get()), 40);
    EXPECT_EQ(cairo_image_surface_get_height(png.get()), 20);
}

TEST_F(RaytraceFile, MissingDirectoryThrows) {
    const fs::path path = dir_ / "no-such-dir" / "cube.png";
    try {
        renderRaytraced(unitCube(), smallOptions(), path);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        ASSERT_FALSE(e.diagnostics().empty());
        EXPECT_EQ(e.diagnostics().front().location.file, path.string());
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_ / "no-such-dir"));
}

TEST_F(RaytraceFile, FailedRenderKeepsThePreviousPicture) {
    const fs::path path = dir_ / "plant.png";
    renderRaytraced(unitCube(), smallOptions(30, 30), path);
    const auto before = fs::file_size(path);
    RaytraceOptions bad = smallOptions();
    bad.width = -1;
    EXPECT_THROW(renderRaytraced(unitCube(), bad, path), Error);
    EXPECT_EQ(fs::file_size(path), before);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace graftal
