#include "standard_streams.hpp"

#include <unistd.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "graftal/diagnostics.hpp"

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
        std::ostringstream all;
        all << std::cin.rdbuf();
        return std::move(all).str();
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
