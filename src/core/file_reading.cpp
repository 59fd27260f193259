// Reading a file whose name comes from user text (see file_reading.hpp for why).
#include "graftal/core/file_reading.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include <sys/stat.h>

namespace graftal {

namespace {

std::string sizeInWords(std::size_t bytes) {
    if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0)
        return std::to_string(bytes >> 20) + " MB";
    if (bytes >= (std::size_t{1} << 10) && bytes % (std::size_t{1} << 10) == 0)
        return std::to_string(bytes >> 10) + " KB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::optional<std::string> readUserFile(const std::filesystem::path& path, std::string& problem,
                                        std::size_t limit) {
    // stat() follows links, so a link to a device is seen as the device.
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) {
        problem = errno == ENOENT ? "cannot be opened (does it exist?)"
                                  : std::string("cannot be opened: ") + std::strerror(errno);
        return std::nullopt;
    }
    if (S_ISDIR(info.st_mode)) {
        problem = "is a directory, not a file";
        return std::nullopt;
    }
    if (!S_ISREG(info.st_mode) && !S_ISFIFO(info.st_mode)) {
        problem = "is a device, not a file";
        return std::nullopt;
    }
    const std::string tooLarge =
        "is larger than " + sizeInWords(limit) + ", more than any file graftal reads there";
    if (S_ISREG(info.st_mode) && static_cast<std::size_t>(info.st_size) > limit) {
        problem = tooLarge;
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        problem = std::string("cannot be opened: ") + std::strerror(errno);
        return std::nullopt;
    }
    // A pipe has no size to check first: read in pieces, one byte past the limit at most.
    std::string bytes;
    char buffer[1 << 16];
    while (bytes.size() <= limit) {
        in.read(buffer, sizeof buffer);
        const std::streamsize got = in.gcount();
        if (got <= 0) break;
        bytes.append(buffer, static_cast<std::size_t>(got));
    }
    if (in.bad()) {
        problem = "cannot be read";
        return std::nullopt;
    }
    if (bytes.size() > limit) {
        problem = tooLarge;
        return std::nullopt;
    }
    return bytes;
}

}  // namespace graftal
