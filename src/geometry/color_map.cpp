// Reading and writing cpfg's binary colour maps. cpfg reads 256 entries of three bytes
// (fread(entry, 3, 1, fp) per colour) and sets no header; it does not check the size, so a
// short file silently leaves colours undefined. Here any size but 768 bytes is an error.
#include "graftal/geometry/color_map.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/file_reading.hpp"

namespace graftal {

namespace {

Error mapError(const std::string& file, const std::string& message) {
    return Error(SourceLocation{file, 0, 0}, message);
}

std::uint8_t toByte(float v) {
    // NaN compares false both ways and would reach lround; treat it as 0.
    float c = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    return static_cast<std::uint8_t>(std::lround(c * 255.0f));
}

}  // namespace

std::vector<Rgb> defaultPalette3D() {
    std::vector<Rgb> palette = Scene::defaultPalette();
    // A mid bark brown: lit and shaded sides stay apart once the ray tracer has decoded it
    // to linear light (the ink of index 0 is about 1 % there: a silhouette).
    palette[0] = {0x8f / 255.0f, 0x6b / 255.0f, 0x47 / 255.0f};
    return palette;
}

std::vector<Rgb> parseColorMap(std::span<const std::uint8_t> bytes, const std::string& fileName) {
    if (bytes.size() != kColorMapBytes)
        throw mapError(fileName, "not a colour map: it has " + std::to_string(bytes.size()) +
                                     " bytes, expected exactly " + std::to_string(kColorMapBytes) +
                                     " (256 colours of 3 bytes: red, green, blue)");
    std::vector<Rgb> colors(kColorMapEntries);
    for (std::size_t i = 0; i < kColorMapEntries; ++i)
        colors[i] = {static_cast<float>(bytes[3 * i]) / 255.0f,
                     static_cast<float>(bytes[3 * i + 1]) / 255.0f,
                     static_cast<float>(bytes[3 * i + 2]) / 255.0f};
    return colors;
}

std::vector<Rgb> loadColorMap(const std::filesystem::path& path) {
    std::string problem;
    // At most the expected size: a larger file is refused unread.
    const std::optional<std::string> text = readUserFile(path, problem, kColorMapBytes);
    if (!text && problem.rfind("is larger than", 0) != 0)
        throw mapError(path.string(), "the colour map " + problem);
    if (!text)
        throw mapError(path.string(),
                       "not a colour map: it has more than " + std::to_string(kColorMapBytes) +
                           " bytes, expected exactly " + std::to_string(kColorMapBytes) +
                           " (256 colours of 3 bytes: red, green, blue)");
    const std::vector<std::uint8_t> bytes(text->begin(), text->end());
    return parseColorMap(bytes, path.string());
}

std::vector<std::uint8_t> encodeColorMap(std::span<const Rgb> colors) {
    if (colors.size() > kColorMapEntries)
        throw mapError(
            "", "a colour map holds at most 256 colours, got " + std::to_string(colors.size()));
    std::vector<std::uint8_t> bytes(kColorMapBytes, 0);
    for (std::size_t i = 0; i < colors.size(); ++i) {
        bytes[3 * i] = toByte(colors[i].r);
        bytes[3 * i + 1] = toByte(colors[i].g);
        bytes[3 * i + 2] = toByte(colors[i].b);
    }
    return bytes;
}

void saveColorMap(const std::filesystem::path& path, std::span<const Rgb> colors) {
    const std::vector<std::uint8_t> bytes = encodeColorMap(colors);
    writeStreamAtomically(
        path,
        [&](std::ostream& out) {
            out.write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
        },
        "colour map");
}

}  // namespace graftal
