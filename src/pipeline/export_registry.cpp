// The export registry (export.hpp): one table of every format graftal writes, each row with
// the one function that writes it to a destination.
#include "graftal/pipeline/export.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "graftal/core/atomic_file.hpp"
#include "graftal/output/output.hpp"
#include "string_export.hpp"

namespace graftal {

namespace fs = std::filesystem;

namespace {

Error requestError(const std::string& message, const char* field = nullptr) {
    Diagnostic d{Severity::Error, SourceLocation{"graftal", 0, 0}, message};
    if (field) d.fields = {field};
    return Error(std::move(d));
}

// Pictures and 3D files: render()'s writer, the format named by the row's extension.
ExportResult writeRendered(const ExportFormat& format, const Model& model,
                           const ExportRequest& request, const Destination& destination) {
    RenderRequest render = request;
    // The checks read the format from the output's name; a stream or memory may have none.
    render.output = destination.kind() == Destination::Kind::File
                        ? destination.path()
                        : fs::path("output" + std::string(format.extension));
    // The checks that need no derivation (a view or a diagram asks for a picture).
    checkRenderRequest(render);
    return renderTo(model, render, *fileFormatFor(render.output), destination);
}

// The frames through the animation encoders, to any destination.
ExportResult writeAnimation(const ExportFormat& format, const Model& model,
                            const ExportRequest& request, const Destination& destination) {
    AnimationRequest animation = request;
    animation.output.clear();  // the destination is the output
    const AnimationResult a =
        writeAnimationTo(model, animation,
                         format.name == "gif"    ? AnimationFormat::Gif
                         : format.name == "webp" ? AnimationFormat::WebP
                                                 : AnimationFormat::Mp4,
                         destination);
    return ExportResult{a.to, a.route, a.notes, {}};
}

// A folder of PNG frames: only a folder on disk can hold it.
ExportResult writeFrames(const ExportFormat&, const Model& model, const ExportRequest& request,
                         const Destination& destination) {
    if (destination.kind() != Destination::Kind::File)
        throw requestError(
            "a folder of PNG frames can only be written to a folder on disk; "
            "use .gif, .webp or .mp4");
    AnimationRequest animation = request;
    animation.output = destination.path();
    checkAnimationRequest(animation);
    const AnimationResult a = writeAnimationFile(model, animation);
    return ExportResult{a.to, a.route, a.notes, {}};
}

// The music layer's format of a music row (the engraved scores share their extensions with
// the pictures: the row's name says which it is).
MusicFormat musicFormatOf(const ExportFormat& format) {
    const std::string_view name = format.name;
    if (name == "mid") return MusicFormat::Midi;
    if (name == "wav") return MusicFormat::Wav;
    if (name == "ly") return MusicFormat::LilyPond;
    if (name == "score-pdf") return MusicFormat::Pdf;
    if (name == "score-png") return MusicFormat::Png;
    if (name == "score-svg") return MusicFormat::Svg;
    return MusicFormat::MusicXml;
}

// The curve the turtle draws, read as a score (LSFP ch. 6.3) by the music layer, written by
// its writer of the row's extension.
ExportResult writeMusic(const ExportFormat& format, const Model& model,
                        const ExportRequest& request, const Destination& destination) {
    const Score score = scoreFromModel(model, requestedSteps(model, request),
                                       request.music.value_or(musicOptions(model.view)),
                                       derivationOptions(model, request));
    request.cancel.check();
    writeScore(score, musicFormatOf(format), destination, request.audio);
    return ExportResult{requestedSteps(model, request), RenderRoute::LineArt, {}, {}};
}

constexpr ExportFormat kFormats[] = {
    {"svg", ".svg", ExportKind::Picture, "line art (SVG)", false, false, true, writeRendered},
    {"png", ".png", ExportKind::Picture, "a picture: line art, or ray traced for 3D", true, false,
     true, writeRendered},
    {"pdf", ".pdf", ExportKind::Picture, "line art (PDF)", true, false, true, writeRendered},
    {"obj", ".obj", ExportKind::Mesh, "Wavefront OBJ with its .mtl materials", false, false, false,
     writeRendered},
    {"ply", ".ply", ExportKind::Mesh, "binary PLY with vertex colours", true, false, false,
     writeRendered},
    {"glb", ".glb", ExportKind::Mesh, "glTF 2.0 binary, repeated organs instanced", true, false,
     false, writeRendered},
    {"gif", ".gif", ExportKind::Animation, "animated GIF", true, false, false, writeAnimation},
    {"webp", ".webp", ExportKind::Animation, "animated WebP", true, false, false, writeAnimation},
    {"mp4", ".mp4", ExportKind::Animation, "H.264 video", true, false, false, writeAnimation},
    {"frames", "", ExportKind::Animation, "a folder of PNG frames", true, true, false, writeFrames},
    {"mid", ".mid", ExportKind::Music, "Standard MIDI File", true, false, false, writeMusic},
    {"wav", ".wav", ExportKind::Music, "audio played by FluidSynth", true, false, false,
     writeMusic},
    {"musicxml", ".musicxml", ExportKind::Music, "MusicXML notation", false, false, false,
     writeMusic},
    {"ly", ".ly", ExportKind::Music, "LilyPond source", false, false, false, writeMusic},
    {"score-pdf", ".pdf", ExportKind::Music, "the score engraved by LilyPond (PDF)", true, false,
     false, writeMusic},
    {"score-png", ".png", ExportKind::Music, "the score engraved by LilyPond (PNG)", true, false,
     false, writeMusic},
    {"score-svg", ".svg", ExportKind::Music, "the score engraved by LilyPond (SVG)", false, false,
     false, writeMusic},
    {"text", ".txt", ExportKind::String, "the derived string as the L-system file writes modules",
     false, false, false, writeDerivedString},
    {"json", ".json", ExportKind::String, "the derived string as JSON, one object per module",
     false, false, false, writeDerivedString},
};

std::string lowered(std::string_view text) {
    std::string s(text);
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

std::string_view exportKindName(ExportKind kind) {
    switch (kind) {
        case ExportKind::Picture:
            return "picture";
        case ExportKind::Mesh:
            return "3D file";
        case ExportKind::Animation:
            return "animation";
        case ExportKind::Music:
            return "music file";
        case ExportKind::String:
            return "string";
    }
    return "file";
}

namespace {

}  // namespace

std::span<const ExportFormat> exportFormats() {
    return kFormats;
}

const ExportFormat* findExportFormat(std::string_view nameOrExtension,
                                     std::optional<ExportKind> kind) {
    const std::string key = lowered(nameOrExtension);
    if (key.empty()) return nullptr;
    const std::string dotted = key.front() == '.' ? key : "." + key;
    // Alternative spellings of a few extensions.
    const std::string extension = dotted == ".midi"  ? ".mid"
                                  : dotted == ".xml" ? ".musicxml"
                                                     : dotted;
    for (const ExportFormat& f : kFormats)
        if ((!kind || f.kind == *kind) && (f.name == key || f.extension == extension)) return &f;
    return nullptr;
}

std::string exportFormatList(std::optional<ExportKind> kind, std::string_view separator,
                             std::string_view last) {
    std::vector<std::string> names;
    for (const ExportFormat& f : kFormats)
        if (!kind || f.kind == *kind)
            names.push_back(f.extension.empty() ? std::string("a folder")
                                                : std::string(f.extension));
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) list += i + 1 == names.size() ? last : separator;
        list += names[i];
    }
    return list;
}

const ExportFormat& exportFormatFor(const ExportRequest& request, const Destination& destination,
                                    std::optional<ExportKind> kind) {
    if (!request.format.empty()) {
        if (const ExportFormat* f = findExportFormat(request.format, kind)) return *f;
        throw requestError(
            "unknown format '" + request.format + "' (use " + exportFormatList(kind) + ")",
            "format");
    }
    const fs::path& path = destination.path();
    const std::string extension = path.extension().string();
    // A name without an extension, or ending in '/', is a folder of frames.
    if ((extension.empty() || path.filename().empty()) &&
        (!kind || *kind == ExportKind::Animation) && destination.kind() == Destination::Kind::File)
        if (const ExportFormat* f = findExportFormat("frames", kind)) return *f;
    if (!extension.empty())
        if (const ExportFormat* f = findExportFormat(extension, kind)) return *f;
    throw requestError(path.string() + ": unknown " + std::string(kind ? exportKindName(*kind) : "file") +
                           " format (use " + exportFormatList(kind) + ")",
                       "format");
}

ExportResult exportModel(const Model& model, const Destination& destination,
                         const ExportRequest& request) {
    const ExportFormat& format = exportFormatFor(request, destination);
    if (format.fileOnly && destination.kind() != Destination::Kind::File)
        throw requestError(std::string(format.description) + " can only be written to disk");
    return format.write(format, model, request, destination);
}

ExportResult exportMap(const MapLSystem& system, const Destination& destination,
                       const ExportRequest& request) {
    const ExportFormat& format = exportFormatFor(request, destination);
    if (!format.drawsMaps)
        throw requestError("a map L-system is drawn as a picture (" +
                           exportFormatList(ExportKind::Picture) + "), not as " +
                           std::string(format.description));
    if (request.view || request.derivationDiagram)
        throw requestError(
            "a view direction or a derivation diagram does not apply to a map "
            "L-system",
            request.view ? "view" : "derivationDiagram");
    const DerivedMap map = derivedMap(system, request.steps, request.map, request.cancel);
    request.cancel.check();
    Scene scene = drawnMap(map, request.map);
    RenderOptions options = request.picture;
    if (options.lineColor) scene.palette[0] = *options.lineColor, options.lineColor.reset();
    if (request.background) options.background = *request.background;
    const FileFormat picture = format.name == "svg"   ? FileFormat::Svg
                               : format.name == "png" ? FileFormat::Png
                                                      : FileFormat::Pdf;
    writeImage(scene, options, picture, destination);
    return ExportResult{map.map.step, RenderRoute::LineArt, {}, {}};
}

}  // namespace graftal
