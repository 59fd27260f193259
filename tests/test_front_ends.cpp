// Every front end gets the same picture: the graftal command, the studio's exports and live
// view, and an animation's last frame all go through the pipeline's stages, so one model
// must look the same in each (kolam dots and `spline: path` included), and a map L-system
// opened in the studio draws its cell layer.
#include <sys/inotify.h>
#include <unistd.h>

#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "graftal/lang/model.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/pipeline/animation.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/studio/studio_model.hpp"
#include "process.hpp"

namespace graftal {
namespace {

namespace fs = std::filesystem;
using testing::readFile;
using testing::runGraftal;

const fs::path kExamples = GRAFTAL_EXAMPLES_DIR;

// The examples' .l files that are string L-systems (not maps), sorted.
std::vector<fs::path> exampleModels() {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(kExamples))
        if (e.path().extension() == ".l" && !isMapLSystemFile(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

Model load(const fs::path& file) {
    ParseResult parsed = loadModel(file);
    if (!parsed.ok()) throw Error(parsed.errors());
    return std::move(parsed.model);
}

studio::ModelInput studioInput(const fs::path& file) {
    studio::ModelInput input;
    input.text = readFile(file);
    input.file = fs::absolute(file);
    return input;
}

fs::path scratchFolder() {
    const fs::path dir =
        fs::temp_directory_path() / ("graftal-front-ends-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

// Pixels of a PNG's bytes, as RGBA rows.
RgbaImage decodePng(const std::string& bytes) {
    struct Reader {
        const std::string* bytes;
        std::size_t at = 0;
    } reader{&bytes};
    auto read = [](void* closure, unsigned char* data, unsigned int length) {
        auto* r = static_cast<Reader*>(closure);
        if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
        std::copy_n(r->bytes->data() + r->at, length, data);
        r->at += length;
        return CAIRO_STATUS_SUCCESS;
    };
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
        cairo_image_surface_create_from_png_stream(read, &reader), &cairo_surface_destroy);
    EXPECT_EQ(cairo_surface_status(surface.get()), CAIRO_STATUS_SUCCESS);
    const int w = cairo_image_surface_get_width(surface.get());
    const int h = cairo_image_surface_get_height(surface.get());
    RgbaImage image(w, h);
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto pixel = *reinterpret_cast<const std::uint32_t*>(data + y * stride + 4 * x);
            std::uint8_t* out = &image.pixels[(std::size_t(y) * w + x) * 4];
            out[0] = std::uint8_t(pixel >> 16), out[1] = std::uint8_t(pixel >> 8);
            out[2] = std::uint8_t(pixel), out[3] = std::uint8_t(pixel >> 24);
        }
    return image;
}

// The share of pixels whose colour differs by more than 8 levels in some channel.
double differingShare(const RgbaImage& a, const RgbaImage& b) {
    if (a.width != b.width || a.height != b.height) return 1;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4)
        for (int k = 0; k < 3; ++k)
            if (std::abs(int(a.pixels[i + k]) - int(b.pixels[i + k])) > 8) {
                ++differing;
                break;
            }
    return double(differing) / (double(a.width) * a.height);
}

bool isInk(const RgbaImage& image) {
    for (std::size_t i = 0; i < image.pixels.size(); i += 4)
        if (image.pixels[i] < 200 || image.pixels[i + 1] < 200 || image.pixels[i + 2] < 200)
            return true;
    return false;
}

TEST(FrontEnds, EveryTwoDimensionalExampleLooksTheSameInTheCommandTheStudioAndAnAnimation) {
    const fs::path scratch = scratchFolder();
    const studio::StudioLimits limits;
    int compared = 0;
    for (const fs::path& file : exampleModels()) {
        SCOPED_TRACE(file.filename().string());
        const Model model = load(file);
        RenderRequest request;
        Derived d = derived(model, request);
        const Scene scene = drawn(model, shownString(model, d, request), request);
        if (scene.is3D || scene.segments.empty() || scene.segments.size() > 200'000) continue;

        // The command's SVG and the studio's export of the same model, byte for byte.
        const fs::path svg = scratch / "cli.svg";
        const testing::RunResult cli =
            runGraftal("render '" + file.string() + "' -o '" + svg.string() + "'");
        ASSERT_EQ(cli.status, 0) << cli.err;
        const studio::ExportedFile exported =
            studio::exportFile(studioInput(file), "svg", limits, {}, scratch);
        EXPECT_EQ(exported.bytes, readFile(svg));

        // The studio's live view draws the same segments in the same box.
        const studio::StudioPicture live =
            studio::derivePicture(studioInput(file), limits, {}, scratch);
        EXPECT_EQ(live.segments, scene.segments.size());
        const Scene liveScene = studio::pictureScene(live);
        EXPECT_EQ(liveScene.segments.size(), scene.segments.size());
        EXPECT_NEAR(liveScene.bounds().max.x, scene.bounds().max.x, 1e-9);
        EXPECT_NEAR(liveScene.bounds().min.y, scene.bounds().min.y, 1e-9);

        // An animation's last frame is the command's PNG.
        const fs::path png = scratch / "cli.png";
        ASSERT_EQ(runGraftal("render '" + file.string() + "' -o '" + png.string() + "'").status, 0);
        AnimationRequest animation;
        animation.from = d.steps;
        const std::vector<AnimationFrame> frames = animationFrames(model, animation);
        ASSERT_FALSE(frames.empty());
        const RgbaImage command = decodePng(readFile(png));
        EXPECT_TRUE(isInk(command));
        EXPECT_LE(differingShare(command, frames.back().image), 0.005);
        ++compared;
    }
    // Most of the gallery is 2D line art.
    EXPECT_GE(compared, 60);
    fs::remove_all(scratch);
}

TEST(FrontEnds, KolamDotsAndSplinePathsReachEveryFrontEnd) {
    const fs::path file = kExamples / "fig6.2-snake-kolam.l";
    const Model model = load(file);
    ASSERT_TRUE(model.view.kolam.dots || model.view.kolam.splineMode == SplineMode::Path);
    RenderRequest request;
    Derived d = derived(model, request);
    const Scene scene = drawn(model, shownString(model, d, request), request);
    ASSERT_FALSE(scene.discs.empty() && model.view.kolam.dots);

    const fs::path scratch = scratchFolder();
    const studio::StudioPicture live =
        studio::derivePicture(studioInput(file), studio::StudioLimits{}, {}, scratch);
    const Scene liveScene = studio::pictureScene(live);
    EXPECT_EQ(liveScene.discs.size(), scene.discs.size());
    EXPECT_EQ(liveScene.segments.size(), scene.segments.size());

    AnimationRequest animation;
    animation.from = d.steps;
    const std::vector<AnimationFrame> frames = animationFrames(model, animation);
    const fs::path png = scratch / "kolam.png";
    ASSERT_EQ(runGraftal("render '" + file.string() + "' -o '" + png.string() + "'").status, 0);
    EXPECT_LE(differingShare(decodePng(readFile(png)), frames.back().image), 0.005);
    fs::remove_all(scratch);
}

TEST(FrontEnds, AThreeDimensionalPlantIsTheSameFileFromTheCommandAndTheStudio) {
    const fs::path scratch = scratchFolder();
    for (const char* name : {"fig3.3-fibonacci-bush.l", "fig3.4-plant.l"}) {
        SCOPED_TRACE(name);
        const fs::path file = kExamples / name;
        for (const char* format : {"glb", "ply", "png"}) {
            const fs::path out = scratch / (std::string("cli.") + format);
            const testing::RunResult cli =
                runGraftal("render '" + file.string() + "' -o '" + out.string() + "'");
            ASSERT_EQ(cli.status, 0) << cli.err;
            const studio::ExportedFile exported =
                studio::exportFile(studioInput(file), format, studio::StudioLimits{}, {}, scratch);
            EXPECT_EQ(exported.bytes, readFile(out)) << format;
        }
    }
    fs::remove_all(scratch);
}

TEST(FrontEnds, StandardOutputGetsTheFileBytesWithoutAScratchFile) {
    const fs::path scratch = scratchFolder();
    const fs::path file = kExamples / "fig3.4-plant.l";
    const fs::path out = scratch / "plant.glb";
    ASSERT_EQ(runGraftal("render '" + file.string() + "' -o '" + out.string() + "'").status, 0);
    const testing::RunResult piped = runGraftal("render '" + file.string() + "' -o - --format glb");
    ASSERT_EQ(piped.status, 0) << piped.err;
    EXPECT_EQ(piped.out, readFile(out));
    // In memory, through the registry, the same bytes again.
    std::string bytes;
    ExportRequest request;
    request.format = "glb";
    exportModel(load(file), Destination::memory(bytes), request);
    EXPECT_EQ(bytes, readFile(out));
    fs::remove_all(scratch);
}

TEST(FrontEnds, AMapLSystemOpenedInTheStudioDrawsItsCellLayer) {
    const fs::path file = kExamples / "fig5.2-cell-layer.l";
    ASSERT_TRUE(isMapLSystemFile(file));
    const fs::path scratch = scratchFolder();
    studio::ModelInput input = studioInput(file);
    const ParseResult parsed = studio::parseInput(input);
    ASSERT_TRUE(parsed.ok());
    const studio::StudioPicture live =
        studio::derivePicture(input, studio::StudioLimits{}, {}, scratch);
    EXPECT_GT(live.segments, 10u);
    EXPECT_FALSE(live.lines.empty());

    // Its SVG download is the command's picture.
    const fs::path svg = scratch / "map.svg";
    ASSERT_EQ(runGraftal("render '" + file.string() + "' -o '" + svg.string() + "'").status, 0);
    EXPECT_EQ(studio::exportFile(input, "svg", studio::StudioLimits{}, {}, scratch).bytes,
              readFile(svg));
    fs::remove_all(scratch);
}

TEST(FrontEnds, TheStudioOffersEveryFormatADownloadCanHold) {
    // The page's export menu is the registry's rows, engraved scores included; only the
    // folder of frames and the derived string (the page shows it) are left out.
    std::vector<std::string_view> offered;
    for (const ExportFormat* f : studio::studioExportFormats()) offered.push_back(f->name);
    std::vector<std::string_view> expected;
    for (const ExportFormat& f : exportFormats())
        if (f.name != "frames" && f.kind != ExportKind::String) expected.push_back(f.name);
    EXPECT_EQ(offered, expected);
    EXPECT_NE(std::find(offered.begin(), offered.end(), "score-svg"), offered.end());

    // The LilyPond source downloaded is the command's file.
    const fs::path scratch = scratchFolder();
    const fs::path file = kExamples / "fig6.9-hilbert-music.l";
    const fs::path ly = scratch / "cli.ly";
    ASSERT_EQ(runGraftal("music '" + file.string() + "' -o '" + ly.string() + "'").status, 0);
    EXPECT_EQ(studio::exportFile(studioInput(file), "ly", studio::StudioLimits{}, {}, scratch).bytes,
              readFile(ly));
    fs::remove_all(scratch);
}

TEST(ExportRegistry, AnimationsAndMusicInMemoryAreTheFilesBytesAndNoScratchFile) {
    const fs::path scratch = scratchFolder();
    const Model music = load(kExamples / "fig6.9-hilbert-music.l");
    const Model plant = load(kExamples / "fig2.5a-koch-curve.l");
    for (const char* name : {"gif", "webp", "mp4", "mid", "wav", "musicxml", "ly"}) {
        SCOPED_TRACE(name);
        const ExportFormat* format = findExportFormat(name);
        ASSERT_NE(format, nullptr);
        const Model& model = format->kind == ExportKind::Music ? music : plant;
        ExportRequest request;
        request.format = name;
        request.steps = 3;
        request.picture.width = request.picture.height = 64;
        const fs::path file = scratch / ("out" + std::string(format->extension));
        exportModel(model, Destination::file(file), request);
        // Watched: nothing of this process's is created in the temporary folder (the watch
        // is first shown to see a file named as the writers named theirs).
        const int watch = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
        ASSERT_GE(watch, 0);
        const fs::path tmp = fs::temp_directory_path();
        ASSERT_GE(::inotify_add_watch(watch, tmp.c_str(), IN_CREATE), 0);
        const std::string ours = "graftal-" + std::to_string(::getpid()) + "-";
        const auto created = [&] {
            std::vector<std::string> names;
            alignas(inotify_event) char events[16384];
            for (ssize_t n; (n = ::read(watch, events, sizeof events)) > 0;)
                for (char* at = events; at < events + n;) {
                    const auto* event = reinterpret_cast<const inotify_event*>(at);
                    if (event->len > 0 && std::string(event->name).rfind(ours, 0) == 0)
                        names.emplace_back(event->name);
                    at += sizeof(inotify_event) + event->len;
                }
            return names;
        };
        std::ofstream(tmp / (ours + "probe")).put('x');
        fs::remove(tmp / (ours + "probe"));
        EXPECT_EQ(created(), std::vector<std::string>{ours + "probe"});
        std::string bytes;
        exportModel(model, Destination::memory(bytes, "download"), request);
        EXPECT_EQ(created(), std::vector<std::string>{});
        ::close(watch);
        EXPECT_GT(bytes.size(), 20u);
        EXPECT_EQ(bytes, readFile(file));
    }
    fs::remove_all(scratch);
}

TEST(ExportRegistry, OneRowPerFormatFoundByNameAndExtension) {
    EXPECT_EQ(findExportFormat("png")->kind, ExportKind::Picture);
    EXPECT_EQ(findExportFormat(".PDF")->kind, ExportKind::Picture);
    EXPECT_EQ(findExportFormat(".pdf", ExportKind::Music)->name, "score-pdf");
    EXPECT_EQ(findExportFormat(".midi")->name, "mid");
    EXPECT_EQ(findExportFormat("glb")->kind, ExportKind::Mesh);
    EXPECT_EQ(findExportFormat("webp")->kind, ExportKind::Animation);
    EXPECT_EQ(findExportFormat("xyz"), nullptr);
    std::vector<std::string_view> names;
    for (const ExportFormat& f : exportFormats()) {
        EXPECT_NE(f.write, nullptr) << f.name;
        EXPECT_EQ(std::count(names.begin(), names.end(), f.name), 0) << f.name;
        names.push_back(f.name);
    }
    EXPECT_GE(names.size(), 17u);
}

TEST(ExportRegistry, AnUnknownFormatIsAnErrorNamingTheKnownOnes) {
    std::string bytes;
    ExportRequest request;
    try {
        exportModel(Model{}, Destination::memory(bytes, "tree.xyz"), request);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(e.messages().find("tree.xyz: unknown file format"), std::string::npos)
            << e.messages();
        EXPECT_NE(e.messages().find(".glb"), std::string::npos);
    }
    EXPECT_TRUE(bytes.empty());
}

}  // namespace
}  // namespace graftal
