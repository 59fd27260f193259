// Surfaces: cpfg's .s files, the shipped leaf and petal, Bézier patch evaluation, and
// cpfg's binary colour maps.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "graftal/geometry/color_map.hpp"
#include "graftal/geometry/surface.hpp"

using namespace graftal;

namespace {

namespace fs = std::filesystem;

const fs::path kSurfacesDir = GRAFTAL_SURFACES_DIR;

// A minimal valid file: one flat unit patch; each line is numbered in the comments of the
// tests that break it.
const std::string kHeader =
    "0 1 0 1 0 0\n"                    // 1
    "CONTACT POINT  X: 0 Y: 0 Z: 0\n"  // 2
    "END POINT  X: 0 Y: 1 Z: 0\n"      // 3
    "HEADING  X: 0 Y: 1 Z: 0\n"        // 4
    "UP  X: 0 Y: 0 Z: 1\n"             // 5
    "SIZE: 1\n";                       // 6
const std::string kPatchHead =
    "flat\n"                                                    // 7
    "TOP COLOR: 1 DIFFUSE: 0.8 BOTTOM COLOR: 1 DIFFUSE: 0.8\n"  // 8
    "AL: ~ A: ~ AR: ~\n"                                        // 9
    "L: ~ R: ~\n"                                               // 10
    "BL: ~ B: ~ BR: ~\n";                                       // 11
const std::string kPoints =
    "0 0 0  0.333333 0 0  0.666667 0 0  1 0 0\n"                              // 12
    "0 0.333333 0  0.333333 0.333333 0  0.666667 0.333333 0  1 0.333333 0\n"  // 13
    "0 0.666667 0  0.333333 0.666667 0  0.666667 0.666667 0  1 0.666667 0\n"  // 14
    "0 1 0  0.333333 1 0  0.666667 1 0  1 1 0\n";                             // 15

std::string flatFile() {
    return kHeader + kPatchHead + kPoints;
}

std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
    std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// The first diagnostic of parsing `text`, or an empty one when it parses.
Diagnostic errorOf(const std::string& text, const std::string& file = "test.s") {
    try {
        parseSurface(text, file);
    } catch (const Error& e) {
        return e.diagnostics().front();
    }
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

void expectNear(const Vec3& a, const Vec3& b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

// A directory of its own under the system temporary directory, removed afterwards.
class TempDir {
  public:
    TempDir() {
        static int counter = 0;
        path_ = fs::temp_directory_path() / ("graftal-surface-test-" + std::to_string(::getpid()) +
                                             "-" + std::to_string(counter++));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

void writeBytes(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

// A patch whose control points form a regular grid on (x0 + col dx, y0 + row dy, 0).
BezierPatch gridPatch(double dx = 1.0 / 3, double dy = 1.0 / 3) {
    BezierPatch p;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            p.points[static_cast<std::size_t>(row * 4 + col)] = {col * dx, row * dy, 0};
    return p;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Reading .s files

TEST(SurfaceFile, ParsesAMinimalFile) {
    Surface s = parseSurface(flatFile(), "dir/flat.s");
    EXPECT_EQ(s.name, "flat");
    ASSERT_EQ(s.patches.size(), 1u);
    EXPECT_EQ(s.patches[0].name, "flat");
    EXPECT_EQ(s.contactPoint, (Vec3{0, 0, 0}));
    EXPECT_EQ(s.endPoint, (Vec3{0, 1, 0}));
    EXPECT_EQ(s.heading, (Vec3{0, 1, 0}));
    EXPECT_EQ(s.up, (Vec3{0, 0, 1}));
    EXPECT_EQ(s.size, 1);
    // Row-major as in the file: the 6th point is the second of the second line.
    expectNear(s.patches[0].points[5], {0.333333, 0.333333, 0});
    expectNear(s.bounds.min, {0, 0, 0});
    expectNear(s.bounds.max, {1, 1, 0});
}

TEST(SurfaceFile, ShippedLeaf) {
    Surface s = loadSurface(kSurfacesDir / "leaf.s");
    EXPECT_EQ(s.name, "leaf");
    ASSERT_EQ(s.patches.size(), 2u);
    EXPECT_EQ(s.patches[0].name, "left");
    EXPECT_EQ(s.patches[1].name, "right");
    EXPECT_EQ(s.contactPoint, (Vec3{0, 0, 0}));
    EXPECT_EQ(s.heading, (Vec3{0, 1, 0}));
    EXPECT_EQ(s.up, (Vec3{0, 0, 1}));
    EXPECT_EQ(s.size, 1);
    // About one unit long along the heading, starting at the contact point.
    EXPECT_NEAR(s.bounds.min.y, 0, 1e-12);
    EXPECT_NEAR(s.bounds.max.y, 1, 1e-12);
    EXPECT_LT(s.bounds.max.x - s.bounds.min.x, 1.0);
    // The two halves share the midrib.
    for (int row = 0; row < 4; ++row)
        EXPECT_EQ(s.patches[0].points[static_cast<std::size_t>(row * 4 + 3)],
                  s.patches[1].points[static_cast<std::size_t>(row * 4)]);
}

TEST(SurfaceFile, ShippedPetal) {
    Surface s = loadSurface(kSurfacesDir / "petal.s");
    EXPECT_EQ(s.name, "petal");
    ASSERT_EQ(s.patches.size(), 1u);
    EXPECT_EQ(s.contactPoint, (Vec3{0, 0, 0}));
    EXPECT_EQ(s.heading, (Vec3{0, 1, 0}));
    EXPECT_NEAR(s.bounds.max.y - s.contactPoint.y, 1.05, 1e-12);
}

TEST(SurfaceFile, ToleratesWhitespaceCaseAndGluedValues) {
    std::string text =
        "  0 1\t0 1 0 0\n\n"
        "contact   point\tX:0 Y :0 Z:   0\n"
        "END POINT X: 0 Y: 1 Z: 0   \r\n"
        "HEADING X: 0 Y: 2 Z: 0\n"
        "UP X: 0 Y: 0 Z: 3\n"
        "SIZE:1\n\n\n" +
        kPatchHead + kPoints + "\n\n";
    Surface s = parseSurface(text, "t.s");
    ASSERT_EQ(s.patches.size(), 1u);
    // HEADING and UP are normalised, as cpfg does.
    EXPECT_EQ(s.heading, (Vec3{0, 1, 0}));
    EXPECT_EQ(s.up, (Vec3{0, 0, 1}));
}

TEST(SurfaceFile, UpIsMadePerpendicularToHeading) {
    std::string text = replaceOnce(flatFile(), "UP  X: 0 Y: 0 Z: 1", "UP  X: 0 Y: 1 Z: 1");
    Surface s = parseSurface(text, "t.s");
    expectNear(s.up, {0, 0, 1});
}

TEST(SurfaceFile, AcceptsPrecisionAndSteditVersion) {
    std::string precision = replaceOnce(flatFile(), "CONTACT", "PRECISION S: 8 T: 6\nCONTACT");
    EXPECT_EQ(parseSurface(precision, "p.s").patches.size(), 1u);

    // bezieredit's extended format: a direction after every neighbour name.
    std::string stedit = "VERSION stedit\n" + kHeader +
                         "flat\n"
                         "TOP COLOR: 1 DIFFUSE: 0.8 BOTTOM COLOR: 1 DIFFUSE: 0.8\n"
                         "AL: ~ ~ A: ~ ~ AR: ~ ~\nL: ~ ~ R: ~ ~\nBL: ~ ~ B: ~ ~ BR: ~ ~\n" +
                         kPoints;
    EXPECT_EQ(parseSurface(stedit, "v.s").patches.size(), 1u);
}

TEST(SurfaceFile, NeighboursMustExistAndAgree) {
    std::string two = kHeader +
                      "a\nTOP COLOR: 1 DIFFUSE: 1 BOTTOM COLOR: 1 DIFFUSE: 1\n"
                      "AL: ~ A: ~ AR: ~\nL: ~ R: b\nBL: ~ B: ~ BR: ~\n" +
                      kPoints +
                      "b\nTOP COLOR: 1 DIFFUSE: 1 BOTTOM COLOR: 1 DIFFUSE: 1\n"
                      "AL: ~ A: ~ AR: ~\nL: a R: ~\nBL: ~ B: ~ BR: ~\n" +
                      kPoints;
    EXPECT_EQ(parseSurface(two, "two.s").patches.size(), 2u);

    Diagnostic missing = errorOf(replaceOnce(two, "R: b", "R: c"));
    EXPECT_EQ(missing.location.line, 10);
    EXPECT_EQ(missing.location.column, 9);
    EXPECT_TRUE(contains(missing.message, "no patch 'c'")) << missing.message;

    Diagnostic mismatch = errorOf(replaceOnce(two, "L: a", "L: ~"));
    EXPECT_EQ(mismatch.location.line, 10);
    EXPECT_TRUE(contains(mismatch.message, "neighbour mismatch")) << mismatch.message;
}

TEST(SurfaceErrors, MissingHeaderField) {
    // No END POINT line: the error is on the HEADING line, where END was expected.
    std::string text = replaceOnce(flatFile(), "END POINT  X: 0 Y: 1 Z: 0\n", "");
    Diagnostic d = errorOf(text, "broken.s");
    EXPECT_EQ(d.location.file, "broken.s");
    EXPECT_EQ(d.location.line, 3);
    EXPECT_EQ(d.location.column, 1);
    EXPECT_TRUE(contains(d.message, "expected 'END'")) << d.message;
    EXPECT_TRUE(contains(d.message, "'HEADING'")) << d.message;

    Diagnostic size = errorOf(replaceOnce(flatFile(), "SIZE: 1\n", ""));
    EXPECT_EQ(size.location.line, 6);
    EXPECT_TRUE(contains(size.message, "'SIZE:'")) << size.message;
}

TEST(SurfaceErrors, NotANumber) {
    Diagnostic header = errorOf(replaceOnce(flatFile(), "SIZE: 1", "SIZE: big"));
    EXPECT_EQ(header.location.line, 6);
    EXPECT_EQ(header.location.column, 7);
    EXPECT_TRUE(contains(header.message, "found 'big'")) << header.message;

    Diagnostic coord = errorOf(
        replaceOnce(flatFile(), "0 0.666667 0  0.333333 0.666667 0", "0 0.666667 0  0.333333 x 0"));
    EXPECT_EQ(coord.location.line, 14);
    EXPECT_EQ(coord.location.column, 24);
    EXPECT_TRUE(contains(coord.message, "y coordinate of control point 10")) << coord.message;

    Diagnostic glued =
        errorOf(replaceOnce(flatFile(), "Y: 1 Z: 0\nHEADING", "Y: 1.0.0 Z: 0\nHEADING"));
    EXPECT_EQ(glued.location.line, 3);
    EXPECT_TRUE(contains(glued.message, "'1.0.0'")) << glued.message;

    Diagnostic infinite = errorOf(replaceOnce(flatFile(), "X: 0 Y: 0 Z: 0", "X: inf Y: 0 Z: 0"));
    EXPECT_EQ(infinite.location.line, 2);

    Diagnostic colour = errorOf(replaceOnce(flatFile(), "TOP COLOR: 1", "TOP COLOR: 1.5"));
    EXPECT_EQ(colour.location.line, 8);
    EXPECT_TRUE(contains(colour.message, "whole number")) << colour.message;
}

TEST(SurfaceErrors, TruncatedPatch) {
    // Only two of the four lines of control points.
    std::string text = kHeader + kPatchHead + kPoints.substr(0, kPoints.find("0 0.666667"));
    Diagnostic d = errorOf(text);
    EXPECT_EQ(d.location.line, 13);  // the last line that has anything on it
    EXPECT_TRUE(contains(d.message, "ends inside patch 'flat'")) << d.message;
    EXPECT_TRUE(contains(d.message, "8 of its 16")) << d.message;

    // Cut in the middle of a point.
    Diagnostic mid = errorOf(kHeader + kPatchHead + "0 0 0  1 0");
    EXPECT_EQ(mid.location.line, 12);
    EXPECT_EQ(mid.location.column, 11);
    EXPECT_TRUE(contains(mid.message, "1 of its 16")) << mid.message;

    // Cut before the neighbours.
    Diagnostic early =
        errorOf(kHeader + "flat\nTOP COLOR: 1 DIFFUSE: 0.8 BOTTOM COLOR: 1 DIFFUSE: 0.8\n");
    EXPECT_EQ(early.location.line, 8);
    EXPECT_TRUE(contains(early.message, "'AL:'")) << early.message;
}

TEST(SurfaceErrors, PatchNameOfTwoWords) {
    Diagnostic d = errorOf(replaceOnce(flatFile(), "flat\n", "flat leaf\n"));
    EXPECT_EQ(d.location.line, 7);
    EXPECT_EQ(d.location.column, 6);
    EXPECT_TRUE(contains(d.message, "expected 'TOP'")) << d.message;
}

TEST(SurfaceErrors, BadFrameAndSize) {
    Diagnostic heading =
        errorOf(replaceOnce(flatFile(), "HEADING  X: 0 Y: 1", "HEADING  X: 0 Y: 0"));
    EXPECT_EQ(heading.location.line, 4);
    EXPECT_TRUE(contains(heading.message, "HEADING")) << heading.message;

    Diagnostic parallel =
        errorOf(replaceOnce(flatFile(), "UP  X: 0 Y: 0 Z: 1", "UP  X: 0 Y: -2 Z: 0"));
    EXPECT_EQ(parallel.location.line, 5);
    EXPECT_TRUE(contains(parallel.message, "parallel")) << parallel.message;

    Diagnostic size = errorOf(replaceOnce(flatFile(), "SIZE: 1", "SIZE: 0"));
    EXPECT_EQ(size.location.line, 6);
    EXPECT_TRUE(contains(size.message, "positive")) << size.message;
}

TEST(SurfaceErrors, NoPatchesAndEmptyFile) {
    Diagnostic none = errorOf(kHeader);
    EXPECT_EQ(none.location.line, 6);
    EXPECT_TRUE(contains(none.message, "at least one patch")) << none.message;

    Diagnostic empty = errorOf("");
    EXPECT_EQ(empty.location.line, 1);
    EXPECT_TRUE(contains(empty.message, "the end of the file")) << empty.message;
}

TEST(SurfaceErrors, MissingFileNamesIt) {
    try {
        loadSurface("/nonexistent/graftal/none.s");
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.diagnostics().front().location.file, "/nonexistent/graftal/none.s");
        EXPECT_EQ(e.diagnostics().front().location.line, 0);
    }
}

TEST(SurfaceErrors, LoadedFileErrorsCarryThePath) {
    TempDir dir;
    fs::path p = dir.path() / "bad.s";
    writeText(p, replaceOnce(flatFile(), "SIZE: 1", "SIZE: x"));
    try {
        loadSurface(p);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        const Diagnostic& d = e.diagnostics().front();
        EXPECT_EQ(d.location.file, p.string());
        EXPECT_EQ(d.location.line, 6);
        EXPECT_TRUE(contains(d.toString(), p.string() + ":6:7: error:")) << d.toString();
    }
}

// ---------------------------------------------------------------------------------------
// The library

TEST(SurfaceLibrary, BuiltinHasTheLeafAndThePetal) {
    SurfaceLibrary lib = SurfaceLibrary::builtin();
    std::vector<std::string> names = lib.names();
    EXPECT_NE(std::find(names.begin(), names.end(), "leaf"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "petal"), names.end());
    ASSERT_NE(lib.find("leaf"), nullptr);
    EXPECT_EQ(lib.find("leaf")->patches.size(), 2u);
    EXPECT_EQ(lib.find("nothing"), nullptr);
}

TEST(SurfaceLibrary, AddAndAddDirectory) {
    TempDir dir;
    writeText(dir.path() / "flat.s", flatFile());
    writeText(dir.path() / "notes.txt", "not a surface");
    SurfaceLibrary lib;
    lib.addDirectory(dir.path());
    EXPECT_EQ(lib.names(), std::vector<std::string>{"flat"});

    Surface other = parseSurface(flatFile(), "other.s");
    lib.add(other);
    EXPECT_EQ(lib.names(), (std::vector<std::string>{"flat", "other"}));

    // A later surface of the same name replaces the earlier.
    Surface again = parseSurface(flatFile(), "flat.s");
    again.size = 2;
    lib.add(again);
    EXPECT_EQ(lib.find("flat")->size, 2);

    EXPECT_THROW(lib.addDirectory(dir.path() / "missing"), Error);
    Surface nameless;
    EXPECT_THROW(lib.add(nameless), Error);
}

TEST(SurfaceLibrary, ABrokenFileInADirectoryIsAnError) {
    TempDir dir;
    writeText(dir.path() / "broken.s", kHeader);
    SurfaceLibrary lib;
    EXPECT_THROW(lib.addDirectory(dir.path()), Error);
}

// ---------------------------------------------------------------------------------------
// Patch evaluation

TEST(BezierPatch, FlatGridIsExactWithTheUpNormal) {
    BezierPatch p = gridPatch();
    for (double s : {0.0, 0.25, 0.5, 0.8, 1.0}) {
        for (double t : {0.0, 0.1, 0.5, 0.75, 1.0}) {
            Vec3 n;
            Vec3 v = evaluatePatch(p, s, t, &n);
            // A regular grid is linearly precise: P(s, t) = (s, t, 0).
            expectNear(v, {s, t, 0}, 1e-14);
            expectNear(n, {0, 0, 1}, 1e-14);
        }
    }
}

TEST(BezierPatch, NormalFollowsSThenT) {
    // s along y and t along x: ds x dt = y x x = -z.
    BezierPatch p;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            p.points[static_cast<std::size_t>(row * 4 + col)] = {row * 2.0, col * 0.5, 7};
    Vec3 n;
    Vec3 v = evaluatePatch(p, 0.5, 0.5, &n);
    expectNear(v, {3, 0.75, 7});
    expectNear(n, {0, 0, -1});
}

TEST(BezierPatch, CornersInterpolateTheCornerControlPoints) {
    BezierPatch p;
    for (std::size_t i = 0; i < 16; ++i) {
        double k = static_cast<double>(i);
        p.points[i] = {std::sin(k) + static_cast<double>(i % 4), std::cos(3 * k) + k / 4,
                       0.3 * std::sin(5 * k)};
    }
    expectNear(evaluatePatch(p, 0, 0), p.points[0]);
    expectNear(evaluatePatch(p, 1, 0), p.points[3]);
    expectNear(evaluatePatch(p, 0, 1), p.points[12]);
    expectNear(evaluatePatch(p, 1, 1), p.points[15]);
    // Edges are the Bézier curves of the border rows: the middle of the first row.
    Vec3 mid = evaluatePatch(p, 0.5, 0);
    Vec3 expected{(p.points[0].x + 3 * p.points[1].x + 3 * p.points[2].x + p.points[3].x) / 8,
                  (p.points[0].y + 3 * p.points[1].y + 3 * p.points[2].y + p.points[3].y) / 8,
                  (p.points[0].z + 3 * p.points[1].z + 3 * p.points[2].z + p.points[3].z) / 8};
    expectNear(mid, expected);
}

TEST(BezierPatch, CurvedPatchNormalIsPerpendicularToTheSurface) {
    BezierPatch p = gridPatch();
    for (std::size_t i = 0; i < 16; ++i) p.points[i].z = 0.2 * std::sin(static_cast<double>(i));
    Vec3 n;
    Vec3 v = evaluatePatch(p, 0.3, 0.6, &n);
    EXPECT_NEAR(length(n), 1, 1e-12);
    double h = 1e-6;
    Vec3 vs = evaluatePatch(p, 0.3 + h, 0.6);
    Vec3 vt = evaluatePatch(p, 0.3, 0.6 + h);
    Vec3 ds{vs.x - v.x, vs.y - v.y, vs.z - v.z};
    Vec3 dt{vt.x - v.x, vt.y - v.y, vt.z - v.z};
    EXPECT_NEAR((n.x * ds.x + n.y * ds.y + n.z * ds.z) / h, 0, 1e-5);
    EXPECT_NEAR((n.x * dt.x + n.y * dt.y + n.z * dt.z) / h, 0, 1e-5);
}

TEST(BezierPatch, CollapsedEdgesGiveFiniteOutwardNormals) {
    // The leaf's halves collapse to one point at the base and one at the tip.
    Surface leaf = loadSurface(kSurfacesDir / "leaf.s");
    for (const BezierPatch& p : leaf.patches) {
        for (double s : {0.0, 0.3, 0.5, 1.0}) {
            for (double t : {0.0, 1e-9, 0.5, 1.0 - 1e-9, 1.0}) {
                Vec3 n;
                evaluatePatch(p, s, t, &n);
                ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
                EXPECT_NEAR(length(n), 1, 1e-9) << p.name << " " << s << " " << t;
                // The top of the leaf faces the turtle's up (+z in the file).
                EXPECT_GT(n.z, 0.5) << p.name << " at s=" << s << " t=" << t;
            }
        }
    }
}

TEST(BezierPatch, TipNormalIsTheLimitFromInside) {
    // Four coincident points on the t = 1 row: the normal there should agree with the
    // normal just inside.
    BezierPatch p = gridPatch();
    for (int col = 0; col < 4; ++col) p.points[static_cast<std::size_t>(12 + col)] = {0.5, 1, 0.2};
    for (double s : {0.0, 0.5, 1.0}) {
        Vec3 atTip, inside;
        evaluatePatch(p, s, 1, &atTip);
        evaluatePatch(p, s, 1 - 1e-4, &inside);
        expectNear(atTip, inside, 1e-3);
    }
}

TEST(BezierPatch, FullyDegeneratePatchesStillGiveUnitNormals) {
    BezierPatch point;
    point.points.fill({1, 2, 3});
    Vec3 n;
    expectNear(evaluatePatch(point, 0.5, 0.5, &n), {1, 2, 3});
    EXPECT_NEAR(length(n), 1, 1e-12);

    BezierPatch line;
    for (std::size_t i = 0; i < 16; ++i) line.points[i] = {static_cast<double>(i), 0, 0};
    for (double s : {0.0, 0.5, 1.0}) {
        evaluatePatch(line, s, s, &n);
        EXPECT_NEAR(length(n), 1, 1e-12);
        EXPECT_NEAR(n.x, 0, 1e-12);  // across the line
    }
}

TEST(BezierPatch, PetalIsCuppedUpwards) {
    Surface petal = loadSurface(kSurfacesDir / "petal.s");
    const BezierPatch& p = petal.patches.front();
    Vec3 middle = evaluatePatch(p, 0.5, 0.7);
    Vec3 margin = evaluatePatch(p, 0.0, 0.7);
    EXPECT_GT(margin.z, middle.z);  // margins raised: a cup opening towards the up vector
    Vec3 n;
    evaluatePatch(p, 0.5, 0.5, &n);
    EXPECT_GT(n.z, 0.5);
}

// ---------------------------------------------------------------------------------------
// Colour maps

TEST(ColorMap, RoundTrip) {
    std::vector<Rgb> colors;
    for (int i = 0; i < 256; ++i)
        colors.push_back({static_cast<float>(i) / 255.0f, static_cast<float>(255 - i) / 255.0f,
                          static_cast<float>((i * 7) % 256) / 255.0f});
    TempDir dir;
    fs::path p = dir.path() / "test.map";
    saveColorMap(p, colors);
    EXPECT_EQ(fs::file_size(p), 768u);
    EXPECT_EQ(loadColorMap(p), colors);
    EXPECT_EQ(parseColorMap(encodeColorMap(colors), "x.map"), colors);
}

TEST(ColorMap, ThreeBytesPerColourRedFirst) {
    std::vector<std::uint8_t> bytes(768, 0);
    bytes[3] = 10;   // colour 1: red
    bytes[4] = 20;   //           green
    bytes[5] = 255;  //           blue
    bytes[765] = 255;
    std::vector<Rgb> colors = parseColorMap(bytes, "x.map");
    ASSERT_EQ(colors.size(), 256u);
    EXPECT_EQ(colors[1], (Rgb{10 / 255.0f, 20 / 255.0f, 1.0f}));
    EXPECT_EQ(colors[255], (Rgb{1.0f, 0, 0}));
    EXPECT_EQ(colors[0], (Rgb{0, 0, 0}));
}

TEST(ColorMap, WrongSizesAreErrorsNamingTheFile) {
    TempDir dir;
    for (std::size_t size :
         {std::size_t{0}, std::size_t{767}, std::size_t{769}, std::size_t{1024}}) {
        fs::path p = dir.path() / ("size" + std::to_string(size) + ".map");
        writeBytes(p, std::vector<std::uint8_t>(size, 7));
        try {
            loadColorMap(p);
            FAIL() << "expected an Error for " << size << " bytes";
        } catch (const Error& e) {
            const Diagnostic& d = e.diagnostics().front();
            EXPECT_EQ(d.location.file, p.string());
            EXPECT_TRUE(contains(d.message, "768")) << d.message;
        }
    }
    EXPECT_THROW(loadColorMap(dir.path() / "missing.map"), Error);
}

TEST(ColorMap, WriterPadsClampsAndRefusesTooMany) {
    std::vector<Rgb> few{{1, 0.5f, 0}, {2, -1, 0.2f}};
    std::vector<std::uint8_t> bytes = encodeColorMap(few);
    ASSERT_EQ(bytes.size(), 768u);
    EXPECT_EQ(bytes[0], 255);
    EXPECT_EQ(bytes[1], 128);
    EXPECT_EQ(bytes[3], 255);  // clamped
    EXPECT_EQ(bytes[4], 0);
    EXPECT_EQ(bytes[5], 51);
    EXPECT_EQ(bytes[6], 0);  // padding is black
    EXPECT_EQ(bytes[767], 0);
    EXPECT_THROW(encodeColorMap(std::vector<Rgb>(257)), Error);
}
