// Reading cpfg's binary material files (layout in material_file.hpp). cpfg reads materials
// until the file ends; a trailing piece shorter than a material is an error here, as a
// truncated file would silently give wrong colours.
#include "graftal/geometry/material_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/file_reading.hpp"

namespace graftal {

namespace {

Rgb colorAt(std::span<const std::uint8_t> m, std::size_t at) {
    return {m[at] / 255.0f, m[at + 1] / 255.0f, m[at + 2] / 255.0f};
}

}  // namespace

std::vector<Material> parseMaterials(std::span<const std::uint8_t> bytes,
                                     const std::string& fileName) {
    if (bytes.size() % kMaterialBytes != 0 || bytes.size() > kMaterialBytes * kMaterialEntries)
        throw Error(SourceLocation{fileName, 0, 0},
                    "not a material file: it has " + std::to_string(bytes.size()) +
                        " bytes, expected a multiple of " + std::to_string(kMaterialBytes) +
                        " (one material per colour index) and at most " +
                        std::to_string(kMaterialBytes * kMaterialEntries));
    std::vector<Material> materials(kMaterialEntries);
    for (std::size_t i = 0; i < bytes.size() / kMaterialBytes; ++i) {
        auto m = bytes.subspan(i * kMaterialBytes, kMaterialBytes);
        Material& out = materials[i];
        out.transparency = m[1] / 255.0f;
        out.ambient = colorAt(m, 2);
        out.diffuse = colorAt(m, 5);
        out.emission = colorAt(m, 8);
        out.specular = colorAt(m, 11);
        out.shininess = m[14];
    }
    return materials;
}

std::vector<Material> loadMaterials(const std::filesystem::path& path) {
    // At most one byte past the largest file, so that a huge wrong file is not read whole.
    std::string problem;
    const std::optional<std::string> text =
        readUserFile(path, problem, kMaterialBytes * kMaterialEntries + 1);
    if (!text) throw Error(SourceLocation{path.string(), 0, 0}, "the material file " + problem);
    const std::vector<std::uint8_t> bytes(text->begin(), text->end());
    return parseMaterials(bytes, path.string());
}

std::vector<Rgb> materialPalette(std::span<const Material> materials) {
    std::vector<Rgb> palette;
    palette.reserve(materials.size());
    for (const Material& m : materials) palette.push_back(m.diffuse);
    return palette;
}

}  // namespace graftal
