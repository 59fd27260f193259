// A folder of numbered PNG frames (frame-0001.png, ...), for other tools to assemble: each
// frame is written as it arrives, so nothing is held.
#include <cstdio>
#include <memory>
#include <string>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/destination.hpp"
#include "graftal/output/animation_file.hpp"
#include "png_encoder.hpp"

namespace graftal {

namespace {

class PngFramesEncoder final : public AnimationEncoder {
  public:
    PngFramesEncoder(const std::filesystem::path& folder, const AnimationEncoding& e)
        : folder_(folder), encoding_(e) {
        std::error_code ec;
        if (!std::filesystem::is_directory(folder, ec))
            throw fileError(folder, "cannot write frames: not a folder");
    }

    void add(const RgbaImage& frame, double) override {
        char name[32];
        std::snprintf(name, sizeof name, "frame-%04d.png", ++count_);
        writeRgbaPng(frame, folder_ / name);
    }

    void finish() override {}

  private:
    std::filesystem::path folder_;
    AnimationEncoding encoding_;
    int count_ = 0;
};

}  // namespace

std::unique_ptr<AnimationEncoder> openPngFramesEncoder(const std::filesystem::path& folder,
                                                       const AnimationEncoding& encoding) {
    return std::make_unique<PngFramesEncoder>(folder, encoding);
}

void writeRgbaPng(const RgbaImage& image, const std::filesystem::path& path) {
    writeRgbaPng(image, Destination::file(path));
}

void writeRgbaPng(const RgbaImage& image, const Destination& destination) {
    const std::filesystem::path& path = destination.path();
    destination.write("PNG", [&](std::ostream& out) {
        encodeRgbaPng(image.pixels.data(), image.width, image.height, out, path.c_str());
    });
}

}  // namespace graftal
