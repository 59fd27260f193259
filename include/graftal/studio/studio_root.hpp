// The folder (or single file) a studio may read and write: every path a request names is
// resolved inside it, and anything that would leave it is refused.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"

namespace graftal::studio {

// A request named a path outside the root, or a file the studio may not touch.
class PathRefused : public Error {
  public:
    explicit PathRefused(const std::string& message);
};

struct ListedFile {
    std::string path;  // relative to the root, with '/' separators
    std::uintmax_t size = 0;
    std::int64_t mtime = 0;  // microseconds since 1970 (exact in a JavaScript number)
};

class StudioRoot {
  public:
    // `path` is a folder (every .l file below it) or one .l file (that file alone, and the
    // view file of its name, NAME.v).
    // Throws Error when it does not exist.
    explicit StudioRoot(const std::filesystem::path& path);

    const std::filesystem::path& folder() const { return folder_; }
    // The one file the studio was started on, relative to folder(); empty for a folder.
    const std::string& onlyFile() const { return onlyFile_; }

    // The absolute path of `relative`: refused when it is empty, absolute, has a '..'
    // component, or leads (through symbolic links) outside the root; also when it is not
    // a model file (.l, or .v view files). `mustExist`: refused when there is no such file.
    std::filesystem::path resolve(std::string_view relative, bool mustExist) const;

    // The model files below the root (hidden and build folders skipped), sorted, at most
    // `limit` of them.
    std::vector<ListedFile> list(std::size_t limit = 5000) const;

  private:
    std::filesystem::path folder_;  // canonical
    std::string onlyFile_;
};

// The modification time of a file in microseconds since 1970 (0 when it cannot be read).
std::int64_t modificationTime(const std::filesystem::path& path);

}  // namespace graftal::studio
