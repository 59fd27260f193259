// Audio: the score played by FluidSynth with a General MIDI SoundFont, written as a WAV file.
#include <fluidsynth.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <mutex>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "graftal/core/atomic_file.hpp"
#include "graftal/music/music.hpp"

namespace graftal {

namespace {

// FluidSynth logs to stderr by default; the library never prints, so its messages are kept
// for the error instead.
thread_local std::string lastFluidMessage;

void keepFluidMessage(int level, const char* message, void*) {
    if (level <= FLUID_ERR) lastFluidMessage = message ? message : "";
}

void silenceFluidSynth() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (int level = FLUID_PANIC; level <= FLUID_DBG; ++level)
            fluid_set_log_function(level, keepFluidMessage, nullptr);
    });
}

struct Synth {
    fluid_settings_t* settings = nullptr;
    fluid_synth_t* synth = nullptr;
    ~Synth() {
        if (synth) delete_fluid_synth(synth);
        if (settings) delete_fluid_settings(settings);
    }
};

void put16(std::ostream& out, std::uint16_t v) {
    char b[2] = {static_cast<char>(v & 0xFF), static_cast<char>(v >> 8)};
    out.write(b, 2);
}

void put32(std::ostream& out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.put(static_cast<char>((v >> (8 * k)) & 0xFF));
}

struct Event {
    std::int64_t frame;
    bool on;
    int pitch, velocity;
};

std::string megabytes(double bytes) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(0) << bytes / (1 << 20) << " MiB";
    return os.str();
}

// The sound of a long score (a slow tempo, a long curve, a large `music unit:`) is refused
// before anything is allocated, with what to lower.
void checkAudioSize(double frames, const Score& score, const std::filesystem::path& path,
                    const AudioOptions& audio) {
    const double bytes = frames * sizeof(float);
    std::ostringstream length;
    length << std::setprecision(3) << score.seconds() << " s of sound at " << audio.sampleRate
           << " Hz";
    const char* lower =
        "lower the steps or the unit (--unit, `music unit:`), raise the tempo (--tempo, `music "
        "tempo:`) or lower --sample-rate";
    if (!std::isfinite(frames) || frames * 2 > 4294967295.0 - 44)
        throw fileError(path, "cannot write audio: " + length.str() +
                                  " is more than a WAV file holds (4 GiB): " + lower);
    if (bytes > static_cast<double>(audio.memoryLimit))
        throw fileError(path, "cannot write audio: " + length.str() + " needs " + megabytes(bytes) +
                                  " of memory, over the memory limit of " +
                                  megabytes(static_cast<double>(audio.memoryLimit)) + ": " + lower +
                                  " (or raise --memory-limit)");
}

}  // namespace

std::filesystem::path findSoundFont() {
    if (const char* env = std::getenv("GRAFTAL_SOUNDFONT"); env && *env) return env;
    // The fuller General MIDI sets first; TimGM6mb (small, always there in Debian's
    // graftal dependencies) last.
    static const char* const candidates[] = {
        "/usr/share/sounds/sf2/FluidR3_GM.sf2",
        "/usr/share/soundfonts/FluidR3_GM.sf2",
        "/usr/share/sounds/sf3/MuseScore_General.sf3",
        "/usr/share/sounds/sf2/MuseScore_General.sf2",
        "/usr/share/sounds/sf2/default-GM.sf2",
        "/usr/share/soundfonts/default.sf2",
        "/usr/share/sounds/sf3/default-GM.sf3",
        "/usr/share/sounds/sf2/TimGM6mb.sf2",
    };
    std::error_code ec;
    for (const char* c : candidates)
        if (std::filesystem::is_regular_file(c, ec)) return c;
    return {};
}

void writeWav(const Score& score, const Destination& destination, const AudioOptions& audio) {
    const std::filesystem::path& path = destination.path();
    if (audio.sampleRate < 8000 || audio.sampleRate > 96000)
        throw fileError(path,
                        "cannot write audio: the sample rate must be from 8000 to 96000, "
                        "got " +
                            std::to_string(audio.sampleRate));
    std::filesystem::path font = audio.soundFont.empty() ? findSoundFont() : audio.soundFont;
    if (font.empty())
        throw fileError(path,
                        "cannot write audio: no General MIDI SoundFont found (install one, e.g. "
                        "'apt-get install timgm6mb-soundfont' or 'make deps', or set "
                        "GRAFTAL_SOUNDFONT to a .sf2 file)");
    silenceFluidSynth();
    lastFluidMessage.clear();
    Synth s;
    s.settings = new_fluid_settings();
    if (!s.settings) throw fileError(path, "cannot write audio: FluidSynth could not start");
    fluid_settings_setnum(s.settings, "synth.sample-rate", audio.sampleRate);
    fluid_settings_setint(s.settings, "synth.threadsafe-api", 0);
    s.synth = new_fluid_synth(s.settings);
    if (!s.synth) throw fileError(path, "cannot write audio: FluidSynth could not start");
    if (fluid_synth_sfload(s.synth, font.c_str(), 1) == FLUID_FAILED)
        throw fileError(path, "cannot write audio: FluidSynth cannot load the SoundFont '" +
                                  font.string() + "'" +
                                  (lastFluidMessage.empty() ? "" : ": " + lastFluidMessage));
    fluid_synth_program_change(s.synth, 0, score.instrument - 1);

    const double framesPerBeat = audio.sampleRate * 60.0 / score.tempo;
    std::vector<Event> events;
    for (const Note& n : score.notes) {
        auto on = static_cast<std::int64_t>(std::llround(n.start * framesPerBeat));
        auto off = static_cast<std::int64_t>(std::llround((n.start + n.duration) * framesPerBeat));
        events.push_back({on, true, n.pitch, n.velocity});
        events.push_back({std::max(off, on + 1), false, n.pitch, 0});
    }
    // At the same frame a note ends before the next begins (a repeated pitch restarts).
    std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
        return a.frame != b.frame ? a.frame < b.frame : (!a.on && b.on);
    });
    const double frames = std::round((score.seconds() + audio.releaseSeconds) * audio.sampleRate);
    checkAudioSize(frames, score, path, audio);
    const auto total = static_cast<std::int64_t>(frames);

    // Mono, rendered in blocks: only the mixed-down sound is kept, to be normalised.
    std::vector<float> mono(static_cast<std::size_t>(total));
    std::vector<float> left(4096), right(4096);
    float peak = 0;
    std::int64_t frame = 0;
    std::size_t next = 0;
    while (frame < total) {
        while (next < events.size() && events[next].frame <= frame) {
            const Event& e = events[next++];
            if (e.on)
                fluid_synth_noteon(s.synth, 0, e.pitch, e.velocity);
            else
                fluid_synth_noteoff(s.synth, 0, e.pitch);
        }
        std::int64_t until = next < events.size() ? std::min(events[next].frame, total) : total;
        until = std::min(until, frame + 4096);
        const int len = static_cast<int>(until - frame);
        if (fluid_synth_write_float(s.synth, len, left.data(), 0, 1, right.data(), 0, 1) !=
            FLUID_OK)
            throw fileError(path, "cannot write audio: FluidSynth failed to render");
        for (int i = 0; i < len; ++i) {
            const float v = 0.5f * (left[i] + right[i]);
            mono[static_cast<std::size_t>(frame + i)] = v;
            peak = std::max(peak, std::abs(v));
        }
        frame = until;
    }

    const float gain = peak > 0 ? 0.9f / peak : 1.0f;
    const auto dataBytes = static_cast<std::uint32_t>(mono.size() * 2);
    destination.write("audio", [&](std::ostream& out) {
            out.write("RIFF", 4);
            put32(out, 36 + dataBytes);
            out.write("WAVEfmt ", 8);
            put32(out, 16);
            put16(out, 1);  // PCM
            put16(out, 1);  // mono
            put32(out, static_cast<std::uint32_t>(audio.sampleRate));
            put32(out, static_cast<std::uint32_t>(audio.sampleRate * 2));
            put16(out, 2);
            put16(out, 16);
            out.write("data", 4);
            put32(out, dataBytes);
            for (float v : mono) {
                long q = std::lround(std::clamp(v * gain, -1.0f, 1.0f) * 32767.0f);
                put16(out, static_cast<std::uint16_t>(static_cast<std::int16_t>(q)));
            }
    });
}

}  // namespace graftal
