// The one registry of what graftal writes: every format of every kind (pictures, 3D files,
// animations, music, a map's picture), found by name or extension, each written by one
// function to a Destination (a file, a stream or memory). The graftal command, the studio
// and programs that embed the library all export through exportModel(); none routes
// formats of its own.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/destination.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/music/music.hpp"
#include "graftal/pipeline/animation.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/pipeline/stages.hpp"

namespace graftal {

enum class ExportKind {
    Picture,    // line art, a ray-traced 3D picture or a derivation diagram (.svg .png .pdf)
    Mesh,       // a 3D file (.obj .ply .glb)
    Animation,  // the development as frames (.gif .webp .mp4, a folder of PNG frames)
    Music,      // the curve read as a score (.mid .wav .musicxml .ly, an engraved score)
    String,     // the derived module string itself, as text or JSON (`graftal derive`)
};

// Every option of every writer; each writer reads what concerns it. The derivation, picture
// and camera settings are RenderRequest's, the frames' AnimationRequest's.
struct ExportRequest : AnimationRequest {
    // The format's name ("png", "glb", "score-pdf") or extension (".png"); empty: from the
    // destination's name (a file's extension).
    std::string format;
    // Music: the score's reading (empty: the model's `music ...:` settings over the
    // defaults) and the synthesiser's settings for audio.
    std::optional<MusicOptions> music;
    AudioOptions audio;
    // Map L-systems: geometry, outline and drawing.
    MapRequest map;
    // The derived string: after the homomorphism (`derive --homo`), and the input's name in
    // its JSON (empty: the model's file).
    bool homomorphism = false;
    std::string inputName;
};

// What a writer did: the steps drawn, the route taken, its notes and an OBJ's materials
// when the OBJ went to a stream or memory (render()'s result, for every format).
using ExportResult = RenderResult;

struct ExportFormat {
    std::string_view name;       // unique: "png", "score-pdf", "frames"
    std::string_view extension;  // with the dot, lower case; empty for a folder
    ExportKind kind;
    std::string_view description;
    bool binary = true;      // false for text formats (SVG, OBJ, MusicXML, LilyPond)
    bool fileOnly = false;   // a folder, or files beside it: never a stream or memory
    bool drawsMaps = false;  // a map L-system can be written in it
    // Writes the model in this row's format.
    ExportResult (*write)(const ExportFormat&, const Model&, const ExportRequest&,
                          const Destination&) = nullptr;
};

// "picture", "3D file", "animation", "music file": for messages and menus.
std::string_view exportKindName(ExportKind kind);

// Every format, in the order the command lists them.
std::span<const ExportFormat> exportFormats();

// By name or extension (with or without the dot, any case), of `kind` when given: the
// pictures come before the engraved scores, so ".pdf" is a picture unless the kind is
// Music. nullptr for an unknown one.
const ExportFormat* findExportFormat(std::string_view nameOrExtension,
                                     std::optional<ExportKind> kind = std::nullopt);

// The format a request names, else the one of the destination's name (a folder without
// an extension is PNG frames when the kind allows it). Throws Error naming the known
// formats of `kind`.
const ExportFormat& exportFormatFor(const ExportRequest& request, const Destination& destination,
                                    std::optional<ExportKind> kind = std::nullopt);

// "svg, png, pdf, ..." of one kind (or all): for messages and help.
std::string exportFormatList(std::optional<ExportKind> kind = std::nullopt,
                             std::string_view separator = ", ", std::string_view last = " or ");

// Derives, draws and writes the model in the request's format to the destination. Throws
// Error (Cancelled when request.cancel is raised); a file destination is never left
// half-written.
ExportResult exportModel(const Model& model, const Destination& destination,
                         const ExportRequest& request);

// A map L-system's picture (the formats with drawsMaps).
ExportResult exportMap(const MapLSystem& system, const Destination& destination,
                       const ExportRequest& request);

}  // namespace graftal
