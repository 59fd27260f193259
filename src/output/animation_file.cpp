// Choosing an animation format by name, and writing any of them atomically: a temporary
// file (or folder) beside the output, renamed into place only when complete.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <string>
#include <system_error>

#include "graftal/core/atomic_file.hpp"
#include "graftal/output/animation_file.hpp"

namespace graftal {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// A folder of frames written before may be replaced; a folder holding anything else is the
// user's and is never touched.
bool holdsOnlyFrames(const fs::path& folder) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() || name.rfind("frame-", 0) != 0 ||
            lowerExtension(entry.path()) != ".png")
            return false;
    }
    return !ec;
}

// Tells an encoder's failures from those of the code that hands it frames.
struct EncoderErrors final : AnimationEncoder {
    explicit EncoderErrors(AnimationEncoder& e) : inner(e) {}
    void add(const RgbaImage& frame, double seconds) override {
        try {
            inner.add(frame, seconds);
        } catch (...) {
            failed = true;
            throw;
        }
    }
    void finish() override { inner.finish(); }

    AnimationEncoder& inner;
    bool failed = false;
};

void writeFrameFolder(const fs::path& output, const AnimationEncoding& encoding,
                      const std::function<void(AnimationEncoder&)>& produce) {
    const fs::path temporary = temporaryPathBeside(output);
    std::error_code ec;
    if (!fs::create_directory(temporary, ec) || ec)
        throw fileError(output, "cannot write frames: cannot create a folder beside it: " +
                                    (ec ? ec.message() : std::string("it exists")));
    try {
        auto encoder = openPngFramesEncoder(temporary, encoding);
        produce(*encoder);
        encoder->finish();
        fs::path previous;
        if (fs::exists(output, ec)) {
            previous = temporaryPathBeside(output);
            fs::rename(output, previous, ec);
            if (ec) throw fileError(output, "cannot replace the frames: " + ec.message());
        }
        fs::rename(temporary, output, ec);
        if (ec) {
            if (!previous.empty()) fs::rename(previous, output, ec);
            throw fileError(output, "cannot write frames: " + ec.message());
        }
        if (!previous.empty()) fs::remove_all(previous, ec);
    } catch (...) {
        fs::remove_all(temporary, ec);
        throw;
    }
}

}  // namespace

std::optional<AnimationFormat> animationFormatFor(const fs::path& path) {
    const std::string text = path.string();
    if (!text.empty() && text.back() == '/') return AnimationFormat::PngFrames;
    const std::string ext = lowerExtension(path);
    if (ext == ".gif") return AnimationFormat::Gif;
    if (ext == ".webp") return AnimationFormat::WebP;
    if (ext == ".mp4") return AnimationFormat::Mp4;
    if (ext.empty()) return AnimationFormat::PngFrames;
    return std::nullopt;
}

std::string animationFormatList() {
    return ".gif, .webp, .mp4 or a folder name (PNG frames)";
}

std::string animationFormatName(AnimationFormat format) {
    switch (format) {
        case AnimationFormat::Gif:
            return "GIF";
        case AnimationFormat::WebP:
            return "WebP";
        case AnimationFormat::Mp4:
            return "MP4";
        case AnimationFormat::PngFrames:
            return "PNG frames";
    }
    return "animation";
}

void checkAnimationOutput(const fs::path& output, AnimationFormat format) {
    fs::path target = output;
    if (format == AnimationFormat::PngFrames && !target.has_filename())
        target = target.parent_path();
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    const std::string what = animationFormatName(format);
    if (!fs::is_directory(dir, ec))
        throw fileError(output,
                        "cannot write " + what + ": '" + dir.string() +
                            (fs::exists(dir, ec) ? "' is not a directory" : "' does not exist"));
    // A file made and removed at once: the folder takes new files (permissions, read-only
    // file systems) before a single frame is rendered.
    const fs::path probe = temporaryPathBeside(target);
    if (std::FILE* f = std::fopen(probe.c_str(), "wb")) {
        std::fclose(f);
        fs::remove(probe, ec);
    } else {
        throw fileError(output,
                        "cannot write " + what + ": cannot create files in '" + dir.string() + "'");
    }
    if (format == AnimationFormat::PngFrames) {
        if (fs::exists(target, ec) && !fs::is_directory(target, ec))
            throw fileError(output, "cannot write frames: it exists and is not a folder");
        if (fs::is_directory(target, ec) && !holdsOnlyFrames(target))
            throw fileError(output,
                            "cannot write frames: the folder holds other files than frame-*.png");
    } else if (fs::is_directory(target, ec)) {
        throw fileError(output, "cannot write " + what + ": it is a folder");
    }
}

namespace {

// Encodes the frames `produce` gives into `file` (any name: the format is given). Errors of
// whatever makes the frames (a derivation's, Cancelled) are kept in `producerError`.
void encodeFrames(const fs::path& file, AnimationFormat format, const AnimationEncoding& encoding,
                  const std::function<void(AnimationEncoder&)>& produce,
                  std::exception_ptr& producerError) {
    std::unique_ptr<AnimationEncoder> encoder;
    switch (format) {
        case AnimationFormat::Gif:
            encoder = openGifEncoder(file, encoding);
            break;
        case AnimationFormat::WebP:
            encoder = openWebPEncoder(file, encoding);
            break;
        case AnimationFormat::Mp4:
            encoder = openMp4Encoder(file, encoding);
            break;
        case AnimationFormat::PngFrames:
            break;
    }
    EncoderErrors watched(*encoder);
    try {
        produce(watched);
    } catch (...) {
        if (!watched.failed) producerError = std::current_exception();
        throw;
    }
    encoder->finish();
}

}  // namespace

void writeAnimation(const Destination& destination, AnimationFormat format,
                    const AnimationEncoding& encoding,
                    const std::function<void(AnimationEncoder&)>& produce) {
    if (destination.kind() == Destination::Kind::File) {
        writeAnimation(destination.path(), format, encoding, produce);
        return;
    }
    if (format == AnimationFormat::PngFrames)
        throw fileError(destination.path(),
                        "a folder of PNG frames can only be written to a folder on disk");
    std::exception_ptr producerError;
    try {
        destination.writeThroughFile(animationFormatName(format), [&](const fs::path& file) {
            encodeFrames(file, format, encoding, produce, producerError);
        });
    } catch (...) {
        if (producerError) std::rethrow_exception(producerError);
        throw;
    }
}

void writeAnimation(const fs::path& output, AnimationFormat format,
                    const AnimationEncoding& encoding,
                    const std::function<void(AnimationEncoder&)>& produce) {
    checkAnimationOutput(output, format);
    if (format == AnimationFormat::PngFrames) {
        writeFrameFolder(output.has_filename() ? output : output.parent_path(), encoding, produce);
        return;
    }
    // Errors of the encoders name the output (writeFileAtomically sees to it); errors of
    // whatever makes the frames (a derivation's, Cancelled) pass through as they are.
    std::exception_ptr producerError;
    try {
        writeFileAtomically(
            output,
            [&](const fs::path& temporary) {
                encodeFrames(temporary, format, encoding, produce, producerError);
            },
            animationFormatName(format));
    } catch (...) {
        if (producerError) std::rethrow_exception(producerError);
        throw;
    }
}

}  // namespace graftal
