// cpfg's material files (.mat): up to 256 materials, one per colour index, each 15 bytes:
// a byte cpfg does not use, transparency, then ambient, diffuse, emission and specular
// colours (three bytes each, red, green, blue) and the shininess. Colours are bytes / 255.
// Indices the file does not reach keep cpfg's defaults (ambient 0.2, diffuse 0.8 grey,
// no emission or specular).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "graftal/core/rgb.hpp"

namespace graftal {

inline constexpr std::size_t kMaterialBytes = 15;
inline constexpr std::size_t kMaterialEntries = 256;

struct Material {
    Rgb ambient{0.2f, 0.2f, 0.2f};
    Rgb diffuse{0.8f, 0.8f, 0.8f};
    Rgb emission{};
    Rgb specular{};
    float shininess = 0;     // 0..255
    float transparency = 0;  // 0 (opaque) .. 1
};

// The 256 materials of a .mat file's bytes. A size that is not a whole number of 15-byte
// materials, or more than 256 of them, throws Error naming `fileName`.
std::vector<Material> parseMaterials(std::span<const std::uint8_t> bytes,
                                     const std::string& fileName);
std::vector<Material> loadMaterials(const std::filesystem::path& path);

// The 3D palette the materials give: each index's diffuse colour (the ray tracer's surfaces
// are matte, so ambient, specular, shininess and transparency are read but not drawn).
std::vector<Rgb> materialPalette(std::span<const Material> materials);

}  // namespace graftal
