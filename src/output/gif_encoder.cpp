// Animated GIF through giflib. Each frame is written as the rectangle that changed since
// the previous one (the rest stays on screen), with its own palette of at most 256 colours:
// the exact colours when the rectangle has no more, otherwise giflib's median cut. With a
// global palette every frame is held until the end, and one palette is cut from them all.
#include <fcntl.h>
#include <gif_lib.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "graftal/core/atomic_file.hpp"
#include "graftal/output/animation_file.hpp"

namespace graftal {

namespace {

struct Rect {
    int x = 0, y = 0, width = 0, height = 0;
};

using Palette = std::vector<GifColorType>;

struct ChosenPalette {
    Palette colors;
    bool exact = true;  // every colour of the pixels is in it
};

std::uint32_t rgbKey(const std::uint8_t* p) {
    return (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
}

// The smallest rectangle holding every pixel that differs from `previous` (the whole
// picture for the first frame); at least one pixel, so that an unchanged frame still
// holds its time on screen.
Rect changedRect(const RgbaImage& frame, const RgbaImage* previous) {
    if (!previous) return {0, 0, frame.width, frame.height};
    int x0 = frame.width, y0 = frame.height, x1 = -1, y1 = -1;
    for (int y = 0; y < frame.height; ++y) {
        const std::uint8_t* a = frame.at(0, y);
        const std::uint8_t* b = previous->at(0, y);
        if (std::memcmp(a, b, std::size_t(frame.width) * 4) == 0) continue;
        y0 = std::min(y0, y);
        y1 = y;
        for (int x = 0; x < frame.width; ++x)
            if (std::memcmp(a + 4 * x, b + 4 * x, 3) != 0) {
                x0 = std::min(x0, x);
                x1 = std::max(x1, x);
            }
    }
    if (x1 < 0) return {0, 0, 1, 1};
    return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

// Maps colours to palette indices: exactly when the palette holds every colour, otherwise
// to the nearest entry, remembered per colour.
class ColorIndex {
  public:
    explicit ColorIndex(const Palette& palette) : palette_(palette) {}

    const GifColorType& color(std::uint8_t i) const { return palette_[i]; }

    std::uint8_t operator()(int r, int g, int b) {
        const std::uint32_t key = (std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | b;
        if (auto it = cache_.find(key); it != cache_.end()) return it->second;
        int best = 0;
        long bestDistance = -1;
        for (std::size_t i = 0; i < palette_.size(); ++i) {
            const long dr = r - palette_[i].Red, dg = g - palette_[i].Green,
                       db = b - palette_[i].Blue;
            const long d = 2 * dr * dr + 4 * dg * dg + 3 * db * db;
            if (bestDistance < 0 || d < bestDistance) {
                bestDistance = d;
                best = int(i);
            }
        }
        cache_.emplace(key, std::uint8_t(best));
        return std::uint8_t(best);
    }

  private:
    const Palette& palette_;
    std::unordered_map<std::uint32_t, std::uint8_t> cache_;
};

// A palette for the pixels of `images` inside their rectangles: their own colours when
// there are at most 256, otherwise a median cut of (a sample of) them.
ChosenPalette choosePalette(const std::vector<std::pair<const RgbaImage*, Rect>>& images) {
    std::unordered_map<std::uint32_t, int> seen;
    bool few = true;
    for (const auto& [image, r] : images) {
        for (int y = r.y; y < r.y + r.height && few; ++y)
            for (int x = r.x; x < r.x + r.width; ++x) {
                seen.emplace(rgbKey(image->at(x, y)), 0);
                if (seen.size() > 256) {
                    few = false;
                    break;
                }
            }
        if (!few) break;
    }
    Palette palette;
    if (few) {
        for (const auto& [key, unused] : seen)
            palette.push_back(
                GifColorType{GifByteType(key >> 16), GifByteType(key >> 8), GifByteType(key)});
        std::sort(palette.begin(), palette.end(), [](const GifColorType& a, const GifColorType& b) {
            return std::tie(a.Red, a.Green, a.Blue) < std::tie(b.Red, b.Green, b.Blue);
        });
        return {palette, true};
    }
    // Median cut over at most about two million pixels, evenly sampled.
    std::size_t total = 0;
    for (const auto& [image, r] : images) total += std::size_t(r.width) * r.height;
    const std::size_t stride = std::max<std::size_t>(1, total / 2'000'000);
    std::vector<GifByteType> red, green, blue;
    std::unordered_map<std::uint32_t, std::size_t> frequency;
    std::size_t n = 0;
    for (const auto& [image, r] : images)
        for (int y = r.y; y < r.y + r.height; ++y)
            for (int x = r.x; x < r.x + r.width; ++x, ++n)
                if (n % stride == 0) {
                    const std::uint8_t* p = image->at(x, y);
                    red.push_back(p[0]);
                    green.push_back(p[1]);
                    blue.push_back(p[2]);
                    ++frequency[rgbKey(p)];
                }
    std::vector<GifByteType> indices(red.size());
    palette.resize(256);
    int size = 256;
    if (GifQuantizeBuffer(unsigned(red.size()), 1, &size, red.data(), green.data(), blue.data(),
                          indices.data(), palette.data()) == GIF_ERROR)
        throw Error(SourceLocation{"graftal", 0, 0}, "GIF: colour quantisation failed");
    palette.resize(std::size_t(std::clamp(size, 1, 256)));
    // The median cut averages its boxes, so the background would come out a shade off
    // white; the most frequent colour (the background) keeps its exact value instead.
    const auto common =
        std::max_element(frequency.begin(), frequency.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    if (common != frequency.end()) {
        const GifColorType exact{GifByteType(common->first >> 16), GifByteType(common->first >> 8),
                                 GifByteType(common->first)};
        ColorIndex nearest(palette);
        palette[nearest(exact.Red, exact.Green, exact.Blue)] = exact;
    }
    return {palette, false};
}

// The rectangle's pixels as palette indices, with Floyd-Steinberg error diffusion when
// asked (only ever needed when the palette is not exact).
std::vector<GifPixelType> indexPixels(const RgbaImage& image, const Rect& r, ColorIndex& index,
                                      bool dither) {
    std::vector<GifPixelType> out(std::size_t(r.width) * r.height);
    if (!dither) {
        for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x) {
                const std::uint8_t* p = image.at(r.x + x, r.y + y);
                out[std::size_t(y) * r.width + x] = index(p[0], p[1], p[2]);
            }
        return out;
    }
    std::vector<std::array<float, 3>> error(std::size_t(r.width + 2) * 2, {0, 0, 0});
    auto err = [&](int row, int x) -> std::array<float, 3>& {
        return error[std::size_t(row & 1) * (r.width + 2) + x + 1];
    };
    for (int y = 0; y < r.height; ++y) {
        for (int x = -1; x <= r.width; ++x) err(y + 1, x) = {0, 0, 0};
        for (int x = 0; x < r.width; ++x) {
            const std::uint8_t* p = image.at(r.x + x, r.y + y);
            int c[3];
            for (int k = 0; k < 3; ++k)
                c[k] = std::clamp(int(std::lround(p[k] + err(y, x)[k])), 0, 255);
            const std::uint8_t i = index(c[0], c[1], c[2]);
            out[std::size_t(y) * r.width + x] = i;
            const GifColorType& q = index.color(i);
            const float e[3] = {float(c[0] - q.Red), float(c[1] - q.Green), float(c[2] - q.Blue)};
            for (int k = 0; k < 3; ++k) {
                err(y, x + 1)[k] += e[k] * 7 / 16;
                err(y + 1, x - 1)[k] += e[k] * 3 / 16;
                err(y + 1, x)[k] += e[k] * 5 / 16;
                err(y + 1, x + 1)[k] += e[k] * 1 / 16;
            }
        }
    }
    return out;
}

int paletteBits(std::size_t colors) {
    int bits = 1;
    while ((std::size_t(1) << bits) < colors) ++bits;
    return bits;
}

class GifEncoder final : public AnimationEncoder {
  public:
    GifEncoder(const std::filesystem::path& file, const AnimationEncoding& e)
        : path_(file), encoding_(e) {
        if (e.width <= 0 || e.height <= 0 || e.width > 65535 || e.height > 65535)
            throw fileError(path_, "GIF: frame size " + std::to_string(e.width) + "x" +
                                       std::to_string(e.height) + " is out of range (1 to 65535)");
        // Opened here rather than by giflib, which would make the file private (0600): a GIF
        // gets the permissions every other picture gets (0666 less the umask).
        const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0)
            throw fileError(path_, std::string("cannot write GIF: ") + std::strerror(errno));
        int error = 0;
        gif_ = EGifOpenFileHandle(fd, &error);
        if (!gif_) {
            ::close(fd);
            fail("cannot create the file", error);
        }
        EGifSetGifVersion(gif_, true);
    }

    ~GifEncoder() override {
        if (gif_) EGifCloseFile(gif_, nullptr);
    }

    void add(const RgbaImage& frame, double seconds) override {
        if (frame.width != encoding_.width || frame.height != encoding_.height)
            throw fileError(path_, "GIF: a frame of " + std::to_string(frame.width) + "x" +
                                       std::to_string(frame.height) + " in a " +
                                       std::to_string(encoding_.width) + "x" +
                                       std::to_string(encoding_.height) + " animation");
        const int delay = std::max(1, int(std::lround(seconds * 100)));
        if (encoding_.globalPalette) {
            held_.push_back({frame, delay});
            return;
        }
        if (!headerWritten_) writeHeader(nullptr);
        const Rect r = changedRect(frame, previous_ ? &*previous_ : nullptr);
        writeFrame(frame, r, choosePalette({{&frame, r}}), delay, true);
        previous_ = frame;
    }

    void finish() override {
        if (encoding_.globalPalette) {
            std::vector<std::pair<const RgbaImage*, Rect>> all;
            for (const auto& [frame, delay] : held_)
                all.push_back({&frame, Rect{0, 0, frame.width, frame.height}});
            const ChosenPalette palette = all.empty()
                                              ? ChosenPalette{{GifColorType{255, 255, 255}}, true}
                                              : choosePalette(all);
            writeHeader(&palette.colors);
            const RgbaImage* previous = nullptr;
            for (const auto& [frame, delay] : held_) {
                writeFrame(frame, changedRect(frame, previous), palette, delay, false);
                previous = &frame;
            }
        }
        if (!headerWritten_) writeHeader(nullptr);
        int error = 0;
        GifFileType* gif = gif_;
        gif_ = nullptr;
        if (EGifCloseFile(gif, &error) == GIF_ERROR) fail("cannot complete the file", error);
    }

  private:
    [[noreturn]] void fail(const std::string& what, int error) const {
        throw fileError(path_, "cannot write GIF: " + what + " (" + GifErrorString(error) + ")");
    }

    void check(int status, const char* what) const {
        if (status == GIF_ERROR) fail(what, gif_ ? gif_->Error : 0);
    }

    // The screen, an optional global palette and the loop-forever (NETSCAPE2.0) extension.
    void writeHeader(const Palette* global) {
        std::unique_ptr<ColorMapObject, decltype(&GifFreeMapObject)> map(nullptr,
                                                                         &GifFreeMapObject);
        if (global) map.reset(makeMap(*global));
        check(EGifPutScreenDesc(gif_, encoding_.width, encoding_.height, 8, 0, map.get()),
              "screen descriptor");
        static const GifByteType netscape[] = {'N', 'E', 'T', 'S', 'C', 'A',
                                               'P', 'E', '2', '.', '0'};
        static const GifByteType loop[] = {1, 0, 0};  // sub-block 1, loop count 0: forever
        check(EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE), "loop extension");
        check(EGifPutExtensionBlock(gif_, sizeof netscape, netscape), "loop extension");
        check(EGifPutExtensionBlock(gif_, sizeof loop, loop), "loop extension");
        check(EGifPutExtensionTrailer(gif_), "loop extension");
        headerWritten_ = true;
    }

    static ColorMapObject* makeMap(const Palette& palette) {
        const int bits = paletteBits(palette.size());
        std::vector<GifColorType> colors(std::size_t(1) << bits, GifColorType{0, 0, 0});
        std::copy(palette.begin(), palette.end(), colors.begin());
        return GifMakeMapObject(1 << bits, colors.data());
    }

    void writeFrame(const RgbaImage& frame, const Rect& r, const ChosenPalette& palette, int delay,
                    bool local) {
        GraphicsControlBlock gcb{};
        gcb.DisposalMode = DISPOSE_DO_NOT;
        gcb.UserInputFlag = false;
        gcb.DelayTime = delay;
        gcb.TransparentColor = NO_TRANSPARENT_COLOR;
        GifByteType extension[4];
        const std::size_t length = EGifGCBToExtension(&gcb, extension);
        check(EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, int(length), extension),
              "frame timing");
        std::unique_ptr<ColorMapObject, decltype(&GifFreeMapObject)> map(nullptr,
                                                                         &GifFreeMapObject);
        if (local) map.reset(makeMap(palette.colors));
        check(EGifPutImageDesc(gif_, r.x, r.y, r.width, r.height, false, map.get()),
              "image descriptor");
        ColorIndex index(palette.colors);
        std::vector<GifPixelType> pixels =
            indexPixels(frame, r, index, encoding_.dither && !palette.exact);
        for (int y = 0; y < r.height; ++y)
            check(EGifPutLine(gif_, pixels.data() + std::size_t(y) * r.width, r.width), "pixels");
    }

    std::filesystem::path path_;
    AnimationEncoding encoding_;
    GifFileType* gif_ = nullptr;
    bool headerWritten_ = false;
    std::optional<RgbaImage> previous_;
    std::vector<std::pair<RgbaImage, int>> held_;
};

}  // namespace

std::unique_ptr<AnimationEncoder> openGifEncoder(const std::filesystem::path& file,
                                                 const AnimationEncoding& encoding) {
    return std::make_unique<GifEncoder>(file, encoding);
}

}  // namespace graftal
