// The music layer's writers that need libsmf or FluidSynth, as libgraftal_music has them in
// a shared build: each loads its plugin on first use (music_plugins.hpp).
#include "music_plugins.hpp"

namespace graftal {

namespace {

const plugins::AudioPlugin& audio(std::string_view what) {
    return plugins::plugin<plugins::AudioPlugin>("audio", what);
}

}  // namespace

void writeMidi(const Score& score, const Destination& destination) {
    plugins::plugin<plugins::MidiPlugin>("midi", "a MIDI file (libsmf)")
        .writeMidi(score, destination);
}

void writeWav(const Score& score, const Destination& destination, const AudioOptions& audioOptions) {
    audio("a WAV file (FluidSynth)").writeWav(score, destination, audioOptions);
}

std::filesystem::path findSoundFont() {
    return audio("finding a SoundFont (FluidSynth)").findSoundFont();
}

}  // namespace graftal
