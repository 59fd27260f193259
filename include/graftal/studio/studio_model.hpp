// What the studio computes for a page: a parse report, a derived picture with its stats,
// and the bytes the browser draws (line segments as typed arrays, meshes as glTF binary,
// exported files through the pipeline's render()).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "graftal/core/cancellation.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/studio/line_buffer.hpp"

namespace graftal::studio {

// What one request may cost: the server refuses or summarises past these.
struct StudioLimits {
    std::size_t bodyBytes = std::size_t(1) << 20;    // a request body (a model's text)
    std::size_t memoryLimit = std::size_t(1) << 30;  // a derivation's strings
    std::uint64_t streamLimit = 10'000'000'000ull;   // the largest string streamed
    std::uint64_t segmentBudget = 2'000'000;         // more: a summarised picture
    std::uint64_t meshSegmentBudget = 150'000;       // more: the 3D view draws lines
    int maxSteps = 10'000;                           // derivation length
    std::size_t stringHeadModules = 2'000;           // modules of the string shown
    double deriveSeconds = 60;                       // then the derivation is stopped
};

// A model as the page holds it: its text (perhaps unsaved), where it lives and the
// overrides the page's sliders set.
struct ModelInput {
    std::string text;
    std::filesystem::path file;  // absolute; names in diagnostics, surfaces beside it
    std::optional<int> steps;    // empty: the file's derivation length
    std::map<std::string, std::string> defines;
    // The view file applied after the text (as `graftal render model.l model.v`), and its
    // text read when the request came: empty for none.
    std::filesystem::path viewFile;
    std::string viewText;
};

// The view file the studio applies to a model file: NAME.v beside NAME.l, else the one .v
// of a model folder (a folder with one .l and one .v, as vlab lays models out). Empty for
// none.
std::filesystem::path viewFileBeside(const std::filesystem::path& modelFile);

// The text parsed, then its view file's settings applied over it (loadModel's order).
ParseResult parseInput(const ModelInput& input);

// A `#define NAME number` line of the text, for a slider.
struct NumericDefine {
    std::string name;
    double value = 0;
    int line = 0;  // 1-based
    bool integer = false;
};
std::vector<NumericDefine> numericDefines(const std::string& text);

// Diagnostics as the page shows them, each with its file's name (the page underlines those
// of the file it edits and lists those of its view file).
nlohmann::json diagnosticsJson(const std::vector<Diagnostic>& diagnostics);

// What decides the picture: the file, steps and overrides, and the text with its comments
// blanked (as the parser blanks them) and runs of blanks made one. An edit in a comment or
// in spacing keeps the key, and the picture already made is reused. A text that includes
// other files gets a key of its own every time (the included files may have changed).
std::string pictureKey(const ModelInput& input);
// A short tag of a key, for the page to say which picture it shows.
std::string pictureTag(const std::string& key);

// {ok, diagnostics, defines, derivationLength, name}: never throws for bad text.
nlohmann::json parseReport(const ModelInput& input);
// The same from the input's parse result (parseInput), when the caller has it already.
nlohmann::json parseReport(const ModelInput& input, const ParseResult& result);

// A derived model ready to draw: its line buffer, or a summarised PNG when over the budget.
// The derived string is kept, not its scene: the 3D view's mesh interprets it again when
// asked (pictureScene), while a keystroke costs no Scene of every segment.
struct StudioPicture {
    Model model;
    int steps = 0;
    ModuleString modules;  // the string the turtle reads (after the homomorphism)
    std::uint64_t segments = 0;
    std::string summaryPng;  // non-empty: the scene was too large; no modules or lines kept
    std::string stringHead;  // the first modules of the derived string
    std::vector<std::string> notes;
    nlohmann::json stats;   // modules, segments, polygons, bbox, deriveMs, drawMs, is3D, encodeMs
    std::string lines;      // the line buffer, made once and sent again while unchanged
    ExportRequest request;  // the pipeline's request it was made with
    // A map L-system's drawn cell layer (its walls), kept whole: a map has no string.
    std::optional<Scene> mapScene;
};

// Parses, derives, interprets and encodes the line buffer. Throws Error (with every parse
// error), Cancelled when `cancel` is raised or the derivation outlasts the limit.
StudioPicture derivePicture(const ModelInput& input, const StudioLimits& limits,
                            const CancellationToken& cancel, const std::filesystem::path& scratch);
// The same for the model parsed from `input` (parseInput, without errors).
StudioPicture derivePicture(const ModelInput& input, Model parsed, const StudioLimits& limits,
                            const CancellationToken& cancel, const std::filesystem::path& scratch);

// The picture's mesh (stems as tubes, polygons, surfaces) as glTF binary: repeated organs
// instanced (EXT_mesh_gpu_instancing) and the buffers compressed (EXT_meshopt_compression)
// as far as writeGlb(MeshScene) does so.
// The scene of a picture that is not summarised: its string interpreted again, smoothed and
// coloured as the line buffer was.
Scene pictureScene(const StudioPicture& picture);

std::string meshGlb(const StudioPicture& picture, const std::filesystem::path& scratch);

// A download: its file name and bytes.
struct ExportedFile {
    std::string fileName;
    std::string bytes;
};

// The formats the page exports: every row of the pipeline's export registry that a download
// can hold (not a folder of frames), each written by the row's writer as the command writes
// it (an OBJ comes as a .zip holding the OBJ and its .mtl). The page builds its export menu
// from this list (/api/info).
const std::vector<const ExportFormat*>& studioExportFormats();

// The model exported as `format` (one of exportFormats(); anything else throws Error).
ExportedFile exportFile(const ModelInput& input, const std::string& format,
                        const StudioLimits& limits, const CancellationToken& cancel,
                        const std::filesystem::path& scratch);

// A small PNG of a model file as render() draws it.
// `viewFile` (perhaps empty) is applied as the live view applies it.
std::string thumbnailPng(const std::filesystem::path& file, const std::filesystem::path& viewFile,
                         int size, const StudioLimits& limits,
                         const std::filesystem::path& scratch);

}  // namespace graftal::studio
