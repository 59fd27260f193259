// Animations: the frames of a development drawn by one fixed camera, and the files they
// are encoded into, decoded back with the libraries' own decoders.
#include <gif_lib.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <webp/demux.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include "graftal/graftal.hpp"
#include "process.hpp"
#include "test_helpers.hpp"

using namespace graftal;
using graftal::testing::loadExample;
using graftal::testing::parseModel;
using graftal::testing::readFile;
using graftal::testing::runGraftal;
using graftal::testing::TempDir;

namespace fs = std::filesystem;

namespace {

// A bush that grows upward from the origin: every step adds a level of branches.
const char* kBush =
    "Lsystem: 1\nderivation length: 4\nangle increment: 30\naxiom: F(1) A\n"
    "A --> F(1) [+A] [-A] F(0.5) A\nendlsystem\n";

std::string example(const std::string& name) {
    return (fs::path(GRAFTAL_EXAMPLES_DIR) / name).string();
}

AnimationRequest smallRequest(int size = 64) {
    AnimationRequest r;
    r.picture.width = r.picture.height = size;
    r.samplesPerPixel = 1;
    r.picture.lineWidth = 2;  // thick enough that every line has dark pixels
    return r;
}

// The GIF as a player shows it: every frame composited over the previous one.
struct DecodedGif {
    int width = 0, height = 0;
    std::vector<int> delays;                         // centiseconds
    std::vector<std::vector<std::uint32_t>> frames;  // RGB per pixel
};

DecodedGif decodeGif(const fs::path& path) {
    int error = 0;
    GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
    EXPECT_NE(gif, nullptr) << GifErrorString(error);
    DecodedGif out;
    if (!gif) return out;
    EXPECT_EQ(DGifSlurp(gif), GIF_OK);
    out.width = gif->SWidth;
    out.height = gif->SHeight;
    std::vector<std::uint32_t> canvas(std::size_t(out.width) * out.height, 0);
    for (int i = 0; i < gif->ImageCount; ++i) {
        const SavedImage& image = gif->SavedImages[i];
        GraphicsControlBlock gcb;
        EXPECT_EQ(DGifSavedExtensionToGCB(gif, i, &gcb), GIF_OK);
        out.delays.push_back(gcb.DelayTime);
        const ColorMapObject* map =
            image.ImageDesc.ColorMap ? image.ImageDesc.ColorMap : gif->SColorMap;
        EXPECT_NE(map, nullptr);
        const GifImageDesc& d = image.ImageDesc;
        for (int y = 0; y < d.Height; ++y)
            for (int x = 0; x < d.Width; ++x) {
                const GifColorType c = map->Colors[image.RasterBits[y * d.Width + x]];
                canvas[std::size_t(d.Top + y) * out.width + d.Left + x] =
                    (std::uint32_t(c.Red) << 16) | (std::uint32_t(c.Green) << 8) | c.Blue;
            }
        out.frames.push_back(canvas);
    }
    DGifCloseFile(gif, &error);
    return out;
}

// The lowest row with ink and the middle of its ink: where the base of an upright plant is.
std::pair<int, double> basePixel(const RgbaImage& image) {
    for (int y = image.height - 1; y >= 0; --y) {
        int count = 0;
        double sum = 0;
        for (int x = 0; x < image.width; ++x)
            if (image.at(x, y)[0] < 128) {
                ++count;
                sum += x;
            }
        if (count > 0) return {y, sum / count};
    }
    return {-1, -1};
}

std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path().filename());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

TEST(Animation, OneFramePerStepFromTheAxiomToTheDerivationLength) {
    AnimationResult result;
    auto frames = animationFrames(parseModel(kBush), smallRequest(), &result);
    ASSERT_EQ(frames.size(), 5u);
    EXPECT_EQ(result.from, 0);
    EXPECT_EQ(result.to, 4);
    EXPECT_EQ(result.route, RenderRoute::LineArt);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        EXPECT_EQ(frames[i].index, int(i));
        EXPECT_EQ(frames[i].step, int(i));
        EXPECT_EQ(frames[i].image.width, 64);
        EXPECT_EQ(frames[i].image.height, 64);
        EXPECT_DOUBLE_EQ(frames[i].seconds, 0.1);
        if (i > 0) {
            EXPECT_NE(frames[i].image, frames[i - 1].image) << "frame " << i;
        }
    }
}

TEST(Animation, TheCameraStaysFixedWhileThePlantGrows) {
    AnimationRequest request = smallRequest(96);
    request.from = 1;
    auto frames = animationFrames(parseModel(kBush), request);
    ASSERT_EQ(frames.size(), 4u);
    // The middle of the first internode, (0, 0.5), drawn in every frame, is at the pixel
    // the fixed camera puts it.
    Model bush = parseModel(kBush);
    AnimationResult result;
    frames = animationFrames(bush, request, &result);
    const ImageTransform fixed = ImageTransform::fit(result.frame, request.picture);
    const int x = int(fixed.x(Vec3{0, 0.5, 0})), y = int(fixed.y(Vec3{0, 0.5, 0}));
    for (const auto& f : frames) EXPECT_LT(f.image.at(x, y)[0], 100) << "step " << f.step;
    // Each step framed on its own bounds (as `render` frames one picture) would put it
    // elsewhere: the check above would see a camera that follows the plant.
    RenderOptions o = request.picture;
    const ImageTransform first = ImageTransform::fit(interpret(bush, derive(bush, 1)).bounds(), o);
    const ImageTransform last = ImageTransform::fit(interpret(bush, derive(bush, 4)).bounds(), o);
    EXPECT_GT(std::abs(first.y(Vec3{0, 0.5, 0}) - last.y(Vec3{0, 0.5, 0})), 5);
    const auto base = basePixel(frames[0].image);
    for (const auto& f : frames) EXPECT_EQ(basePixel(f.image).first, base.first);
}

TEST(Animation, GifDecodesBackWithItsFramesSizeAndDelays) {
    TempDir dir;
    const fs::path out = dir.path() / "bush.gif";
    const auto bush = dir.write("bush.l", kBush);
    auto r = runGraftal("animate " + bush.string() + " -o " + out.string() +
                        " --size 80x60 --fps 5 --hold 2");
    ASSERT_EQ(r.status, 0) << r.err;
    const DecodedGif gif = decodeGif(out);
    EXPECT_EQ(gif.width, 80);
    EXPECT_EQ(gif.height, 60);
    ASSERT_EQ(gif.frames.size(), 5u);
    EXPECT_EQ(gif.delays, (std::vector<int>{20, 20, 20, 20, 220}));
    for (std::size_t i = 1; i < gif.frames.size(); ++i)
        EXPECT_NE(gif.frames[i], gif.frames[i - 1]) << "frame " << i;
    // The first frame (the axiom: one segment) is mostly background, the last is not.
    auto ink = [](const std::vector<std::uint32_t>& f) {
        return std::count_if(f.begin(), f.end(), [](std::uint32_t c) { return c != 0xFFFFFF; });
    };
    EXPECT_LT(ink(gif.frames.front()), ink(gif.frames.back()));
}

TEST(Animation, GifWithOneGlobalPaletteShowsTheSameFrames) {
    TempDir dir;
    AnimationRequest request = smallRequest();
    request.output = dir.path() / "local.gif";
    Model bush = parseModel(kBush);
    writeAnimationFile(bush, request);
    request.output = dir.path() / "global.gif";
    request.globalPalette = true;
    writeAnimationFile(bush, request);
    const DecodedGif local = decodeGif(dir.path() / "local.gif");
    const DecodedGif global = decodeGif(dir.path() / "global.gif");
    ASSERT_EQ(global.frames.size(), 5u);
    // Line art in black on white has few colours: both palettes hold them exactly.
    EXPECT_EQ(local.frames, global.frames);
    EXPECT_EQ(filesIn(dir.path()), (std::vector<fs::path>{"global.gif", "local.gif"}));
}

TEST(Animation, Mp4IsH264WithEveryFrameAndTheHold) {
    TempDir dir;
    AnimationRequest request = smallRequest();
    request.output = dir.path() / "bush.mp4";
    request.fps = 10;
    request.holdSeconds = 1;
    writeAnimationFile(parseModel(kBush), request);

    AVFormatContext* format = nullptr;
    ASSERT_EQ(avformat_open_input(&format, request.output.c_str(), nullptr, nullptr), 0);
    ASSERT_GE(avformat_find_stream_info(format, nullptr), 0);
    ASSERT_EQ(format->nb_streams, 1u);
    const AVStream* stream = format->streams[0];
    EXPECT_EQ(stream->codecpar->codec_id, AV_CODEC_ID_H264);
    EXPECT_EQ(stream->codecpar->width, 64);
    EXPECT_EQ(stream->codecpar->height, 64);
    // 5 frames and 1 s of the last one held at 10 frames per second: 15 frames, 1.5 s.
    EXPECT_EQ(stream->nb_frames, 15);
    EXPECT_NEAR(stream->duration * av_q2d(stream->time_base), 1.5, 0.01);
    avformat_close_input(&format);
}

TEST(Animation, WebPDecodesBackFrameByFrame) {
    TempDir dir;
    AnimationRequest request = smallRequest();
    request.output = dir.path() / "bush.webp";
    writeAnimationFile(parseModel(kBush), request);
    const std::string bytes = readFile(request.output);
    WebPData data{reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()};
    WebPAnimDecoderOptions options;
    ASSERT_TRUE(WebPAnimDecoderOptionsInit(&options));
    WebPAnimDecoder* decoder = WebPAnimDecoderNew(&data, &options);
    ASSERT_NE(decoder, nullptr);
    WebPAnimInfo info;
    ASSERT_TRUE(WebPAnimDecoderGetInfo(decoder, &info));
    EXPECT_EQ(info.canvas_width, 64u);
    EXPECT_EQ(info.frame_count, 5u);
    int decoded = 0, last = 0;
    while (WebPAnimDecoderHasMoreFrames(decoder)) {
        std::uint8_t* pixels = nullptr;
        int timestamp = 0;
        ASSERT_TRUE(WebPAnimDecoderGetNext(decoder, &pixels, &timestamp));
        ++decoded;
        last = timestamp;
    }
    EXPECT_EQ(decoded, 5);
    EXPECT_EQ(last, 500);  // the end of the fifth frame of 100 ms
    WebPAnimDecoderDelete(decoder);
}

TEST(Animation, PngFramesGoToAFolderThatIsReplacedWhole) {
    TempDir dir;
    const auto bush = dir.write("bush.l", kBush);
    const fs::path frames = dir.path() / "frames";
    auto r = runGraftal("animate " + bush.string() + " -o " + frames.string() + " --size 32x32");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(filesIn(frames),
              (std::vector<fs::path>{"frame-0001.png", "frame-0002.png", "frame-0003.png",
                                     "frame-0004.png", "frame-0005.png"}));
    r = runGraftal("animate " + bush.string() + " -o " + frames.string() + " --to 1 --size 32x32");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(filesIn(frames), (std::vector<fs::path>{"frame-0001.png", "frame-0002.png"}));
    // A folder that holds anything else is not the command's to replace.
    std::ofstream(frames / "notes.txt") << "mine";
    r = runGraftal("animate " + bush.string() + " -o " + frames.string() + " --size 32x32");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("holds other files"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(frames / "notes.txt"));
    EXPECT_EQ(filesIn(dir.path()), (std::vector<fs::path>{"bush.l", "frames"}));
}

TEST(Animation, TurntableFramesDifferWhileTheStringDoesNot) {
    const std::string lychnis = example("fig3.9-lychnis-3d.l");
    Model model = loadExample(lychnis);
    AnimationRequest request = smallRequest(48);
    request.from = 6;
    request.to = 6;
    request.lastFrames = 3;
    request.turntableDegrees = 40;
    AnimationResult result;
    auto frames = animationFrames(model, request, &result);
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(result.route, RenderRoute::RayTraced);
    for (const auto& f : frames) EXPECT_EQ(f.step, 6);
    EXPECT_NE(frames[0].image, frames[1].image);
    EXPECT_NE(frames[1].image, frames[2].image);
    // Without the turntable the three frames are one picture.
    request.turntableDegrees = 0;
    auto still = animationFrames(model, request);
    EXPECT_EQ(still[0].image, still[2].image);
}

TEST(Animation, TurntableTurnsLineArtToo) {
    AnimationRequest request = smallRequest();
    request.from = 2;
    request.to = 2;
    request.lastFrames = 2;
    request.turntableDegrees = 60;
    auto frames = animationFrames(parseModel(kBush), request);
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_NE(frames[0].image, frames[1].image);
}

TEST(Animation, BadOptionsAreClearErrorsAndLeaveNoFile) {
    TempDir dir;
    const auto bush = dir.write("bush.l", kBush);
    const std::string out = (dir.path() / "a.gif").string();
    auto r = runGraftal("animate " + bush.string() + " -o " + out + " --from 3 --to 2");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--from 3 is after --to 2"), std::string::npos) << r.err;
    r = runGraftal("animate " + bush.string() + " -o " + out + " --from 7");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--from 7 is after the last step, 4"), std::string::npos) << r.err;
    r = runGraftal("animate " + bush.string() + " -o " + (dir.path() / "a.avi").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("unknown animation format"), std::string::npos) << r.err;
    r = runGraftal("animate " + bush.string() + " -o " + (dir.path() / "no/such/a.gif").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
    // A "folder" that is a file cannot take the output either.
    r = runGraftal("animate " + bush.string() + " -o " + (bush / "a.gif").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("is not a directory"), std::string::npos) << r.err;
    r = runGraftal("animate " + bush.string() + " -o " + out + " --fps 0");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--fps"), std::string::npos) << r.err;
    EXPECT_EQ(filesIn(dir.path()), (std::vector<fs::path>{"bush.l"}));
}

TEST(Animation, AFolderThatCannotBeWrittenIsRefusedBeforeRendering) {
    if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
    TempDir dir;
    const auto bush = dir.write("bush.l", kBush);
    const fs::path locked = dir.path() / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    auto r = runGraftal("animate " + bush.string() + " -o " + (locked / "a.gif").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("cannot create files in"), std::string::npos) << r.err;
    r = runGraftal("animate " + bush.string() + " -o " + (locked / "frames").string());
    EXPECT_EQ(r.status, 1);
    fs::permissions(locked, fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(locked));
}

TEST(Animation, CancelledLeavesNoFileBehind) {
    TempDir dir;
    for (const char* name : {"c.gif", "c.webp", "c.mp4", "frames"}) {
        AnimationRequest request = smallRequest();
        request.output = dir.path() / name;
        request.frameProgress = [&](int done, int) {
            if (done == 2) request.cancel.cancel();
        };
        EXPECT_THROW(writeAnimationFile(parseModel(kBush), request), Cancelled) << name;
        EXPECT_TRUE(fs::is_empty(dir.path())) << name;
    }
}

TEST(Animation, ModelsWithoutAgesGetInBetweenFramesOfTheCameraOnly) {
    AnimationRequest request = smallRequest();
    request.framesPerStep = 3;
    std::vector<std::string> notes;
    request.notify = [&](const Diagnostic& d) { notes.push_back(d.message); };
    AnimationResult result;
    auto frames = animationFrames(parseModel(kBush), request, &result);
    ASSERT_EQ(frames.size(), 13u);  // 4 steps of 3 frames, and the last step
    EXPECT_FALSE(result.continuous);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("declares no module ages"), std::string::npos) << notes[0];
    EXPECT_EQ(frames[0].image, frames[1].image);
    EXPECT_NE(frames[2].image, frames[3].image);
    EXPECT_DOUBLE_EQ(frames[4].age, 1 + 1.0 / 3);
}

TEST(Animation, DeclaredAgesGrowThePlantBetweenSteps) {
    // An internode that lengthens with age up to 4 units, and an apex that makes one.
    const char* text =
        "Lsystem: 1\nderivation length: 3\nage: I(t)\naxiom: A\n"
        "A --> I(0) A\nI(t) --> I(t+1)\nhomomorphism\nI(t) --> F(min(t, 4))\nendlsystem\n";
    Model model = parseModel(text);
    ASSERT_EQ(model.lsystem.ages.size(), 1u);
    AnimationRequest request = smallRequest();
    request.framesPerStep = 4;
    AnimationResult result;
    auto frames = animationFrames(model, request, &result);
    ASSERT_EQ(frames.size(), 13u);
    EXPECT_TRUE(result.continuous);
    // From the first internode on (frame 4, step 1, is I(0): no length yet), every frame
    // shows more stem than the one before: the plant grows between steps.
    auto ink = [](const RgbaImage& image) {
        int n = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) n += image.at(x, y)[0] < 128;
        return n;
    };
    EXPECT_EQ(ink(frames[3].image), 0);
    for (std::size_t i = 5; i < frames.size(); ++i)
        EXPECT_GT(ink(frames[i].image), ink(frames[i - 1].image)) << "frame " << i;
    // The strings are the L-system's own: the derivation does not see the ages.
    EXPECT_EQ(derive(model, 2).toString(model.lsystem.symbols), "I(1)I(0)A");
}

TEST(Animation, AgeDeclarationsNameOneParameter) {
    EXPECT_EQ(graftal::testing::parseError("Lsystem: 1\nage: F(l, a)\naxiom: F(1,0)\nendlsystem\n"),
              "test.l:2:6: error: 'age:' names one parameter of 'F' as its age: write F(a), or "
              "F(_, a) with _ for "
              "the other parameters");
    Model m = parseModel("Lsystem: 1\nage: F(_, a) I(i)\naxiom: F(1,0)\nendlsystem\n");
    ASSERT_EQ(m.lsystem.ages.size(), 2u);
    EXPECT_EQ(m.lsystem.ages[0].symbol, Symbol('F'));
    EXPECT_EQ(m.lsystem.ages[0].parameter, 1u);
    EXPECT_EQ(m.lsystem.ages[1].symbol, Symbol('I'));
    EXPECT_EQ(m.lsystem.ages[1].parameter, 0u);
    // Printed back as the language writes it, and read again to the same declarations.
    std::ostringstream printed;
    m.lsystem.print(printed);
    EXPECT_NE(printed.str().find("age: F(_, a)\nage: I(a)\n"), std::string::npos) << printed.str();
    EXPECT_EQ(parseModel(printed.str()).lsystem.ages.size(), 2u);
}

TEST(Animation, RayTracedGifsAreQuantisedWithOrWithoutDithering) {
    TempDir dir;
    Model lychnis = loadExample(example("fig3.9-lychnis-3d.l"));
    AnimationRequest request = smallRequest(128);
    request.samplesPerPixel = 4;  // shading and antialiasing: far more than 256 colours
    request.from = 5;
    request.to = 6;
    for (bool dither : {false, true}) {
        request.dither = dither;
        request.output = dir.path() / (dither ? "dithered.gif" : "plain.gif");
        writeAnimationFile(lychnis, request);
        const DecodedGif gif = decodeGif(request.output);
        ASSERT_EQ(gif.frames.size(), 2u);
        // A ray-traced plant has more than two colours, and the background stays white.
        std::set<std::uint32_t> colours(gif.frames[1].begin(), gif.frames[1].end());
        EXPECT_GT(colours.size(), 8u);
        EXPECT_EQ(gif.frames[1][0], 0xFFFFFFu);
    }
    EXPECT_NE(readFile(dir.path() / "plain.gif"), readFile(dir.path() / "dithered.gif"));
}

namespace {

// Pixels that are not the background colour (the top-left corner's).
std::size_t inkPixels(const RgbaImage& image) {
    std::size_t n = 0;
    const std::uint8_t* corner = image.at(0, 0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (!std::equal(corner, corner + 3, image.at(x, y))) ++n;
    return n;
}

}  // namespace

TEST(Animation, AStringThatDrawsNothingAnimatesItsDerivationRowByRow) {
    // Anabaena's filament (Fig 1.4) has no turtle meaning: its development is the diagram
    // of its derivation, one row more each step, the cells where the last frame has them.
    Model model = loadExample(example("fig1.4-anabaena.l"));
    AnimationRequest request = smallRequest(300);
    request.to = 4;
    AnimationResult result;
    auto frames = animationFrames(model, request, &result);
    EXPECT_EQ(result.route, RenderRoute::DerivationDiagram);
    ASSERT_EQ(frames.size(), 5u);
    ASSERT_FALSE(result.notes.empty());
    EXPECT_NE(result.notes.front().message.find("derivation"), std::string::npos);
    for (std::size_t i = 1; i < frames.size(); ++i) {
        EXPECT_EQ(frames[i].step, int(i));
        EXPECT_GT(inkPixels(frames[i].image), inkPixels(frames[i - 1].image)) << i;
    }
    // The rows drawn stay where they are: the axiom's row of the first frame is the same
    // pixels in the last.
    const RgbaImage& first = frames.front().image;
    const RgbaImage& last = frames.back().image;
    std::size_t same = 0, inked = 0;
    for (int y = 0; y < first.height; ++y)
        for (int x = 0; x < first.width; ++x)
            if (!std::equal(first.at(0, 0), first.at(0, 0) + 3, first.at(x, y))) {
                ++inked;
                same += std::equal(first.at(x, y), first.at(x, y) + 4, last.at(x, y));
            }
    ASSERT_GT(inked, 0u);
    EXPECT_EQ(same, inked);

    // Asked for on a model that draws (the bush), --derivation animates the diagram too;
    // it does not turn.
    AnimationRequest asked = smallRequest(200);
    asked.derivationDiagram = true;
    AnimationResult bush;
    EXPECT_EQ(animationFrames(parseModel(kBush), asked, &bush).size(), 5u);
    EXPECT_EQ(bush.route, RenderRoute::DerivationDiagram);
    asked.turntableDegrees = 10;
    EXPECT_THROW(animationFrames(parseModel(kBush), asked), Error);
}
