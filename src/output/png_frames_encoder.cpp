// A folder of numbered PNG frames (frame-0001.png, ...), for other tools to assemble: each
// frame is written as it arrives, so nothing is held.
#include <cairo.h>

#include <cstdio>
#include <memory>
#include <string>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/destination.hpp"
#include "graftal/output/animation_file.hpp"

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
    using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
    SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, image.width, image.height),
                       &cairo_surface_destroy);
    if (auto st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS)
        throw fileError(path,
                        std::string("cannot create the image: ") + cairo_status_to_string(st));
    cairo_surface_flush(surface.get());
    unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < image.height; ++y) {
        // ARGB32 is one native-endian premultiplied word per pixel.
        auto* row = reinterpret_cast<std::uint32_t*>(data + std::size_t(y) * stride);
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = image.at(x, y);
            const std::uint32_t a = p[3];
            auto pre = [a](std::uint32_t c) { return (c * a + 127) / 255; };
            row[x] = (a << 24) | (pre(p[0]) << 16) | (pre(p[1]) << 8) | pre(p[2]);
        }
    }
    cairo_surface_mark_dirty(surface.get());
    destination.write("PNG", [&](std::ostream& out) {
        auto write = [](void* closure, const unsigned char* bytes, unsigned int length) {
            auto* stream = static_cast<std::ostream*>(closure);
            stream->write(reinterpret_cast<const char*>(bytes), length);
            return *stream ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
        };
        if (auto st = cairo_surface_write_to_png_stream(surface.get(), write, &out);
            st != CAIRO_STATUS_SUCCESS)
            throw fileError(path, std::string("cannot write PNG: ") + cairo_status_to_string(st));
    });
}

}  // namespace graftal
