// cpfg's colour maps (.map files): 256 colours, each three bytes red, green, blue (0-255),
// one after another with nothing before or after them: exactly 768 bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "graftal/geometry/scene.hpp"

namespace graftal {

inline constexpr std::size_t kColorMapEntries = 256;
inline constexpr std::size_t kColorMapBytes = kColorMapEntries * 3;

// The palette of 3D pictures and meshes when a file gives no colour map: the 2D palette
// (Scene::defaultPalette, in the same order, so `;(1)` is a leaf green in both) except that
// index 0, the colour of every uncoloured stem, is a bark brown light enough to show its
// shading instead of the near-black ink of line art.
std::vector<Rgb> defaultPalette3D();

// The 256 colours of a .map file's bytes. Any other size throws Error naming `fileName`
// and saying how many bytes were expected.
std::vector<Rgb> parseColorMap(std::span<const std::uint8_t> bytes, const std::string& fileName);
std::vector<Rgb> loadColorMap(const std::filesystem::path& path);

// The 768 bytes of a .map file. Each channel is clamped to [0, 1] and rounded to the
// nearest of 0..255; fewer than 256 colours are padded with black, more throw Error.
std::vector<std::uint8_t> encodeColorMap(std::span<const Rgb> colors);
// Writes atomically (a temporary file beside `path`, then a rename); throws Error.
void saveColorMap(const std::filesystem::path& path, std::span<const Rgb> colors);

}  // namespace graftal
