#include "graftal/core/file_format.hpp"

#include <array>
#include <cctype>

namespace graftal {

namespace {

constexpr std::array<FileFormatInfo, 6> kFormats{{
    {FileFormat::Svg, ".svg", FormatKind::Picture, "SVG", "scalable vector graphics"},
    {FileFormat::Png, ".png", FormatKind::Picture, "PNG", "raster picture (ray traced for 3D)"},
    {FileFormat::Pdf, ".pdf", FormatKind::Picture, "PDF", "vector page"},
    {FileFormat::Obj, ".obj", FormatKind::Mesh, "OBJ", "Wavefront mesh, materials in a .mtl"},
    {FileFormat::Ply, ".ply", FormatKind::Mesh, "PLY", "binary mesh with vertex colours"},
    {FileFormat::Glb, ".glb", FormatKind::Mesh, "glTF", "glTF 2.0 binary mesh"},
}};

}  // namespace

std::span<const FileFormatInfo> fileFormats() {
    return kFormats;
}

const FileFormatInfo& fileFormatInfo(FileFormat format) {
    for (const FileFormatInfo& f : kFormats)
        if (f.format == format) return f;
    return kFormats.front();  // unreachable: every enumerator has a row
}

std::optional<FileFormat> fileFormatFor(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const FileFormatInfo& f : kFormats)
        if (ext == f.extension) return f.format;
    return std::nullopt;
}

std::string extensionList(std::optional<FormatKind> kind, std::string_view separator,
                          std::string_view last) {
    std::string list;
    std::size_t listed = 0, total = 0;
    for (const FileFormatInfo& f : kFormats) total += !kind || f.kind == *kind;
    for (const FileFormatInfo& f : kFormats) {
        if (kind && f.kind != *kind) continue;
        if (listed > 0) list += listed + 1 == total ? last : separator;
        list += f.extension;
        ++listed;
    }
    return list;
}

}  // namespace graftal
