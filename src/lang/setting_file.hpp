// The file a view setting names (`contour: 1 leaf.con`, `curve: stem.crv`, `function:
// f.func`): found relative to the file the setting is written in, as cpfg finds them beside
// the view file, and read with the library's limits (graftal/file_reading.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/file_reading.hpp"
#include "graftal/lang/parser_target.hpp"

namespace graftal {

// `name` resolved against the setting's own file.
inline std::filesystem::path settingFilePath(const ViewSetting& setting, const std::string& name) {
    std::filesystem::path path(name);
    if (path.is_relative())
        path = std::filesystem::path(setting.location.file).parent_path() / path;
    return path;
}

// The bytes of `path`, or nullopt after an error at the setting naming "the `what` file".
inline std::optional<std::string> readSettingFile(const ViewSetting& setting,
                                                  const std::filesystem::path& path,
                                                  const std::string& what,
                                                  DiagnosticList& diagnostics) {
    std::string problem;
    std::optional<std::string> bytes = readUserFile(path, problem);
    if (!bytes)
        diagnostics.error(setting.location,
                          "the " + what + " file '" + path.string() + "' " + problem);
    return bytes;
}

}  // namespace graftal
