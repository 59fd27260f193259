// The graftal subcommands. Each returns the process exit status; errors propagate as
// graftal::Error and are formatted by main().
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "graftal/output.hpp"

namespace graftal::cli {

struct InputOptions {
    std::string file;
    std::optional<int> steps;                    // -n
    std::map<std::string, std::string> defines;  // -D NAME=VALUE
    std::optional<std::uint64_t> seed;
    std::size_t memoryLimit = std::size_t(2) << 30;
    unsigned threads = 0;
};

struct RenderCommandOptions {
    std::string output;
    RenderOptions render;
};

int runDerive(const InputOptions& in, bool homomorphism);
int runStats(const InputOptions& in, bool geometry);
int runRender(const InputOptions& in, const RenderCommandOptions& out);

// "2G", "512M", "1000000" -> bytes; throws Error on a malformed size.
std::size_t parseByteSize(const std::string& text);
// "800x600" -> width, height; throws Error.
void parseImageSize(const std::string& text, int& width, int& height);
// "#rrggbb", "rrggbb" or a few names (black, white, ...) -> colour; throws Error.
Rgb parseColor(const std::string& text);

}  // namespace graftal::cli
