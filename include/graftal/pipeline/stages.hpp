// The pipeline's stages, in the order the data flows: a model is derived, its string drawn
// by the turtle into a scene, the scene meshed, and the mesh or scene made a picture or a
// file (export.hpp). Every front end — the graftal command, the studio, a program that
// embeds the library — calls these and assembles nothing of its own, so that one model looks
// the same wherever it is shown. Requests are RenderRequest (pipeline.hpp): what a stage does
// not use it ignores.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/maps/map_drawing.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/maps/plane_map.hpp"
#include "graftal/output/render3d.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/turtle/polyline_scene.hpp"

namespace graftal {

// A derived model: the string after `steps` steps and what the turtle reads of it.
struct Derived {
    int steps = 0;
    // The derived string, as `graftal derive` prints it. Emptied by shownString() when the
    // homomorphism leaves it as it is (its memory is then `shown`'s).
    ModuleString modules;
    std::size_t moduleCount = 0;  // modules.size() before anything was moved out
    std::vector<Diagnostic> notes;
};

// Derives the model for the request: the steps checked once (requestedSteps), the
// derivation options of the model's view (derivationOptions), cancellation and progress as
// the request says. Throws Error (Cancelled when request.cancel is raised).
Derived derived(const Model& model, const DeriveRequest& request);

// What the turtle reads: the derived string after the homomorphism (the string itself,
// moved, when the model has none).
ModuleString shownString(const Model& model, Derived& derived, const DeriveRequest& request);

// The turtle's scene of a shown string, as every front end draws it: B-spline smoothing (the
// request's, else the file's; through the drawn segments, or through the whole path with f
// moves when `spline: path`), kolam dots, and the file's colour map (read beside the
// request's source file, else the model's file).
Scene drawn(const Model& model, ModuleString shown, const RenderRequest& request);

// The same as polylines into `lines` (its buffers reused): the turtle's fast path for line
// art and the studio. A model that smooths its paths is drawn as a scene, kept in
// `lines.rest` with `lines.segments` and `lines.segmentBounds` set from it.
void drawnLines(const Model& model, const ModuleString& shown, const RenderRequest& request,
                PolylineScene& lines);

// Whether drawn() smooths the paths (a spline through the segments or the whole path).
bool drawsSplines(const Model& model, const RenderRequest& request);

// What a mesh is made for, which decides how thin stems and repeated organs are meshed.
enum class MeshPurpose {
    File,     // OBJ, PLY, GLB: true widths, tubes everywhere
    Picture,  // ray tracing: stems at least half a pixel thick, the thinnest as curves
    Viewer,   // an interactive 3D view: few sides, stems widened to show, organs instanced
};

// The parts of meshing that hold for every frame of a model: surfaces, palette, options.
struct MeshSetup {
    MeshOptions options;
    SurfaceLibrary surfaces;
    std::optional<std::vector<Rgb>> palette;  // the 3D palette, over the scene's own
    MeshPurpose purpose = MeshPurpose::File;
};

// The model's surfaces (read beside the source), its 3D palette (materials, else bark brown
// unless a colour map colours it) and the request's mesh resolution for `purpose`.
MeshSetup meshSetup(const Model& model, const RenderRequest& request, MeshPurpose purpose);

// The scene meshed: surfaces the file does not declare are dropped with a warning at the
// production that places them (as cpfg draws nothing for them). For pictures, call
// setPictureRadii(setup.options, …) first (render_settings.hpp does it for ray tracing).
MeshScene meshed(const Model& model, Scene scene, const MeshSetup& setup,
                 std::vector<Diagnostic>& notes);

// The file's camera and light with the request's overrides (ray-traced pictures).
RaytraceOptions cameraFor(const Model& model, const RenderRequest& request);

// How a map L-system (LSFP ch. 5) is derived and drawn.
struct MapRequest {
    MapDerivationOptions derivation;  // geometry (siero, relaxed) and outline
    MapDrawingOptions drawing;        // fill, widths, splines
};

// A derived map and what its steps reported.
struct DerivedMap {
    PlaneMap map;
    MapStepReport last;
    long long relaxIterations = 0;  // over all steps
};

// Derives a map L-system `steps` steps (the file's derivation length when empty).
DerivedMap derivedMap(const MapLSystem& system, std::optional<int> steps, const MapRequest& request,
                      const CancellationToken& cancel = {});

// The map's cell walls (and fills) as a 2D scene.
Scene drawnMap(const DerivedMap& map, const MapRequest& request);

}  // namespace graftal
