// The one table of the files graftal writes: extension, kind and name of every format.
// The writers name their format from it in messages, and the command picks a writer by it.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace graftal {

enum class FileFormat { Svg, Png, Pdf, Obj, Ply, Glb };

// Pictures are drawn from a Scene (or ray traced, for a 3D PNG); meshes are written from a
// Mesh.
enum class FormatKind { Picture, Mesh };

struct FileFormatInfo {
    FileFormat format;
    std::string_view extension;  // lower case, with the dot: ".svg"
    FormatKind kind;
    std::string_view name;         // in messages: "cannot write PLY: ..."
    std::string_view description;  // what the file holds
};

// Every format, pictures first, in the order the command lists them.
std::span<const FileFormatInfo> fileFormats();

const FileFormatInfo& fileFormatInfo(FileFormat format);

// From the file name's extension (case-insensitive); nullopt for an unknown one.
std::optional<FileFormat> fileFormatFor(const std::filesystem::path& path);

// The extensions of one kind (or of all formats), as a message lists them:
// ".svg, .png or .pdf" (`separator` between them, `last` before the last one).
std::string extensionList(std::optional<FormatKind> kind = std::nullopt,
                          std::string_view separator = ", ", std::string_view last = " or ");

}  // namespace graftal
