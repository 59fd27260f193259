// Reading a file whose name comes from user text: a model, what it #includes, and the
// surface, contour, function, material and colour files its view names. Such a name can
// be a device (`/dev/zero` never ends, `/dev/tty` waits for a key) or a file far larger
// than any model, so a plain read could hang or fill memory. Only regular files and pipes
// (`/dev/stdin` fed by a shell) are read, and never more than a limit.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace graftal {

// Larger than any hand-written or generated model file, small enough to hold.
inline constexpr std::size_t kUserFileLimit = std::size_t{256} << 20;

// The bytes of `path`, or nullopt with `problem` set to what went wrong, worded to follow
// the file's name ("cannot be opened (does it exist?)", "is a directory, not a file", "is a
// device, not a file", "is larger than 256 MB, more than any model file"). A limit is given
// in bytes; a file of exactly `limit` bytes is read.
std::optional<std::string> readUserFile(const std::filesystem::path& path, std::string& problem,
                                        std::size_t limit = kUserFileLimit);

}  // namespace graftal
