// graftal music: a curve read as a score (LSFP ch. 6.3), written as MIDI, audio or notation.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "commands.hpp"

namespace graftal::cli {

struct MusicCommandOptions {
    std::string output;
    std::string scale, root, axis;  // empty: the file's setting, else the default
    std::optional<double> tempo, unit;
    std::optional<int> instrument;
    int sampleRate = 44100;
    std::string soundFont;
};

void addMusicOptions(CLI::App& command, MusicCommandOptions& options);
int runMusic(const InputOptions& in, const MusicCommandOptions& options);

}  // namespace graftal::cli
