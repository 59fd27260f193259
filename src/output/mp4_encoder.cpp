// MP4 (H.264) through FFmpeg's libraries: libswscale turns RGBA into YUV 4:2:0, libavcodec
// encodes with libx264, libavformat writes the MP4 container. The video runs at a constant
// frame rate, so a frame that stays longer (the held last frame) is repeated.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cmath>
#include <string>

#include "graftal/core/atomic_file.hpp"
#include "graftal/output/animation_file.hpp"

namespace graftal {

namespace {

std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

class Mp4Encoder final : public AnimationEncoder {
  public:
    Mp4Encoder(const std::filesystem::path& file, const AnimationEncoding& e)
        : path_(file), encoding_(e) {}

    // Separate from the constructor so that the destructor frees what a failure leaves.
    void open() {
        const AnimationEncoding& e = encoding_;
        const std::filesystem::path& file = path_;
        // The library never prints: FFmpeg's and x264's own chatter goes nowhere, and
        // failures come back as errors.
        av_log_set_level(AV_LOG_QUIET);
        // 4:2:0 needs even sides; an odd picture loses its last row or column.
        width_ = e.width & ~1;
        height_ = e.height & ~1;
        if (width_ < 2 || height_ < 2)
            throw fileError(path_, "MP4: frame size " + std::to_string(e.width) + "x" +
                                       std::to_string(e.height) + " is too small (2x2 at least)");
        check(avformat_alloc_output_context2(&format_, nullptr, "mp4", file.c_str()),
              "cannot start the MP4 container");
        const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
        if (!codec) codec = avcodec_find_encoder(AV_CODEC_ID_H264);
        if (!codec) throw fileError(path_, "cannot write MP4: FFmpeg has no H.264 encoder");
        stream_ = avformat_new_stream(format_, nullptr);
        codec_ = avcodec_alloc_context3(codec);
        if (!stream_ || !codec_) throw fileError(path_, "cannot write MP4: out of memory");
        rate_ = av_d2q(e.fps, 1000000);
        codec_->width = width_;
        codec_->height = height_;
        codec_->pix_fmt = AV_PIX_FMT_YUV420P;
        codec_->time_base = av_inv_q(rate_);
        codec_->framerate = rate_;
        codec_->gop_size = std::max(1, int(std::lround(e.fps * 2)));
        if (format_->oformat->flags & AVFMT_GLOBALHEADER)
            codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
        const int crf = std::clamp(int(std::lround(51 - 0.4 * e.quality)), 0, 51);
        av_opt_set(codec_->priv_data, "preset", "fast", 0);
        av_opt_set(codec_->priv_data, "crf", std::to_string(crf).c_str(), 0);
        check(avcodec_open2(codec_, codec, nullptr), "cannot start the H.264 encoder");
        check(avcodec_parameters_from_context(stream_->codecpar, codec_), "codec parameters");
        stream_->time_base = codec_->time_base;
        stream_->avg_frame_rate = rate_;
        check(avio_open(&format_->pb, file.c_str(), AVIO_FLAG_WRITE), "cannot create the file");
        check(avformat_write_header(format_, nullptr), "cannot write the MP4 header");

        frame_ = av_frame_alloc();
        packet_ = av_packet_alloc();
        if (!frame_ || !packet_) throw fileError(path_, "cannot write MP4: out of memory");
        frame_->format = AV_PIX_FMT_YUV420P;
        frame_->width = width_;
        frame_->height = height_;
        check(av_frame_get_buffer(frame_, 0), "cannot allocate a frame");
        scaler_ = sws_getContext(width_, height_, AV_PIX_FMT_RGBA, width_, height_,
                                 AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
        if (!scaler_) throw fileError(path_, "cannot write MP4: cannot convert RGBA to YUV");
    }

    ~Mp4Encoder() override {
        sws_freeContext(scaler_);
        av_frame_free(&frame_);
        av_packet_free(&packet_);
        avcodec_free_context(&codec_);
        if (format_) {
            if (format_->pb) avio_closep(&format_->pb);
            avformat_free_context(format_);
        }
    }

    void add(const RgbaImage& image, double seconds) override {
        if (image.width != encoding_.width || image.height != encoding_.height)
            throw fileError(path_, "MP4: a frame of " + std::to_string(image.width) + "x" +
                                       std::to_string(image.height) + " in a " +
                                       std::to_string(encoding_.width) + "x" +
                                       std::to_string(encoding_.height) + " video");
        check(av_frame_make_writable(frame_), "cannot allocate a frame");
        const std::uint8_t* source[1] = {image.pixels.data()};
        const int stride[1] = {image.width * 4};
        sws_scale(scaler_, source, stride, 0, height_, frame_->data, frame_->linesize);
        const double frames = seconds * av_q2d(rate_);
        const int repeats = std::max(1, int(std::lround(frames)));
        for (int k = 0; k < repeats; ++k) {
            frame_->pts = nextPts_++;
            check(avcodec_send_frame(codec_, frame_), "cannot encode a frame");
            drain();
        }
    }

    void finish() override {
        check(avcodec_send_frame(codec_, nullptr), "cannot complete the video");
        drain();
        check(av_write_trailer(format_), "cannot complete the MP4 file");
        check(avio_closep(&format_->pb), "cannot close the file (disk full?)");
    }

  private:
    void check(int status, const std::string& what) const {
        if (status < 0)
            throw fileError(path_, "cannot write MP4: " + what + " (" + avError(status) + ")");
    }

    void drain() {
        while (true) {
            const int status = avcodec_receive_packet(codec_, packet_);
            if (status == AVERROR(EAGAIN) || status == AVERROR_EOF) return;
            check(status, "cannot encode a frame");
            av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
            packet_->stream_index = stream_->index;
            check(av_interleaved_write_frame(format_, packet_), "cannot write a frame");
        }
    }

    std::filesystem::path path_;
    AnimationEncoding encoding_;
    int width_ = 0, height_ = 0;
    AVRational rate_{10, 1};
    AVFormatContext* format_ = nullptr;
    AVStream* stream_ = nullptr;
    AVCodecContext* codec_ = nullptr;
    AVFrame* frame_ = nullptr;
    AVPacket* packet_ = nullptr;
    SwsContext* scaler_ = nullptr;
    std::int64_t nextPts_ = 0;
};

}  // namespace

std::unique_ptr<AnimationEncoder> openMp4Encoder(const std::filesystem::path& file,
                                                 const AnimationEncoding& encoding) {
    auto encoder = std::make_unique<Mp4Encoder>(file, encoding);
    encoder->open();
    return encoder;
}

}  // namespace graftal
