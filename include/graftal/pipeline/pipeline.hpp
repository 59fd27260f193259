// The whole road from a parsed model to a file, decided as the graftal command decides it:
// whether to stream, which surfaces and colour map, the camera (the file's view with the
// caller's overrides), ray tracing for 3D pictures, line art for 2D ones. A program that
// embeds graftal calls render() and gets the same picture `graftal render` would write.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/cancellation.hpp"
#include "graftal/core/destination.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/file_format.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/geometry/projection.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/output/output.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal {

enum class StreamPolicy {
    Auto,    // stream only when the string would not fit the memory limit (with a note)
    Always,  // always stream; an error when the L-system or the output cannot be streamed
};

// How to derive: what `-n`, `--seed`, `--threads`, `--memory-limit` and `--stream` say.
struct DeriveRequest {
    std::optional<int> steps;     // empty: the file's derivation length
    std::optional<int> maxSteps;  // the most steps a front end allows (the studio's limit)
    std::optional<std::uint64_t> seed;
    // Whose random numbers (`--random cpfg|graftal`); empty: as the model says.
    std::optional<RandomStreams> random;
    unsigned threads = 0;  // 0: one per core
    std::size_t memoryLimit = std::size_t(2) << 30;
    StreamPolicy stream = StreamPolicy::Auto;
    // The most modules a streamed run may expand one by one (a picture drawn from subtree
    // summaries expands a few per pixel and is not counted against it).
    std::uint64_t streamLimit = 100'000'000'000ull;
    // Called after every derivation step with the step and the string's size.
    std::function<void(int step, std::size_t modules)> progress;
    // Called at once with every note (e.g. "streaming it instead"); they are also returned.
    std::function<void(const Diagnostic&)> notify;
    // Where a model's printf writes (cpfg writes to standard error). Empty: dropped.
    std::function<void(std::string_view)> print;
    // Answers the ?E modules instead of the environment the file's `environment:` lines
    // describe: one a program supplies (a binding's, written in its own language). Shared,
    // as requests are copied from stage to stage.
    std::shared_ptr<Environment> environment;
    CancellationToken cancel;
    // How parameters are stored (DerivationOptions::precision).
    Precision precision = Precision::Single;
};

struct RenderRequest : DeriveRequest {
    std::filesystem::path output;  // its extension picks the format (see file_format.hpp)
    // Surfaces and colour maps named by the model are read relative to this file's folder;
    // empty: the model's own file.
    std::filesystem::path sourceFile;
    RenderOptions picture;              // size, margin, line width, ...
    std::optional<Rgb> background;      // overrides the file's background
    std::optional<ViewDirection> view;  // draw a 3D scene as line art seen from here
    // Camera overrides for ray-traced pictures; each empty one takes the file's view.
    std::optional<Vec3> viewpoint, target, up, light;
    std::optional<double> fieldOfView;
    int samplesPerPixel = 4;
    int tubeSides = 8;
    int surfaceDivisions = 8;   // grid cells per side of a surface's patch (see MeshResolution)
    bool ground = false;        // ray-traced pictures: a floor under the plant, with its shadow
    std::optional<int> spline;  // B-spline subdivisions (0: off); empty: the file's
    // The spline through every turtle position, f moves included (kolams); empty: the file's.
    std::optional<bool> splinePath;
    bool kolamDots = false;  // draw the kolam's dots (also when the file says `kolam dots: on`)
    bool derivationDiagram = false;  // draw the derivation steps, not the turtle's picture
    GlbOptions glb;                  // .glb files: instancing, compression
};

enum class RenderRoute {
    StreamedPicture,    // drawn while the derivation streamed
    LineArt,            // 2D (or projected 3D) picture
    RayTraced,          // 3D scene as a ray-traced PNG
    Mesh,               // OBJ, PLY or glTF binary
    DerivationDiagram,  // the strings of every step, asked for or because nothing is drawn
};

struct RenderResult {
    int steps = 0;
    RenderRoute route = RenderRoute::LineArt;
    std::vector<Diagnostic> notes;
    // An OBJ's materials (.mtl text) when the OBJ went to a stream or memory; a file's
    // are written beside it.
    std::string materials;
};

// How finely a 3D scene is meshed: the sides of a stem's tube and the grid cells per side
// of a surface's Bézier patch (RenderRequest::tubeSides, surfaceDivisions).
struct MeshResolution {
    int tubeSides = 8;
    int surfaceDivisions = 8;
};

// What `--quality` names: low (5 sides, 4 divisions), medium (8 and 8, the default), high
// (16 and 16), or a number N from 3 to 64 (N sides, N divisions). Empty for anything else.
std::optional<MeshResolution> meshResolutionFor(std::string_view quality);

// The steps a request asks for: its own, else the model's derivation length. Throws Error
// (about the field "steps") for a negative count or one over request.maxSteps: the one
// place a step count is checked.
int requestedSteps(const Model& model, const DeriveRequest& request);
// The same check for any step count (a map L-system's): returns `steps`.
int checkedSteps(int steps, std::optional<int> maxSteps = std::nullopt,
                 const std::string& file = {});

// Whether to stream. Auto: when the predicted string would not fit the memory limit and
// `canStream` (with a note saying whether the string or the picture's geometry does not
// fit). When it would not fit and cannot stream, throws before anything is allocated; the
// Error's Diagnostic carries its remedies (Remedy). A streamed run that would expand more
// than streamLimit modules one by one is refused; a `pixelBound` picture (drawn from
// subtree summaries, its time growing with its pixels) expands a few per pixel.
bool shouldStream(const Model& model, int steps, const DeriveRequest& request, bool canStream,
                  bool countGeometry, bool pixelBound, std::vector<Diagnostic>& notes);

// `error` with Remedy::Stream added when it is the memory limit met by a held derivation
// that streaming would not meet: the growth could not be predicted ahead (conditions), so
// shouldStream() held the string. The stream is suggested, not taken by itself: without a
// prediction nothing bounds how long it would run. Empty for any other error (rethrow it
// as it is: it may be a Cancelled).
std::optional<Error> withStreamRemedy(const Error& error, const Model& model,
                                      const DeriveRequest& request, bool canStream);

// Returns work() (a held derivation for `request`); what it throws is rethrown, with
// Remedy::Stream added where withStreamRemedy() adds it.
template <class Work>
auto suggestingStream(const Model& model, const DeriveRequest& request, bool canStream,
                      Work&& work) {
    try {
        return work();
    } catch (const Error& e) {
        if (auto suggested = withStreamRemedy(e, model, request, canStream)) throw *suggested;
        throw;
    }
}

// The options of a derivation made for a request (its query resolver places the turtle of
// the model's view).
DerivationOptions derivationOptions(const Model& model, const DeriveRequest& request);

// The request's output format; throws Error for an unknown extension or options that do not
// fit it (a view or a derivation diagram for a 3D file), before anything is derived.
FileFormat checkRenderRequest(const RenderRequest& request);

// The scene render() draws for the derived (and homomorphism-applied) string `shown`: the
// turtle's scene with the request's or the file's B-spline smoothing (through the drawn
// segments, or through the whole path with f moves when `spline: path`) and kolam dots.
Scene sceneForRender(const Model& model, ModuleString shown, const RenderRequest& request);

// A picture or 3D file of `format` to any destination: the writer of those formats in the
// export registry (export.hpp). Throws Error (Cancelled when request.cancel is raised).
RenderResult renderTo(const Model& model, const RenderRequest& request, FileFormat format,
                      const Destination& destination);

// Derives and renders to request.output as `graftal render` does. Throws Error (Cancelled
// when request.cancel is raised); no partial output file is left.
RenderResult render(const Model& model, const RenderRequest& request);

}  // namespace graftal
