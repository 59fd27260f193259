// render(): a model to a picture or a 3D file. 2D scenes become line art; 3D scenes become
// ray-traced PNGs and meshes, or line art seen from a view direction.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "graftal/bspline.hpp"
#include "graftal/color_map.hpp"
#include "graftal/derivation_diagram.hpp"
#include "graftal/file_format.hpp"
#include "graftal/framed_picture.hpp"
#include "graftal/kolam.hpp"
#include "graftal/material_file.hpp"
#include "graftal/mesh.hpp"
#include "graftal/mesh_scene.hpp"
#include "graftal/pipeline.hpp"
#include "graftal/render3d.hpp"
#include "graftal/streamed_picture.hpp"
#include "graftal/surface.hpp"
#include "graftal/turtle.hpp"
#include "pipeline/render_settings.hpp"

namespace graftal {

namespace {

Error requestError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

}  // namespace

// The settings render() and the animations share (render_settings.hpp).
std::filesystem::path sourceFolder(const Model& model, const RenderRequest& request) {
    const std::filesystem::path file =
        request.sourceFile.empty() ? std::filesystem::path(model.lsystem.file) : request.sourceFile;
    return file.parent_path();
}

// Surfaces a file declares (`surface: l leaf.s 0.5`) are read relative to the file; a
// name without a file on disk falls back to the built-in surfaces (leaf, petal).
SurfaceLibrary surfacesFor(const ViewSettings& view, const std::filesystem::path& dir) {
    SurfaceLibrary lib = SurfaceLibrary::builtin();
    for (const auto& decl : view.materials.surfaces) {
        std::filesystem::path path = dir / decl.file;
        Surface s;
        if (std::filesystem::exists(path)) {
            s = loadSurface(path);
        } else if (const Surface* builtin =
                       lib.find(std::filesystem::path(decl.file).stem().string())) {
            s = *builtin;
        } else {
            throw Error(decl.location, "surface file '" + decl.file + "' not found (looked in " +
                                           (dir.empty() ? std::string(".") : dir.string()) +
                                           " and the built-in surfaces)");
        }
        s.name = decl.name;
        s.size *= decl.scale;
        lib.add(std::move(s));
    }
    return lib;
}

// The file's view with the request's overrides.
RaytraceOptions raytraceOptions(const ViewSettings& v, const RenderRequest& request) {
    RaytraceOptions r;
    r.width = request.picture.width;
    r.height = request.picture.height;
    r.samplesPerPixel = request.samplesPerPixel;
    r.threads = request.threads;
    r.background = request.background ? *request.background
                                      : v.camera.background.value_or(request.picture.background);
    r.camera.viewpoint = request.viewpoint ? request.viewpoint : v.camera.viewpoint;
    r.camera.target = request.target ? request.target : v.camera.referencePoint;
    if (auto up = request.up ? request.up : v.camera.upVector) r.camera.up = *up;
    if (v.camera.twistDegrees != 0 && !request.up) {
        // cpfg's twist turns the camera about its viewing direction: 45 degrees turns the up
        // vector (0,1,0) of a camera looking along -z to (-0.71,0.71,0), as cpfg writes it.
        Vec3 d{0, 0, -1};
        if (r.camera.viewpoint && r.camera.target)
            d = normalizedOr(*r.camera.target - *r.camera.viewpoint, d);
        const double a = v.camera.twistDegrees * 3.14159265358979323846 / 180.0;
        const Vec3 u = r.camera.up;
        r.camera.up =
            u * std::cos(a) - cross(d, u) * std::sin(a) + d * (dot(d, u) * (1 - std::cos(a)));
    }
    if (auto fov = request.fieldOfView ? request.fieldOfView : v.camera.fieldOfView)
        r.camera.fieldOfView = *fov;
    r.camera.orthographic = v.camera.parallelProjection;
    r.camera.fitWindow = v.camera.parallelProjection && !request.viewpoint && !request.target;
    if (auto light = request.light ? request.light : v.camera.lightDirection)
        r.lighting.sunDirection = *light;
    r.ground = request.ground;
    if (v.camera.lightIntensity) r.lighting.sunIntensity = 0.9 * *v.camera.lightIntensity;
    if (v.camera.skyIntensity) r.lighting.skyIntensity = *v.camera.skyIntensity;
    return r;
}

void setPictureRadii(MeshOptions& mo, const Bounds& bounds, const RaytraceOptions& options) {
    if (bounds.empty()) return;
    // The size of a pixel where the camera looks, as it frames the scene's box (the scene
    // as drawn fills the picture a little more, so this errs towards thicker).
    const Camera camera = framedCamera(options.camera, bounds, options.width, options.height);
    const double distance = length(*camera.target - *camera.viewpoint);
    const double pixel =
        2 * distance * std::tan(camera.fieldOfView * 3.14159265358979323846 / 360) / options.height;
    if (!(pixel > 0) || !std::isfinite(pixel)) return;
    // A stem thinner than a pixel would vanish between the rays: it is drawn at least half a
    // pixel thick, as line art would. A stem under about two pixels across becomes a round
    // curve: its tube's sides could not be told apart there, and a curve costs a fraction of
    // a tube's memory and time. 3D files keep the true widths and tubes.
    mo.minimumRadius = 0.5 * pixel;
    mo.curveRadius = pixel;
}

// Line art's options: pfg's scale factor makes the picture fill that share of the frame
// (100 = all of it), and the file's background applies unless the request overrides it.
RenderOptions lineArtOptions(const Model& model, const RenderRequest& request) {
    RenderOptions render = request.picture;
    double fill = std::clamp(model.view.camera.scaleFactor / 100.0, 0.01, 1.0);
    render.margin = 0.5 - (0.5 - render.margin) * fill;
    if (request.background)
        render.background = *request.background;
    else if (model.view.camera.background)
        render.background = *model.view.camera.background;
    return render;
}

namespace {

// The derivation as a diagram: the axiom and the string after every step.
void renderDerivation(const Model& model, int steps, const RenderRequest& request) {
    std::vector<ModuleString> strings;
    Derivation derivation(model, derivationOptions(model, request));
    strings.push_back(derivation.current());
    for (int k = 0; k < steps; ++k) {
        derivation.step();
        strings.push_back(derivation.current());
    }
    RenderOptions render = request.picture;
    if (request.background)
        render.background = *request.background;
    else if (model.view.camera.background)
        render.background = *model.view.camera.background;
    request.cancel.check();
    writeDerivationDiagram(strings, model.lsystem.symbols, render, request.output);
}

// True when the string holds a label, @L: the module L right after an @.
bool hasLabels(const ModuleString& s) {
    const auto& symbols = s.symbols();
    for (std::size_t i = 0; i + 1 < symbols.size(); ++i)
        if (symbols[i] == '@' && symbols[i + 1] == 'L') return true;
    return false;
}

void addNote(RenderResult& result, const RenderRequest& request, const Model& model,
             std::string message) {
    Diagnostic d{Severity::Note, SourceLocation{model.lsystem.file, 0, 0}, std::move(message)};
    if (request.notify) request.notify(d);
    result.notes.push_back(std::move(d));
}

// The camera settings a request gives: they apply to ray-traced pictures only.
std::vector<std::string> cameraSettingsGiven(const RenderRequest& request) {
    const RenderRequest defaults;
    std::vector<std::string> given;
    if (request.viewpoint) given.push_back("viewpoint");
    if (request.target) given.push_back("target");
    if (request.up) given.push_back("up");
    if (request.light) given.push_back("light");
    if (request.fieldOfView) given.push_back("fieldOfView");
    if (request.samplesPerPixel != defaults.samplesPerPixel) given.push_back("samplesPerPixel");
    if (request.ground) given.push_back("ground");
    return given;
}

// The line art settings a request gives: a ray-traced picture or a 3D file has no lines.
std::vector<std::string> lineArtSettingsGiven(const RenderRequest& request) {
    const RenderOptions defaults;
    std::vector<std::string> given;
    if (request.picture.lineWidth != defaults.lineWidth) given.push_back("lineWidth");
    if (request.picture.lineColor) given.push_back("lineColor");
    if (request.picture.margin != defaults.margin) given.push_back("margin");
    return given;
}

// The GLB settings a request gives: they apply to .glb files only.
std::vector<std::string> glbSettingsGiven(const RenderRequest& request) {
    const GlbOptions defaults;
    std::vector<std::string> given;
    if (request.glb.instancing != defaults.instancing) given.push_back("glbInstancing");
    if (request.glb.compression != defaults.compression) given.push_back("glbCompression");
    return given;
}

void warnAt(RenderResult& result, const RenderRequest& request, SourceLocation where,
            std::string message) {
    Diagnostic d{Severity::Warning, std::move(where), std::move(message)};
    if (request.notify) request.notify(d);
    result.notes.push_back(std::move(d));
}

// Where surface `name` is first placed (`~` then `name`): the first production whose successor
// places it, or the file when only the axiom does.
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

// Settings the route taken does not use are said, not silently dropped.
void warnIgnored(RenderResult& result, const RenderRequest& request, const Model& model,
                 std::string message, std::vector<std::string> fields) {
    if (fields.empty()) return;
    Diagnostic d{Severity::Warning, SourceLocation{model.lsystem.file, 0, 0}, std::move(message)};
    d.fields = std::move(fields);
    if (request.notify) request.notify(d);
    result.notes.push_back(std::move(d));
}

// Line art (2D scenes, 3D ones seen from a view, streamed pictures and derivations): no
// camera, no tubes.
void warnLineArtIgnores(RenderResult& result, const RenderRequest& request, const Model& model,
                        bool scene3D) {
    std::vector<std::string> fields = cameraSettingsGiven(request);
    if (request.tubeSides != RenderRequest{}.tubeSides) fields.push_back("tubeSides");
    if (request.surfaceDivisions != RenderRequest{}.surfaceDivisions)
        fields.push_back("surfaceDivisions");
    for (std::string& f : glbSettingsGiven(request)) fields.push_back(std::move(f));
    warnIgnored(result, request, model,
                scene3D ? "the 3D scene is drawn as 2D line art; its 3D settings are ignored"
                        : "the scene is 2D and drawn as line art; 3D settings are ignored",
                std::move(fields));
}

}  // namespace

FileFormat checkRenderRequest(const RenderRequest& request) {
    const std::string output = request.output.string();
    const std::optional<FileFormat> format = fileFormatFor(output);
    if (!format) throw requestError(output + ": unknown format (use " + extensionList() + ")");
    const bool picture = fileFormatInfo(*format).kind == FormatKind::Picture;
    // Messages name the request's fields; the command names them as its flags.
    auto misfit = [](std::string message, std::string field) {
        Diagnostic d{Severity::Error, SourceLocation{"graftal", 0, 0}, std::move(message)};
        d.fields = {std::move(field)};
        return Error(std::move(d));
    };
    if (request.view && !picture)
        throw misfit("a view direction draws 2D line art; it applies to " +
                         extensionList(FormatKind::Picture, ", ", " and ") + ", not 3D files",
                     "view");
    if (request.derivationDiagram && !picture)
        throw misfit("a derivation diagram is a picture; use .svg, .png or .pdf",
                     "derivationDiagram");
    return *format;
}

Scene sceneForRender(const Model& model, ModuleString shown, const RenderRequest& request) {
    const bool path = request.splinePath.value_or(model.view.kolam.splineMode == SplineMode::Path);
    int subdivisions = request.spline.value_or(model.view.kolam.splineSubdivisions);
    if (request.splinePath.value_or(false) && !request.spline && subdivisions == 0)
        subdivisions = 8;
    // The kolams' B-spline runs through every position of the turtle, f moves included
    // (LSFP 6.2.3): the moves become drawn segments, so the whole path is one curve.
    if (path && subdivisions > 0)
        for (Symbol& s : shown.rawSymbols())
            if (s == 'f') s = 'F';
    Scene scene = interpret(model, shown);
    shown = ModuleString{};
    if (request.kolamDots || model.view.kolam.dots)
        addKolamDots(scene, model.view.turtle.stepLength, 0.08 * model.view.turtle.stepLength);
    if (subdivisions > 0) scene = smoothSegments(scene, subdivisions);
    return scene;
}

RenderResult render(const Model& model, const RenderRequest& request) {
    const std::string output = request.output.string();
    const std::optional<FileFormat> format = checkRenderRequest(request);
    const bool picture = fileFormatInfo(*format).kind == FormatKind::Picture;

    RenderResult result;
    result.steps = requestedSteps(model, request);
    const int steps = result.steps;
    if (request.derivationDiagram) {
        request.cancel.check();
        warnLineArtIgnores(result, request, model, false);
        renderDerivation(model, steps, request);
        result.route = RenderRoute::DerivationDiagram;
        return result;
    }

    {
        // A 2D PNG can be drawn while the derivation streams; everything else needs the scene.
        bool png2D = *format == FileFormat::Png;
        bool pixelBound = png2D && streamedPictureIsSummarised(model, steps, request.memoryLimit,
                                                               request.picture);
        // A picture with many strokes per pixel is drawn from its subtree summaries even when
        // its string would fit: its time then grows with the image, not with the string.
        // (The streamed picture has neither colour maps nor splines.)
        const bool plainLines = model.view.materials.colorMap.empty() &&
                                request.spline.value_or(model.view.kolam.splineSubdivisions) <= 0;
        if ((pixelBound && plainLines) ||
            shouldStream(model, steps, request, png2D, true, pixelBound, result.notes)) {
            warnLineArtIgnores(result, request, model, false);
            RenderOptions render = request.picture;
            double fill = std::clamp(model.view.camera.scaleFactor / 100.0, 0.01, 1.0);
            render.margin = 0.5 - (0.5 - render.margin) * fill;
            renderStreamedPng(model, steps, derivationOptions(model, request), render, output);
            result.route = RenderRoute::StreamedPicture;
            return result;
        }
    }
    const DerivationOptions derivation = derivationOptions(model, request);
    ModuleString modules = derive(model, steps, derivation);
    request.cancel.check();
    ModuleString shown = applyHomomorphism(model.lsystem, modules, derivation);
    // cpfg writes the text of @L("...") into its picture; graftal draws no text. Said once.
    if (hasLabels(shown)) addNote(result, request, model, "labels (@L) are not drawn");
    Scene scene = sceneForRender(model, std::move(shown), request);
    modules = ModuleString{};
    const std::filesystem::path folder = sourceFolder(model, request);
    if (!model.view.materials.colorMap.empty())
        scene.palette = loadColorMap(folder / model.view.materials.colorMap);

    if (picture && scene.segments.empty() && scene.polygonCount() == 0 && scene.surfaces.empty() &&
        scene.discs.empty() && scene.spheres.empty()) {
        // No turtle meaning (Anabaena's cells, the Fibonacci words): the derivation is
        // the picture the book draws for such systems.
        addNote(result, request, model, "the string draws nothing; drawing its derivation instead");
        warnLineArtIgnores(result, request, model, false);
        renderDerivation(model, steps, request);
        result.route = RenderRoute::DerivationDiagram;
        return result;
    }
    request.cancel.check();

    bool threeD = scene.is3D && !request.view;
    if (picture && !(threeD && *format == FileFormat::Png)) {
        // Line art: 2D scenes as they are, 3D scenes seen from the front unless told.
        // Discs and spheres are drawn as their projected outlines.
        warnLineArtIgnores(result, request, model, scene.is3D);
        if (scene.is3D || !scene.discs.empty() || !scene.spheres.empty())
            scene = projectScene(scene, request.view.value_or(ViewDirection::Front));
        writeImage(scene, lineArtOptions(model, request), output);
        result.route = RenderRoute::LineArt;
        return result;
    }

    warnIgnored(result, request, model,
                picture ? "the 3D scene is ray traced, without lines; line settings are ignored"
                        : "a 3D file holds no lines; line settings are ignored",
                lineArtSettingsGiven(request));
    if (!picture)
        warnIgnored(result, request, model,
                    "a 3D file holds no camera or light; these settings are ignored",
                    cameraSettingsGiven(request));
    if (*format != FileFormat::Glb)
        warnIgnored(result, request, model,
                    "instancing and compression settings apply to .glb files only; ignored",
                    glbSettingsGiven(request));
    // Uncoloured 3D plants are bark brown, not line art's ink, so their shading shows.
    if (model.view.materials.colorMap.empty()) scene.palette = defaultPalette3D();
    if (!model.view.materials.materialFile.empty())
        scene.palette = materialPalette(loadMaterials(folder / model.view.materials.materialFile));
    SurfaceLibrary surfaces = surfacesFor(model.view, folder);
    // cpfg draws nothing for a `~X` no `surface:` line declares: said, not an error.
    for (const std::string& name : removeUnknownSurfaces(scene, surfaces))
        warnAt(result, request, placedAt(model.lsystem, name),
               "'~" + name + "' places surface '" + name +
                   "', which no 'surface:' line declares: nothing is drawn for it (as in cpfg)");
    MeshOptions mo;
    // The view file's `cylinder sides:` unless --tube-sides was given.
    mo.tubeSides = request.tubeSides != RenderRequest{}.tubeSides
                       ? request.tubeSides
                       : model.view.materials.tubeSides.value_or(request.tubeSides);
    mo.surfaceDivisions = request.surfaceDivisions;
    mo.cylinders = model.view.materials.lineStyle == LineStyle::Cylinders;
    if (picture) setPictureRadii(mo, scene.bounds(), raytraceOptions(model.view, request));
    const MeshScene mesh = buildMeshScene(scene, mo, &surfaces);
    scene = Scene{};  // the meshes hold everything now: its memory goes before the render
    request.cancel.check();
    result.route = RenderRoute::Mesh;
    switch (*format) {
        case FileFormat::Obj:
            writeObj(mesh, output);
            break;
        case FileFormat::Ply:
            writePly(mesh, output);
            break;
        case FileFormat::Glb:
            writeGlb(mesh, output, request.glb);
            break;
        case FileFormat::Png:
        case FileFormat::Svg:
        case FileFormat::Pdf:
            // Only a 3D scene drawn as a PNG gets here: it is ray traced.
            renderRaytraced(mesh, raytraceOptions(model.view, request), output);
            result.route = RenderRoute::RayTraced;
            break;
    }
    return result;
}

}  // namespace graftal
