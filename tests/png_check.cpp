// png_check FILE.png: exit 0 when the PNG reads and is not blank (its pixels are not all
// one colour); prints its size and how many pixels differ from the first one.
#include <cairo.h>

#include <cstdint>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: png_check FILE.png\n");
        return 2;
    }
    cairo_surface_t* image = cairo_image_surface_create_from_png(argv[1]);
    if (cairo_surface_status(image) != CAIRO_STATUS_SUCCESS) {
        std::fprintf(stderr, "%s: not a readable PNG\n", argv[1]);
        cairo_surface_destroy(image);
        return 1;
    }
    cairo_surface_flush(image);
    const int width = cairo_image_surface_get_width(image);
    const int height = cairo_image_surface_get_height(image);
    const int stride = cairo_image_surface_get_stride(image);
    const unsigned char* data = cairo_image_surface_get_data(image);
    std::uint32_t first = 0;
    std::memcpy(&first, data, sizeof first);
    long differing = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint32_t pixel = 0;
            std::memcpy(&pixel, data + y * stride + 4 * x, sizeof pixel);
            if (pixel != first) ++differing;
        }
    cairo_surface_destroy(image);
    std::printf("%s: %dx%d, %ld pixels differ from the corner\n", argv[1], width, height,
                differing);
    return width > 0 && height > 0 && differing > 0 ? 0 : 1;
}
