// "-" for a file: the L-system read from standard input, a picture or mesh written to
// standard output. Both go through a scratch file, so the library reads and writes files as
// always and a failed run writes nothing.
#pragma once

#include <filesystem>
#include <string>

#include "graftal/core/file_format.hpp"

namespace graftal::cli {

// The name diagnostics give to standard input.
inline constexpr const char* kStdinName = "<stdin>";

// A file in the temporary directory, removed with its folder when this goes.
class ScratchFile {
  public:
    explicit ScratchFile(const std::string& name);
    ~ScratchFile();
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path folder_, path_;
};

// All of standard input, read at the first call and kept: the command looks at it to
// choose between a map L-system and a string one before it parses it.
const std::string& standardInputText();

// Copies all of standard input (standardInputText()) into `file`.
void saveStandardInput(const ScratchFile& file);

// Copies `file` to standard output; false when standard output failed.
bool copyToStandardOutput(const std::filesystem::path& file);

// The format `graftal render -o -` writes: --format's (`format`, empty for SVG). Throws a
// usage error for an unknown format, or a binary one when standard output is a terminal.
FileFormat standardOutputFormat(const std::string& format);

}  // namespace graftal::cli
