// PNG and PDF output, and writeImage's atomic file handling. Pictures are read back the way
// a user would look at them: decode the PNG and inspect pixels, ask pdfinfo about the PDF.
#include <cairo.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/output.hpp"

namespace graftal {
namespace {

namespace fs = std::filesystem;

Scene unitSquare() {
    Scene s;
    const Vec3 p[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i) s.segments.push_back({p[i], p[(i + 1) % 4]});
    return s;
}

Scene triangle(std::uint16_t color) {
    Scene s;
    const std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}};
    s.addPolygon(v, color);
    return s;
}

struct Pixel {
    int r, g, b;
};

// A decoded PNG. The pictures are opaque, so ARGB32's premultiplication changes nothing.
class Png {
  public:
    explicit Png(const fs::path& path)
        : surface_(cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy) {}

    bool ok() const { return cairo_surface_status(surface_.get()) == CAIRO_STATUS_SUCCESS; }
    int width() const { return cairo_image_surface_get_width(surface_.get()); }
    int height() const { return cairo_image_surface_get_height(surface_.get()); }
    Pixel at(int x, int y) const {
        cairo_surface_flush(surface_.get());
        const unsigned char* row = cairo_image_surface_get_data(surface_.get()) +
                                   y * cairo_image_surface_get_stride(surface_.get());
        std::uint32_t v;
        std::memcpy(&v, row + 4 * x, 4);
        return {static_cast<int>((v >> 16) & 255), static_cast<int>((v >> 8) & 255),
                static_cast<int>(v & 255)};
    }
    std::set<std::uint32_t> colours() const {
        std::set<std::uint32_t> s;
        for (int y = 0; y < height(); ++y)
            for (int x = 0; x < width(); ++x) {
                const Pixel p = at(x, y);
                s.insert(static_cast<std::uint32_t>(p.r << 16 | p.g << 8 | p.b));
            }
        return s;
    }

  private:
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface_;
};

int luminance(const Pixel& p) {
    return (p.r * 299 + p.g * 587 + p.b * 114) / 1000;
}

::testing::AssertionResult isColour(const Pixel& p, const Rgb& c, int tolerance = 2) {
    const int r = static_cast<int>(std::lround(c.r * 255)),
              g = static_cast<int>(std::lround(c.g * 255)),
              b = static_cast<int>(std::lround(c.b * 255));
    if (std::abs(p.r - r) <= tolerance && std::abs(p.g - g) <= tolerance &&
        std::abs(p.b - b) <= tolerance)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "pixel (" << p.r << ", " << p.g << ", " << p.b
                                         << ") is not (" << r << ", " << g << ", " << b << ")";
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> entriesOf(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    return names;
}

// Each test gets an empty directory of its own, removed afterwards.
class ImageFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("graftal-" + std::string(info->test_suite_name()) +
                                            "-" + info->name() + "-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
        fs::remove_all(dir_, ec);
    }
    const fs::path& dir() const { return dir_; }

  private:
    fs::path dir_;
};

// A 200 x 200 picture with a 20 px margin: the unit square's edges run along x = 20,
// x = 180, y = 20 and y = 180, drawn 3 px wide so that whole pixels are covered.
RenderOptions squareOptions() {
    RenderOptions o;
    o.width = o.height = 200;
    o.margin = 0.1;
    o.lineWidth = 3;
    return o;
}

using PngWriter = ImageFileTest;
using PdfWriter = ImageFileTest;
using WriteImage = ImageFileTest;

// ---- PNG ---------------------------------------------------------------------------------

TEST_F(PngWriter, DecodesWithTheRequestedSize) {
    RenderOptions o;
    o.width = 320;
    o.height = 200;
    const fs::path file = dir() / "square.png";
    writeImage(unitSquare(), o, file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    EXPECT_EQ(png.width(), 320);
    EXPECT_EQ(png.height(), 200);
}

TEST_F(PngWriter, CornerPixelIsBackground) {
    const fs::path file = dir() / "square.png";
    writeImage(unitSquare(), squareOptions(), file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    for (auto [x, y] : {std::pair{0, 0}, {199, 0}, {0, 199}, {199, 199}})
        EXPECT_TRUE(isColour(png.at(x, y), {1, 1, 1})) << x << "," << y;
}

TEST_F(PngWriter, BackgroundOptionIsHonoured) {
    RenderOptions o = squareOptions();
    o.background = {0.2f, 0.4f, 0.6f};
    const fs::path file = dir() / "square.png";
    writeImage(unitSquare(), o, file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    EXPECT_TRUE(isColour(png.at(0, 0), o.background));
    EXPECT_TRUE(isColour(png.at(100, 100), o.background));  // inside the square
}

TEST_F(PngWriter, PixelsOnTheSquareAreDark) {
    const fs::path file = dir() / "square.png";
    writeImage(unitSquare(), squareOptions(), file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    // Mid-points of the four edges, and the four corners.
    for (auto [x, y] : {std::pair{20, 100},
                        {180, 100},
                        {100, 20},
                        {100, 180},
                        {20, 20},
                        {180, 180},
                        {20, 180},
                        {180, 20}})
        EXPECT_LT(luminance(png.at(x, y)), 80) << x << "," << y;
    EXPECT_TRUE(isColour(png.at(100, 100), {1, 1, 1}));  // the inside stays empty
    EXPECT_TRUE(isColour(png.at(10, 100), {1, 1, 1}));   // and so does the margin
}

TEST_F(PngWriter, DefaultLineWidthIsVisible) {
    RenderOptions o;  // 800 x 800, automatic line width
    const fs::path file = dir() / "square.png";
    writeImage(unitSquare(), o, file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    // The left edge lies on x = 40; one of the two pixel columns beside it must be inked.
    const int darkest = std::min(luminance(png.at(39, 400)), luminance(png.at(40, 400)));
    EXPECT_LT(darkest, 128);
}

TEST_F(PngWriter, PolygonInteriorHasItsFillColour) {
    const Scene s = triangle(1);
    const fs::path file = dir() / "leaf.png";
    writeImage(s, squareOptions(), file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    // The triangle spans x 20..180 and y 60..140 in the image; its centroid is (100, 113).
    EXPECT_TRUE(isColour(png.at(100, 113), s.colorOf(1)));
    EXPECT_TRUE(isColour(png.at(100, 40), {1, 1, 1}));  // above the apex
}

TEST_F(PngWriter, ColourOverridesAreHonoured) {
    Scene s = triangle(1);
    s.segments.push_back({{0, 0, 0}, {2, 0, 0}});  // along the triangle's base
    RenderOptions o = squareOptions();
    o.fillColor = Rgb{0, 0, 1};
    o.lineColor = Rgb{1, 0, 0};
    const fs::path file = dir() / "leaf.png";
    writeImage(s, o, file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    EXPECT_TRUE(isColour(png.at(100, 113), {0, 0, 1}));
    EXPECT_TRUE(isColour(png.at(100, 140), {1, 0, 0}));  // lines are drawn over polygons
}

TEST_F(PngWriter, VerticalLineIsCentred) {
    Scene s;
    s.segments.push_back({{3, -1, 0}, {3, 4, 0}});
    RenderOptions o = squareOptions();
    o.width = 301;  // an odd width puts the line on the middle pixel's centre
    const fs::path file = dir() / "line.png";
    writeImage(s, o, file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    EXPECT_LT(luminance(png.at(150, 100)), 80);
    EXPECT_LT(luminance(png.at(150, 25)), 80);          // it reaches the top margin...
    EXPECT_TRUE(isColour(png.at(150, 10), {1, 1, 1}));  // ...but not beyond
    EXPECT_TRUE(isColour(png.at(100, 100), {1, 1, 1}));
}

TEST_F(PngWriter, AntialiasingOffUsesOnlyInkAndBackground) {
    Scene s;
    s.segments.push_back({{0, 0, 0}, {1, 0.37, 0}});  // a slanted line
    RenderOptions o = squareOptions();
    o.lineWidth = 1.5;
    o.antialias = false;
    const fs::path sharp = dir() / "sharp.png", smooth = dir() / "smooth.png";
    writeImage(s, o, sharp);
    o.antialias = true;
    writeImage(s, o, smooth);
    const Png a(sharp), b(smooth);
    ASSERT_TRUE(a.ok());
    ASSERT_TRUE(b.ok());
    EXPECT_EQ(a.colours().size(), 2u);
    EXPECT_GT(b.colours().size(), 2u);
}

TEST_F(PngWriter, EmptySceneIsAllBackground) {
    const fs::path file = dir() / "empty.png";
    writeImage(Scene{}, squareOptions(), file);
    const Png png(file);
    ASSERT_TRUE(png.ok());
    EXPECT_EQ(png.colours(), (std::set<std::uint32_t>{0xffffff}));
}

TEST_F(PngWriter, MillionSegmentsRenderQuickly) {
    // A connected spiral of a million segments, 80 turns. It takes about half a second of
    // CPU; the bound only catches a writer that went quadratic or strokes every segment
    // alone. CPU time, not wall time, so that a busy machine does not fail it.
    Scene s;
    s.segments.reserve(1'000'000);
    Vec3 p{0, 0, 0};
    for (int i = 0; i < 1'000'000; ++i) {
        const double a = i * 5e-4, r = 1 + i * 1e-5;
        const Vec3 q{r * std::cos(a), r * std::sin(a), 0};
        s.segments.push_back({p, q});
        p = q;
    }
    RenderOptions o;
    const fs::path file = dir() / "spiral.png";
    const std::clock_t start = std::clock();
    writeImage(s, o, file);
    const double seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    EXPECT_LT(seconds, 5.0);
    EXPECT_TRUE(Png(file).ok());
}

// The byte of a PNG file's header that says its colour type: 2 RGB, 6 RGBA.
int colourType(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string header(26, '\0');
    in.read(header.data(), 26);
    return static_cast<unsigned char>(header[25]);
}

TEST_F(PngWriter, TheFileHoldsTheDrawnPixelsAndNoAlphaWhenOpaque) {
    Scene s = triangle(2);
    s.segments = unitSquare().segments;
    RenderOptions o;
    o.width = 97;  // not a multiple of 4 pixels: rows have no padding to lean on
    o.height = 61;
    const fs::path file = dir() / "drawn.png";
    writePng(s, o, file);
    EXPECT_EQ(colourType(file), 2);
    const RgbaImage drawn = drawLineArt(s, o, s.bounds());
    const Png png(file);
    ASSERT_TRUE(png.ok());
    ASSERT_EQ(png.width(), 97);
    int ink = 0;
    for (int y = 0; y < 61; ++y)
        for (int x = 0; x < 97; ++x) {
            const Pixel p = png.at(x, y);
            const std::uint8_t* d = drawn.at(x, y);
            ASSERT_EQ(p.r, d[0]) << x << "," << y;
            ASSERT_EQ(p.g, d[1]) << x << "," << y;
            ASSERT_EQ(p.b, d[2]) << x << "," << y;
            ink += p.r < 128;
        }
    EXPECT_GT(ink, 50);
}

TEST_F(PngWriter, TranslucentPixelsKeepTheirAlpha) {
    RgbaImage image(5, 3);
    for (int x = 0; x < 5; ++x) {
        std::uint8_t* p = &image.pixels[(5 + std::size_t(x)) * 4];
        p[0] = 200, p[1] = 100, p[2] = 50, p[3] = static_cast<std::uint8_t>(x * 60);
    }
    const fs::path file = dir() / "translucent.png";
    writeRgbaPng(image, file);
    EXPECT_EQ(colourType(file), 6);
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> read(
        cairo_image_surface_create_from_png(file.c_str()), &cairo_surface_destroy);
    ASSERT_EQ(cairo_surface_status(read.get()), CAIRO_STATUS_SUCCESS);
    const unsigned char* row =
        cairo_image_surface_get_data(read.get()) + cairo_image_surface_get_stride(read.get());
    for (int x = 0; x < 5; ++x) {
        std::uint32_t v;
        std::memcpy(&v, row + 4 * x, 4);
        const int a = static_cast<int>(v >> 24);
        EXPECT_EQ(a, x * 60);
        // Cairo reads it back premultiplied.
        EXPECT_NEAR(static_cast<int>((v >> 16) & 255), 200 * a / 255, 1);
        EXPECT_NEAR(static_cast<int>(v & 255), 50 * a / 255, 1);
    }
}

TEST_F(PngWriter, ZeroSizeThrowsNamingThePath) {
    RenderOptions o;
    o.width = 0;
    const fs::path file = dir() / "zero.png";
    try {
        writePng(unitSquare(), o, file);
        FAIL() << "expected graftal::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}

// ---- PDF ---------------------------------------------------------------------------------

TEST_F(PdfWriter, FileStartsWithPdfMagic) {
    const fs::path file = dir() / "square.pdf";
    writeImage(unitSquare(), RenderOptions{}, file);
    EXPECT_EQ(readFile(file).rfind("%PDF-", 0), 0u);
}

TEST_F(PdfWriter, PdfinfoReportsThePageSize) {
    if (std::system("command -v pdfinfo > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "pdfinfo (poppler-utils) is not installed";
    RenderOptions o;
    o.width = 300;
    o.height = 200;
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}};
    s.addPolygon(v, 1);
    const fs::path file = dir() / "square.pdf";
    writeImage(s, o, file);
    const std::string command = "pdfinfo '" + file.string() + "' 2>&1";
    std::unique_ptr<FILE, decltype(&pclose)> pipe(popen(command.c_str(), "r"), &pclose);
    ASSERT_TRUE(pipe);
    std::string output;
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe.get())) output += buf;
    EXPECT_NE(output.find("Pages:"), std::string::npos) << output;
    EXPECT_NE(output.find("300 x 200 pts"), std::string::npos) << output;
}

// ---- writeImage --------------------------------------------------------------------------

TEST_F(WriteImage, UnknownExtensionThrowsAndLeavesNoFile) {
    const fs::path file = dir() / "x.bmp";
    try {
        writeImage(unitSquare(), RenderOptions{}, file);
        FAIL() << "expected graftal::Error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
        EXPECT_NE(message.find(".png"), std::string::npos) << message;
        EXPECT_NE(message.find(".svg"), std::string::npos) << message;
    }
    EXPECT_TRUE(entriesOf(dir()).empty());
}

TEST_F(WriteImage, ExtensionIsCaseInsensitive) {
    const fs::path file = dir() / "SQUARE.PNG";
    writeImage(unitSquare(), RenderOptions{}, file);
    EXPECT_TRUE(Png(file).ok());
}

TEST_F(WriteImage, MissingDirectoryThrowsAndLeavesNoTemporary) {
    for (const char* name : {"a.png", "a.svg", "a.pdf"}) {
        const fs::path file = dir() / "no" / "such" / name;
        try {
            writeImage(unitSquare(), RenderOptions{}, file);
            ADD_FAILURE() << "expected graftal::Error for " << file;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_TRUE(entriesOf(dir()).empty());
}

TEST_F(WriteImage, UnwritableDirectoryThrowsNamingThePath) {
    if (::geteuid() == 0) GTEST_SKIP() << "root can write anywhere";
    fs::permissions(dir(), fs::perms::owner_read | fs::perms::owner_exec);
    for (const char* name : {"a.png", "a.svg", "a.pdf"}) {
        const fs::path file = dir() / name;
        try {
            writeImage(unitSquare(), RenderOptions{}, file);
            ADD_FAILURE() << "expected graftal::Error for " << file;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        }
    }
    fs::permissions(dir(), fs::perms::owner_all);
    EXPECT_TRUE(entriesOf(dir()).empty());
}

TEST_F(WriteImage, TargetThatIsADirectoryThrowsAndLeavesNoTemporary) {
    const fs::path file = dir() / "taken.png";
    fs::create_directory(file);
    EXPECT_THROW(writeImage(unitSquare(), RenderOptions{}, file), Error);
    EXPECT_EQ(entriesOf(dir()), (std::vector<std::string>{"taken.png"}));
    EXPECT_TRUE(fs::is_directory(file));
}

TEST_F(WriteImage, ReplacesAnExistingFile) {
    const fs::path file = dir() / "square.png";
    std::ofstream(file) << "old contents";
    writeImage(unitSquare(), RenderOptions{}, file);
    EXPECT_TRUE(Png(file).ok());
    EXPECT_EQ(entriesOf(dir()), (std::vector<std::string>{"square.png"}));
}

TEST_F(WriteImage, FailedWriteKeepsThePreviousFile) {
    for (const char* name : {"a.png", "a.svg", "a.pdf"}) {
        const fs::path file = dir() / name;
        std::ofstream(file) << "previous picture";
        RenderOptions o;
        o.width = -5;
        EXPECT_THROW(writeImage(unitSquare(), o, file), Error) << name;
        EXPECT_EQ(readFile(file), "previous picture") << name;
    }
    EXPECT_EQ(entriesOf(dir()).size(), 3u) << "no temporaries left";
}

TEST_F(WriteImage, PngPdfAndSvgOfTheSameSceneAllExist) {
    Scene s = unitSquare();
    const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}};
    s.addPolygon(v, 3);
    for (const char* name : {"p.png", "p.pdf", "p.svg"}) {
        writeImage(s, RenderOptions{}, dir() / name);
        EXPECT_GT(fs::file_size(dir() / name), 100u) << name;
    }
    EXPECT_EQ(entriesOf(dir()).size(), 3u);
}

}  // namespace
}  // namespace graftal
