// graftal music: the options become MusicOptions over the file's `music ...:` settings; the
// library derives, reads the curve and writes the score.
#include "music_command.hpp"

#include <filesystem>

#include "commands.hpp"
#include "graftal/music/music.hpp"
#include "graftal/pipeline/export.hpp"

namespace graftal::cli {

namespace {

Error optionError(const std::string& option, const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, option + ": " + message);
}

}  // namespace

void addMusicOptions(CLI::App& cmd, MusicCommandOptions& o) {
    cmd.add_option("-o,--output", o.output, "output file: " + musicExtensionList())->required();
    cmd.add_option("--scale", o.scale,
                   "major, minor, pentatonic, blues, chromatic, or semitone offsets such as "
                   "0,2,4,7,9 (default: the file's, else major)");
    cmd.add_option("--root", o.root, "the first note, e.g. C4 (middle C, the default) or 60");
    cmd.add_option("--tempo", o.tempo, "beats per minute (default 120)");
    cmd.add_option("--instrument", o.instrument, "General MIDI program 1..128 (1: piano)");
    cmd.add_option("--axis", o.axis,
                   "y: pitch from y, time from horizontal moves (the book's reading); x: the "
                   "other way round");
    cmd.add_option("--unit", o.unit, "beats per step length (default 1: a quarter note)");
    cmd.add_option("--sample-rate", o.sampleRate, "audio samples per second for .wav (44100)")
        ->check(CLI::Range(8000, 96000));
    cmd.add_option("--soundfont", o.soundFont,
                   "General MIDI SoundFont (.sf2) for .wav (default: the best installed one)");
}

int runMusic(const InputOptions& in, const MusicCommandOptions& o) {
    // The music format of the output's extension, from the export registry (.pdf, .png and
    // .svg are engraved scores here, not pictures).
    const ExportFormat* format =
        findExportFormat(std::filesystem::path(o.output).extension().string(), ExportKind::Music);
    if (!format)
        throw optionError("-o",
                          "'" + o.output + "': expected a music file " + musicExtensionList());
    Loaded l = loadInput(in);
    MusicOptions options = musicOptions(l.model.view);
    if (!o.scale.empty())
        if (std::string e = parseScale(o.scale, options.scale); !e.empty())
            throw optionError("--scale", e);
    if (!o.root.empty())
        if (std::string e = parseNoteName(o.root, options.root); !e.empty())
            throw optionError("--root", e);
    if (o.tempo) options.tempo = *o.tempo;
    if (o.instrument) options.instrument = *o.instrument;
    if (o.unit) options.unit = *o.unit;
    if (!o.axis.empty()) {
        if (o.axis != "x" && o.axis != "y")
            throw optionError("--axis", "expected x or y, got '" + o.axis + "'");
        options.pitchFromX = o.axis == "x";
    }
    ExportRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(in);
    request.steps = l.steps;
    request.format = format->name;
    request.music = options;
    request.audio.sampleRate = o.sampleRate;
    request.audio.soundFont = o.soundFont;
    request.audio.memoryLimit = in.memoryLimit;
    exportModel(l.model, Destination::file(o.output), request);
    endProgressLine();
    return 0;
}

}  // namespace graftal::cli
