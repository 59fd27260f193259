// graftal_plugin_midi.so: Standard MIDI Files written with libsmf (music_plugins.hpp).
#include "music_plugins.hpp"

namespace graftal::plugins {
namespace {
const MidiPlugin kTable{
    .writeMidi = &writeMidi,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_midi() {
    return &graftal::plugins::kTable;
}
