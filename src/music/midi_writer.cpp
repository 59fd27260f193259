// Standard MIDI Files through libsmf: a tempo track and a track of notes.
#include <glib.h>  // before smf.h, which includes it inside extern "C"
#include <smf.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include "graftal/core/atomic_file.hpp"
#include "graftal/music/music.hpp"

namespace graftal {

namespace {

constexpr int kTicksPerBeat = 480;

// libsmf reports problems through GLib's log under its own domain; the library never
// prints, so they are kept for the error message instead.
thread_local std::string lastSmfMessage;

void keepSmfMessage(const gchar*, GLogLevelFlags, const gchar* message, gpointer) {
    lastSmfMessage = message ? message : "";
}

void silenceSmf() {
    static std::once_flag once;
    std::call_once(once, [] {
        g_log_set_handler(
            "libsmf",
            static_cast<GLogLevelFlags>(G_LOG_LEVEL_MASK | G_LOG_FLAG_FATAL | G_LOG_FLAG_RECURSION),
            keepSmfMessage, nullptr);
    });
}

struct SmfDeleter {
    void operator()(smf_t* s) const { smf_delete(s); }
};

int ticks(double beats) {
    return static_cast<int>(std::lround(beats * kTicksPerBeat));
}

void addEvent(smf_track_t* track, int at, std::initializer_list<unsigned char> bytes) {
    std::vector<unsigned char> b(bytes);
    smf_event_t* e = smf_event_new_from_pointer(b.data(), static_cast<int>(b.size()));
    if (!e) throw Error(SourceLocation{}, "libsmf could not make an event: " + lastSmfMessage);
    smf_track_add_event_pulses(track, e, at);
}

void addText(smf_track_t* track, unsigned char type, const std::string& text) {
    std::vector<unsigned char> b{0xFF, type, static_cast<unsigned char>(text.size())};
    b.insert(b.end(), text.begin(), text.begin() + std::min<std::size_t>(text.size(), 127));
    b[2] = static_cast<unsigned char>(b.size() - 3);
    smf_event_t* e = smf_event_new_from_pointer(b.data(), static_cast<int>(b.size()));
    if (e) smf_track_add_event_pulses(track, e, 0);
}

}  // namespace

void writeMidi(const Score& score, const Destination& destination) {
    const std::filesystem::path& path = destination.path();
    silenceSmf();
    lastSmfMessage.clear();
    std::unique_ptr<smf_t, SmfDeleter> smf(smf_new());
    if (!smf) throw fileError(path, "cannot write MIDI file: libsmf could not start");
    if (smf_set_ppqn(smf.get(), kTicksPerBeat) != 0 || smf_set_format(smf.get(), 1) != 0)
        throw fileError(path, "cannot write MIDI file: " + lastSmfMessage);

    smf_track_t* tempoTrack = smf_track_new();
    smf_add_track(smf.get(), tempoTrack);
    const long usPerBeat = std::lround(60'000'000.0 / score.tempo);
    if (!score.title.empty()) addText(tempoTrack, 0x03, score.title);
    addEvent(tempoTrack, 0,
             {0xFF, 0x51, 0x03, static_cast<unsigned char>((usPerBeat >> 16) & 0xFF),
              static_cast<unsigned char>((usPerBeat >> 8) & 0xFF),
              static_cast<unsigned char>(usPerBeat & 0xFF)});
    addEvent(tempoTrack, 0, {0xFF, 0x58, 0x04, 4, 2, 24, 8});  // 4/4

    smf_track_t* notes = smf_track_new();
    smf_add_track(smf.get(), notes);
    addEvent(notes, 0, {0xC0, static_cast<unsigned char>(score.instrument - 1)});
    int end = 0;
    for (const Note& n : score.notes) {
        int on = ticks(n.start), off = std::max(on + 1, ticks(n.start + n.duration));
        addEvent(
            notes, on,
            {0x90, static_cast<unsigned char>(n.pitch), static_cast<unsigned char>(n.velocity)});
        addEvent(notes, off, {0x80, static_cast<unsigned char>(n.pitch), 0});
        end = std::max(end, off);
    }
    if (smf_track_add_eot_pulses(tempoTrack, end) != 0 || smf_track_add_eot_pulses(notes, end) != 0)
        throw fileError(path, "cannot write MIDI file: " + lastSmfMessage);

    destination.writeThroughFile("MIDI file", [&](const std::filesystem::path& file) {
        if (smf_save(smf.get(), file.c_str()) != 0)
            throw fileError(path, "cannot write MIDI file: " +
                                      (lastSmfMessage.empty() ? std::string("libsmf failed")
                                                              : lastSmfMessage));
    });
}

}  // namespace graftal
