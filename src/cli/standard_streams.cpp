#include "standard_streams.hpp"

#include <unistd.h>

#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/file_reading.hpp"

namespace graftal::cli {

ScratchFile::ScratchFile(const std::string& name) {
    static int counter = 0;
    folder_ = std::filesystem::temp_directory_path() /
              ("graftal-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(folder_);
    path_ = folder_ / name;
}

ScratchFile::~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove_all(folder_, ec);
}

const std::string& standardInputText() {
    static const std::string text = [] {
        if (::isatty(STDIN_FILENO)) {  // typed in: ends with the user's Ctrl-D
            std::ostringstream all;
            all << std::cin.rdbuf();
            return std::move(all).str();
        }
        // A file, a pipe or a device redirected in: read with the library's limits, so
        // that `< /dev/zero` is an error and not an endless read.
        std::string problem;
        std::optional<std::string> bytes = readUserFile("/dev/stdin", problem);
        if (!bytes) throw Error(SourceLocation{kStdinName, 0, 0}, "standard input " + problem);
        return std::move(*bytes);
    }();
    return text;
}

void saveStandardInput(const ScratchFile& file) {
    std::ofstream out(file.path(), std::ios::binary);
    out << standardInputText();
    out.flush();
    if (!out)
        throw Error(SourceLocation{kStdinName, 0, 0},
                    "cannot keep standard input in " + file.path().string());
}

bool copyToStandardOutput(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::cout << in.rdbuf();
    std::cout.flush();
    return static_cast<bool>(std::cout);
}

}  // namespace graftal::cli
