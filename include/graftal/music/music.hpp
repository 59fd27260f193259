// Fractal music (LSFP ch. 6.3): "an L-system is used to generate a fractal curve, which is
// subsequently interpreted as a sequence of notes". The curve is traversed in drawing order;
// each maximal run of horizontal segments is one note whose pitch comes from its y-coordinate
// through a scale (C major by default, the first note the root) and whose duration is
// proportional to its length; vertical moves change the pitch, not the time.
//
// A Score is a plain value (a list of notes with a tempo and an instrument), so any front end
// can play or show it; the writers make Standard MIDI Files (libsmf), audio (FluidSynth and a
// General MIDI SoundFont), LilyPond source, engraved scores (the lilypond program) and
// MusicXML.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "graftal/core/destination.hpp"
#include "graftal/core/music_scale.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal {

struct Note {
    int pitch = 60;       // MIDI note number, 0..127 (60 is middle C)
    double start = 0;     // beats from the beginning
    double duration = 1;  // beats
    int velocity = 80;    // MIDI velocity, 1..127
    friend bool operator==(const Note&, const Note&) = default;
};

struct Score {
    std::vector<Note> notes;  // in time order, none overlapping
    double tempo = 120;       // quarter-note beats per minute
    int instrument = 1;       // General MIDI program, 1..128 (1: acoustic grand piano)
    std::string title;

    double beats() const;    // end of the last note
    double seconds() const;  // beats() at the tempo
};

// How a curve becomes a score: the command's options and a file's `music ...:` settings.
struct MusicOptions {
    ScaleSteps scale{0, 2, 4, 5, 7, 9, 11};  // C major's offsets
    int root = 60;                           // the first note's pitch (C4)
    double tempo = 120;
    int instrument = 1;
    bool pitchFromX = false;  // false: the book's reading, pitch from y and time from x
    double unit = 1;          // beats per step length
    int velocity = 80;
};

// The defaults with a model's `music ...:` view settings applied.
MusicOptions musicOptions(const ViewSettings& view);

// Reads the 2D curve of `scene` (its segments in drawing order) as a score. `stepLength` is
// the grid of the curve: a height of one step is one degree of the scale, a length of one step
// lasts `options.unit` beats. The first note is the root; a note k degrees above it is
// root + the scale's k-th offset, an octave higher every scale length. Segments that are
// neither horizontal nor vertical end a note and take no time. Throws Error when the curve
// has no horizontal segment, when a note would fall outside MIDI's range 0..127, or for
// options out of range.
Score scoreFromScene(const Scene& scene, double stepLength, const MusicOptions& options);

// Derives `steps` steps (the file's length when negative), interprets and reads the curve.
Score scoreFromModel(const Model& model, int steps, const MusicOptions& options,
                     DerivationOptions derivation = {});

// The music formats, by the output's extension.
enum class MusicFormat { Midi, Wav, LilyPond, Pdf, Png, Svg, MusicXml };
// .mid/.midi, .wav, .ly, .pdf, .png, .svg, .musicxml/.xml; empty for anything else.
std::optional<MusicFormat> musicFormatFor(const std::filesystem::path& path);
// "mid wav ly pdf png svg musicxml": for messages.
std::string musicExtensionList();

// Standard MIDI File, format 1: a tempo track and one track with the notes on channel 1,
// 480 ticks per beat.
void writeMidi(const Score& score, const Destination& destination);
inline void writeMidi(const Score& score, const std::filesystem::path& path) {
    writeMidi(score, Destination::file(path));
}

// The audio synthesised by FluidSynth with `soundFont` (empty: findSoundFont()): 16-bit PCM
// WAV, mono, `sampleRate` samples per second; the score's length plus `releaseSeconds` for
// the last note to ring out.
// The sound is held in memory once (4 bytes a sample) to be normalised: a score whose sound
// needs more than `memoryLimit` (or more than a WAV file's 4 GiB) is an Error saying what to
// lower.
struct AudioOptions {
    int sampleRate = 44100;
    double releaseSeconds = 1.0;
    std::filesystem::path soundFont;
    std::size_t memoryLimit = std::size_t(512) << 20;  // some 50 minutes at 44100 Hz
};
void writeWav(const Score& score, const Destination& destination,
              const AudioOptions& audio = {});
inline void writeWav(const Score& score, const std::filesystem::path& path,
                     const AudioOptions& audio = {}) {
    writeWav(score, Destination::file(path), audio);
}

// The General MIDI SoundFont to play with: $GRAFTAL_SOUNDFONT when set, else the best of
// Debian's standard paths (FluidR3, MuseScore General, then TimGM6mb). Empty when none.
std::filesystem::path findSoundFont();

// LilyPond source of the score: one staff, 4/4, notes that cross a bar line split and tied.
std::string lilyPondSource(const Score& score, bool onePage = false);
void writeLilyPond(const Score& score, const Destination& destination);
inline void writeLilyPond(const Score& score, const std::filesystem::path& path) {
    writeLilyPond(score, Destination::file(path));
}

// The engraved score (.pdf, .png or .svg) made by running the lilypond program. Throws Error
// saying how to install LilyPond when it is not on the PATH (the .ly output needs nothing).
// LilyPond (and the Ghostscript it starts) may map at most `memoryLimit` bytes, and run for
// $GRAFTAL_LILYPOND_SECONDS (default 120 s); past either it is stopped, with an Error.
void engraveScore(const Score& score, const std::filesystem::path& path,
                  std::size_t memoryLimit = std::size_t(1) << 30);
// The same as `format` (Pdf, Png or Svg) to a file, a stream or memory.
void engraveScore(const Score& score, MusicFormat format, const Destination& destination,
                  std::size_t memoryLimit = std::size_t(1) << 30);
// Where the lilypond program is; empty when it is not installed.
std::filesystem::path findLilyPond();

// MusicXML 4.0 (score-partwise), for MuseScore and other notation programs.
std::string musicXml(const Score& score);
void writeMusicXml(const Score& score, const Destination& destination);
inline void writeMusicXml(const Score& score, const std::filesystem::path& path) {
    writeMusicXml(score, Destination::file(path));
}

// Writes the score in the format of `path`'s extension. Throws Error for an unknown one.
void writeScore(const Score& score, const std::filesystem::path& path,
                const AudioOptions& audio = {});
// The same in `format` to a file, a stream or memory.
void writeScore(const Score& score, MusicFormat format, const Destination& destination,
                const AudioOptions& audio = {});

}  // namespace graftal
