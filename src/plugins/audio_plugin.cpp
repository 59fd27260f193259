// graftal_plugin_audio.so: scores played by FluidSynth into WAV files (music_plugins.hpp).
#include "music_plugins.hpp"

namespace graftal::plugins {
namespace {
const AudioPlugin kTable{
    .writeWav = &writeWav,
    .findSoundFont = &findSoundFont,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_audio() {
    return &graftal::plugins::kTable;
}
