// The pipeline's stages (stages.hpp): derive, draw, mesh. Every picture, file, animation
// frame and studio view is made through these, so a model looks the same in each.
#include "graftal/pipeline/stages.hpp"

#include <algorithm>
#include <filesystem>

#include "graftal/geometry/bspline.hpp"
#include "graftal/geometry/color_map.hpp"
#include "graftal/geometry/kolam.hpp"
#include "graftal/geometry/material_file.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/turtle/turtle.hpp"
#include "render_settings.hpp"

namespace graftal {

namespace fs = std::filesystem;

Derived derived(const Model& model, const DeriveRequest& request) {
    Derived d;
    d.steps = requestedSteps(model, request);
    request.cancel.check();
    d.modules = derive(model, d.steps, derivationOptions(model, request));
    d.moduleCount = d.modules.size();
    request.cancel.check();
    return d;
}

ModuleString shownString(const Model& model, Derived& derived, const DeriveRequest& request) {
    if (model.lsystem.homomorphism.empty()) return std::move(derived.modules);
    ModuleString shown =
        applyHomomorphism(model.lsystem, derived.modules, derivationOptions(model, request));
    request.cancel.check();
    return shown;
}

namespace {

// The B-spline subdivisions drawn() smooths with (0: none) and whether the spline runs
// through the whole path (kolams).
struct Smoothing {
    int subdivisions = 0;
    bool path = false;
};

Smoothing smoothingFor(const Model& model, const RenderRequest& request) {
    Smoothing s;
    s.path = request.splinePath.value_or(model.view.kolam.splineMode == SplineMode::Path);
    s.subdivisions = request.spline.value_or(model.view.kolam.splineSubdivisions);
    if (request.splinePath.value_or(false) && !request.spline && s.subdivisions == 0)
        s.subdivisions = 8;
    return s;
}

bool drawsKolamDots(const Model& model, const RenderRequest& request) {
    return request.kolamDots || model.view.kolam.dots;
}

// The colour map's palette, when the file names one.
void applyColorMap(const Model& model, const RenderRequest& request, Scene& scene) {
    if (!model.view.materials.colorMap.empty())
        scene.palette = loadColorMap(sourceFolder(model, request) / model.view.materials.colorMap);
}

// Where surface `name` is first placed (`~` then `name`): the first production whose
// successor places it, or the file when only the axiom does.
SourceLocation placedAt(const LSystem& ls, const std::string& name) {
    // `~` is a module of its own (as in cpfg): the surface is the module after it.
    const int tilde = ls.symbols.find("~");
    const int symbol = ls.symbols.find(name);
    for (const auto* list : {&ls.productions, &ls.decomposition, &ls.homomorphism})
        for (const Production& p : *list)
            for (std::size_t i = 0; i + 1 < p.successor.size(); ++i)
                if (static_cast<int>(p.successor[i].symbol) == tilde &&
                    static_cast<int>(p.successor[i + 1].symbol) == symbol)
                    return p.location;
    return SourceLocation{ls.file, 0, 0};
}

}  // namespace

bool drawsSplines(const Model& model, const RenderRequest& request) {
    return smoothingFor(model, request).subdivisions > 0;
}

Scene drawn(const Model& model, ModuleString shown, const RenderRequest& request) {
    const Smoothing smoothing = smoothingFor(model, request);
    // The kolams' B-spline runs through every position of the turtle, f moves included
    // (LSFP 6.2.3): the moves become drawn segments, so the whole path is one curve.
    if (smoothing.path && smoothing.subdivisions > 0)
        for (Symbol& s : shown.rawSymbols())
            if (s == 'f') s = 'F';
    Scene scene = interpret(model, shown);
    shown = ModuleString{};
    if (drawsKolamDots(model, request))
        addKolamDots(scene, model.view.turtle.stepLength, 0.08 * model.view.turtle.stepLength);
    if (smoothing.subdivisions > 0) scene = smoothSegments(scene, smoothing.subdivisions);
    applyColorMap(model, request, scene);
    return scene;
}

void drawnLines(const Model& model, const ModuleString& shown, const RenderRequest& request,
                PolylineScene& lines) {
    if (drawsSplines(model, request) || drawsKolamDots(model, request)) {
        // Smoothed paths and dots are drawn by the scene's own code; the line buffer
        // encodes the scene as it is.
        Scene scene = drawn(model, shown, request);
        lines.clear();
        lines.segments = scene.segments.size();
        lines.segmentBounds = scene.bounds();
        lines.rest = std::move(scene);
        return;
    }
    interpretPolylines(model, shown, lines);
    applyColorMap(model, request, lines.rest);
}

MeshSetup meshSetup(const Model& model, const RenderRequest& request, MeshPurpose purpose) {
    MeshSetup setup;
    setup.purpose = purpose;
    const fs::path folder = sourceFolder(model, request);
    setup.surfaces = surfacesFor(model.view, folder);
    // Uncoloured 3D plants are bark brown, not line art's ink, so their shading shows.
    if (model.view.materials.colorMap.empty()) setup.palette = defaultPalette3D();
    if (!model.view.materials.materialFile.empty())
        setup.palette = materialPalette(loadMaterials(folder / model.view.materials.materialFile));
    MeshOptions& mo = setup.options;
    // The view file's `cylinder sides:` unless the request names its own.
    mo.tubeSides = request.tubeSides != RenderRequest{}.tubeSides
                       ? request.tubeSides
                       : model.view.materials.tubeSides.value_or(request.tubeSides);
    mo.surfaceDivisions = request.surfaceDivisions;
    mo.cylinders = model.view.materials.lineStyle == LineStyle::Cylinders;
    if (purpose == MeshPurpose::Viewer) {
        // Repeated organs (leaves, flowers) once each, placed by instancing; few sides, as
        // a live view redraws the mesh at every turn.
        mo.tubeSides = 6;
        mo.instancing = true;
    }
    return setup;
}

MeshScene meshed(const Model& model, Scene scene, const MeshSetup& setup,
                 std::vector<Diagnostic>& notes) {
    if (setup.palette) scene.palette = *setup.palette;
    // cpfg draws nothing for a `~X` no `surface:` line declares: said, not an error.
    for (const std::string& name : removeUnknownSurfaces(scene, setup.surfaces))
        notes.push_back(Diagnostic{
            Severity::Warning, placedAt(model.lsystem, name),
            "'~" + name + "' places surface '" + name +
                "', which no 'surface:' line declares: nothing is drawn for it (as in cpfg)"});
    MeshOptions options = setup.options;
    if (setup.purpose == MeshPurpose::Viewer) {
        // Stems thinner than about a pixel of an 800-pixel view are widened so that they
        // show.
        if (const Bounds b = scene.bounds(); !b.empty()) {
            const double extent =
                std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
            options.minimumRadius = 0.5 * extent / 500.0;
        }
    }
    return buildMeshScene(scene, options, &setup.surfaces);
}

RaytraceOptions cameraFor(const Model& model, const RenderRequest& request) {
    return raytraceOptions(model.view, request);
}

DerivedMap derivedMap(const MapLSystem& system, std::optional<int> steps, const MapRequest& request,
                      const CancellationToken& cancel) {
    const int n = checkedSteps(steps.value_or(system.derivationLength), std::nullopt, system.file);
    DerivedMap d;
    d.map = deriveMap(system, n, request.derivation, [&](const PlaneMap&, const MapStepReport& r) {
        d.last = r;
        d.relaxIterations += r.relaxIterations;
        cancel.check();
    });
    return d;
}

Scene drawnMap(const DerivedMap& map, const MapRequest& request) {
    return mapScene(map.map, request.drawing);
}

}  // namespace graftal
