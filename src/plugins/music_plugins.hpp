// The tables of the music layer's plugins (plugin_loader.hpp); music_forwarders.cpp defines
// the layer's functions in libgraftal_music by calling through them.
#pragma once

#include <cstdint>
#include <filesystem>

#include "graftal/music/music.hpp"
#include "plugin_loader.hpp"

namespace graftal::plugins {

// libsmf (graftal_plugin_midi.so): Standard MIDI Files.
struct MidiPlugin {
    std::uint32_t abi = kPluginAbi;
    void (*writeMidi)(const Score&, const Destination&);
};

// FluidSynth (graftal_plugin_audio.so): the score played with a SoundFont, as WAV.
struct AudioPlugin {
    std::uint32_t abi = kPluginAbi;
    void (*writeWav)(const Score&, const Destination&, const AudioOptions&);
    std::filesystem::path (*findSoundFont)();
};

}  // namespace graftal::plugins
