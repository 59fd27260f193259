// Writing a file atomically: every writer of graftal (pictures, meshes, colour maps) puts
// its bytes in a hidden temporary file in the target's own directory (rename is atomic
// only within one file system) and renames it over the target when complete, so a reader
// never sees half a file and a failed write never destroys the previous one.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

// An Error located at `path` (no line or column): how writers report a file they cannot
// write.
Error fileError(const std::filesystem::path& path, const std::string& message);

// ".<name>.tmp-<pid>-<n>" beside `target`: hidden, recognisably graftal's, unique per
// process and call.
std::filesystem::path temporaryPathBeside(const std::filesystem::path& target);

// Calls write(temporary) for a temporary file beside `path` and renames it into place
// when write returns; on any failure the temporary is removed and nothing is left at
// `path`. Errors name `path`, never the temporary, and begin "cannot write <what>: ".
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write,
                         const std::string& what = "image");

// The same for a writer that writes to a stream: the temporary is opened as a binary
// file, and a failed write (a full disk) is an error.
void writeStreamAtomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write,
                           const std::string& what);

}  // namespace graftal
