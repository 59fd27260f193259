// Animations as files: GIF (giflib), animated WebP (libwebp), MP4 H.264 (FFmpeg) and a
// folder of numbered PNG frames. Frames arrive one by one as RGBA images, so a sequence
// never has to be held whole; every format is written atomically (no partial output).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graftal/core/destination.hpp"

namespace graftal {

// An image in memory: RGBA8 pixels, rows top to bottom, no padding.
struct RgbaImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;  // width * height * 4 bytes

    RgbaImage() = default;
    RgbaImage(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 4, 255) {}
    const std::uint8_t* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 4]; }
    // An opaque image from packed RGB bytes (what the ray tracer makes).
    static RgbaImage fromRgb(const std::vector<std::uint8_t>& rgb, int w, int h) {
        RgbaImage image(w, h);
        for (std::size_t i = 0, n = std::size_t(w) * h; i < n; ++i)
            for (int k = 0; k < 3; ++k) image.pixels[4 * i + k] = rgb[3 * i + k];
        return image;
    }
    friend bool operator==(const RgbaImage&, const RgbaImage&) = default;
};

enum class AnimationFormat { Gif, WebP, Mp4, PngFrames };

// By the output's name: .gif, .webp, .mp4; a name without an extension (or ending in '/')
// is a folder of PNG frames. nullopt for any other extension.
std::optional<AnimationFormat> animationFormatFor(const std::filesystem::path& path);
// ".gif, .webp, .mp4 or a folder", for messages.
std::string animationFormatList();
std::string animationFormatName(AnimationFormat format);

struct AnimationEncoding {
    int width = 0, height = 0;  // every frame has this size
    double fps = 10;
    // GIF: one palette for the whole animation (all frames are held until the end) instead
    // of one per frame.
    bool globalPalette = false;
    // GIF: Floyd-Steinberg error diffusion when a frame has more than 256 colours. Off by
    // default: line art's few colours and antialiased edges look cleaner without it.
    bool dither = false;
    // WebP: every frame lossless; otherwise each frame takes the smaller of lossless and
    // lossy at `quality` (line art mostly comes out lossless, ray-traced pictures lossy).
    bool lossless = false;
    int quality = 85;  // WebP lossy quality and (mapped to a CRF) MP4 quality, 0-100
};

// Receives frames in order; `seconds` is how long a frame stays on screen.
class AnimationEncoder {
  public:
    virtual ~AnimationEncoder() = default;
    virtual void add(const RgbaImage& frame, double seconds) = 0;
    // Completes the file; before that it is not a valid animation.
    virtual void finish() = 0;
};

// Encoders writing to `file` (opened at once, so an unwritable place fails before any
// frame is made). Used through writeAnimation(), which makes the write atomic.
std::unique_ptr<AnimationEncoder> openGifEncoder(const std::filesystem::path& file,
                                                 const AnimationEncoding& encoding);
std::unique_ptr<AnimationEncoder> openWebPEncoder(const std::filesystem::path& file,
                                                  const AnimationEncoding& encoding);
std::unique_ptr<AnimationEncoder> openMp4Encoder(const std::filesystem::path& file,
                                                 const AnimationEncoding& encoding);
// Into an existing folder: frame-0001.png, frame-0002.png, ... (durations are not kept).
std::unique_ptr<AnimationEncoder> openPngFramesEncoder(const std::filesystem::path& folder,
                                                       const AnimationEncoding& encoding);

// Checks that `output` can be written (its folder exists; a frame folder that exists holds
// nothing but frames) before anything is rendered. Throws Error naming the output.
void checkAnimationOutput(const std::filesystem::path& output, AnimationFormat format);

// Opens the encoder on a temporary file (or folder) beside `output`, lets `produce` add the
// frames, finishes, and renames it into place. On any exception (Cancelled included) the
// temporary is removed and a previous `output` is left as it was. Throws Error.
void writeAnimation(const std::filesystem::path& output, AnimationFormat format,
                    const AnimationEncoding& encoding,
                    const std::function<void(AnimationEncoder&)>& produce);
// The same to a stream or memory (an animation in a download, a Python caller's bytes),
// through an anonymous file in memory: no file is made in any folder. A file destination is
// the call above.
void writeAnimation(const Destination& destination, AnimationFormat format,
                    const AnimationEncoding& encoding,
                    const std::function<void(AnimationEncoder&)>& produce);

// The PNG writer for one frame in memory (atomically, like every writer).
void writeRgbaPng(const RgbaImage& image, const std::filesystem::path& path);
// The same to any destination (a file is written atomically).
void writeRgbaPng(const RgbaImage& image, const Destination& destination);

}  // namespace graftal
