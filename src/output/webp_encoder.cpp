// Animated WebP through libwebp's WebPAnimEncoder: each frame is encoded as it arrives
// (lossless or lossy, whichever is smaller for the frame) and the encoder itself keeps only
// the compressed frames; the file is assembled at the end.
#include <webp/encode.h>
#include <webp/mux.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "graftal/core/atomic_file.hpp"
#include "graftal/output/animation_file.hpp"

namespace graftal {

namespace {

class WebPEncoder final : public AnimationEncoder {
  public:
    WebPEncoder(const std::filesystem::path& file, const AnimationEncoding& e)
        : path_(file), encoding_(e) {}

    // Separate from the constructor so that the destructor frees what a failure leaves.
    void open() {
        const AnimationEncoding& e = encoding_;
        const std::filesystem::path& file = path_;
        if (e.width <= 0 || e.height <= 0 || e.width > WEBP_MAX_DIMENSION ||
            e.height > WEBP_MAX_DIMENSION)
            throw fileError(path_, "WebP: frame size " + std::to_string(e.width) + "x" +
                                       std::to_string(e.height) + " is out of range (1 to " +
                                       std::to_string(WEBP_MAX_DIMENSION) + ")");
        file_ = std::fopen(file.c_str(), "wb");
        if (!file_)
            throw fileError(path_, std::string("cannot write WebP: ") + std::strerror(errno));
        WebPAnimEncoderOptions options;
        if (!WebPAnimEncoderOptionsInit(&options) || !WebPConfigInit(&config_))
            throw fileError(path_, "cannot write WebP: libwebp version mismatch");
        options.anim_params.loop_count = 0;  // forever
        options.allow_mixed = e.lossless ? 0 : 1;
        encoder_ = WebPAnimEncoderNew(e.width, e.height, &options);
        if (!encoder_) throw fileError(path_, "cannot write WebP: cannot start the encoder");
        config_.lossless = e.lossless ? 1 : 0;
        config_.quality = float(e.quality);
        config_.method = 4;
    }

    ~WebPEncoder() override {
        if (encoder_) WebPAnimEncoderDelete(encoder_);
        if (file_) std::fclose(file_);
    }

    void add(const RgbaImage& frame, double seconds) override {
        WebPPicture picture;
        if (!WebPPictureInit(&picture))
            throw fileError(path_, "cannot write WebP: libwebp version mismatch");
        picture.use_argb = 1;
        picture.width = frame.width;
        picture.height = frame.height;
        std::unique_ptr<WebPPicture, decltype(&WebPPictureFree)> owned(&picture, &WebPPictureFree);
        if (!WebPPictureImportRGBA(&picture, frame.pixels.data(), frame.width * 4))
            throw fileError(path_, "cannot write WebP: out of memory for a frame");
        if (!WebPAnimEncoderAdd(encoder_, &picture, timestampMs_, &config_))
            throw fileError(path_,
                            std::string("cannot write WebP: ") + WebPAnimEncoderGetError(encoder_));
        timestampMs_ += std::max(1, int(std::lround(seconds * 1000)));
    }

    void finish() override {
        // A last call without a picture marks the end of the last frame's time.
        if (!WebPAnimEncoderAdd(encoder_, nullptr, timestampMs_, nullptr))
            throw fileError(path_,
                            std::string("cannot write WebP: ") + WebPAnimEncoderGetError(encoder_));
        WebPData data;
        WebPDataInit(&data);
        if (!WebPAnimEncoderAssemble(encoder_, &data))
            throw fileError(path_,
                            std::string("cannot write WebP: ") + WebPAnimEncoderGetError(encoder_));
        const bool written = std::fwrite(data.bytes, 1, data.size, file_) == data.size;
        WebPDataClear(&data);
        const bool closed = std::fclose(file_) == 0;
        file_ = nullptr;
        if (!written || !closed)
            throw fileError(path_, "cannot write WebP: write failed (disk full?)");
    }

  private:
    std::filesystem::path path_;
    AnimationEncoding encoding_;
    std::FILE* file_ = nullptr;
    WebPAnimEncoder* encoder_ = nullptr;
    WebPConfig config_;
    int timestampMs_ = 0;
};

}  // namespace

std::unique_ptr<AnimationEncoder> openWebPEncoder(const std::filesystem::path& file,
                                                  const AnimationEncoding& encoding) {
    auto encoder = std::make_unique<WebPEncoder>(file, encoding);
    encoder->open();
    return encoder;
}

}  // namespace graftal
