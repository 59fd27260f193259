// The PNG encoder (png_encoder.hpp), on libpng.
#include "png_encoder.hpp"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <string>
#include <vector>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

namespace {

constexpr int kLevel = 3;
constexpr int kFilteredStrategy = 1;  // zlib's Z_FILTERED

struct Sink {
    std::ostream* out;
    bool failed = false;
    char message[200] = "";
};

void writeBytes(png_structp png, png_bytep data, png_size_t length) {
    auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
    if (sink->failed) return;
    sink->out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
    if (!*sink->out) sink->failed = true;
}

void flushBytes(png_structp) {}

// libpng reports errors by longjmp: back into encode(), whose frame holds no C++ object.
[[noreturn]] void onError(png_structp png, png_const_charp message) {
    auto* sink = static_cast<Sink*>(png_get_error_ptr(png));
    std::snprintf(sink->message, sizeof sink->message, "%s", message ? message : "libpng error");
    png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

// Fills `row` (3 or 4 bytes a pixel) with image row y.
using RowFiller = void (*)(const void* image, int y, std::uint8_t* row);

// Returns false with sink.message set when libpng failed.
bool encode(Sink& sink, int width, int height, bool alpha, const void* image, RowFiller fill,
            std::uint8_t* row) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, info ? &info : nullptr);
        return false;
    }
    png_set_write_fn(png, &sink, writeBytes, flushBytes);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 alpha ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, kLevel);
    png_set_compression_strategy(png, kFilteredStrategy);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
    png_write_info(png, info);
    for (int y = 0; y < height && !sink.failed; ++y) {
        fill(image, y, row);
        png_write_row(png, row);
    }
    if (!sink.failed) png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}

void encodeWith(int width, int height, bool alpha, const void* image, RowFiller fill,
                std::ostream& out, const char* what) {
    Sink sink{&out};
    std::vector<std::uint8_t> row(static_cast<std::size_t>(width) * (alpha ? 4 : 3));
    if (!encode(sink, width, height, alpha, image, fill, row.data()))
        throw Error(SourceLocation{what, 0, 0},
                    std::string("cannot write PNG: ") +
                        (sink.message[0] ? sink.message : "out of memory"));
    if (sink.failed) throw Error(SourceLocation{what, 0, 0}, "cannot write PNG: write failed");
}

struct ArgbImage {
    const std::uint8_t* pixels;
    int width, stride;
};

const std::uint32_t* argbRow(const ArgbImage& im, int y) {
    return reinterpret_cast<const std::uint32_t*>(im.pixels + static_cast<std::size_t>(y) *
                                                                  static_cast<std::size_t>(im.stride));
}

void fillArgbOpaque(const void* image, int y, std::uint8_t* row) {
    const auto& im = *static_cast<const ArgbImage*>(image);
    const std::uint32_t* p = argbRow(im, y);
    for (int x = 0; x < im.width; ++x, row += 3) {
        row[0] = static_cast<std::uint8_t>(p[x] >> 16);
        row[1] = static_cast<std::uint8_t>(p[x] >> 8);
        row[2] = static_cast<std::uint8_t>(p[x]);
    }
}

void fillArgbAlpha(const void* image, int y, std::uint8_t* row) {
    const auto& im = *static_cast<const ArgbImage*>(image);
    const std::uint32_t* p = argbRow(im, y);
    for (int x = 0; x < im.width; ++x, row += 4) {
        const std::uint32_t a = p[x] >> 24;
        // Cairo's unpremultiplying: rounded, and nothing where alpha is 0.
        auto straight = [a](std::uint32_t c) {
            return static_cast<std::uint8_t>(a == 0 ? 0 : (c * 255 + a / 2) / a);
        };
        row[0] = straight((p[x] >> 16) & 0xFF);
        row[1] = straight((p[x] >> 8) & 0xFF);
        row[2] = straight(p[x] & 0xFF);
        row[3] = static_cast<std::uint8_t>(a);
    }
}

struct RgbaBytes {
    const std::uint8_t* pixels;
    int width;
};

void fillRgbaOpaque(const void* image, int y, std::uint8_t* row) {
    const auto& im = *static_cast<const RgbaBytes*>(image);
    const std::uint8_t* p = im.pixels + static_cast<std::size_t>(y) * im.width * 4;
    for (int x = 0; x < im.width; ++x, row += 3, p += 4) {
        row[0] = p[0];
        row[1] = p[1];
        row[2] = p[2];
    }
}

void fillRgbaAlpha(const void* image, int y, std::uint8_t* row) {
    const auto& im = *static_cast<const RgbaBytes*>(image);
    const std::uint8_t* p = im.pixels + static_cast<std::size_t>(y) * im.width * 4;
    std::copy(p, p + static_cast<std::size_t>(im.width) * 4, row);
}

}  // namespace

void encodeArgbPng(const std::uint8_t* pixels, int width, int height, int stride,
                   std::ostream& out, const char* what) {
    const ArgbImage image{pixels, width, stride};
    bool opaque = true;
    for (int y = 0; y < height && opaque; ++y) {
        const std::uint32_t* p = argbRow(image, y);
        for (int x = 0; x < width; ++x) opaque &= (p[x] >> 24) == 0xFF;
    }
    encodeWith(width, height, !opaque, &image, opaque ? fillArgbOpaque : fillArgbAlpha, out,
               what);
}

void encodeRgbaPng(const std::uint8_t* pixels, int width, int height, std::ostream& out,
                   const char* what) {
    const RgbaBytes image{pixels, width};
    bool opaque = true;
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    for (std::size_t i = 0; i < n; ++i) opaque &= pixels[4 * i + 3] == 0xFF;
    encodeWith(width, height, !opaque, &image, opaque ? fillRgbaOpaque : fillRgbaAlpha, out,
               what);
}

}  // namespace graftal
