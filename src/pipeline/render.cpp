// render(): a model to a picture or a 3D file. 2D scenes become line art; 3D scenes become
// ray-traced PNGs and meshes, or line art seen from a view direction.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "graftal/core/file_format.hpp"
#include "graftal/geometry/bspline.hpp"
#include "graftal/geometry/color_map.hpp"
#include "graftal/geometry/kolam.hpp"
#include "graftal/geometry/material_file.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/surface.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/output/derivation_diagram.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/render3d.hpp"
#include "graftal/output/streamed_picture.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/turtle/turtle.hpp"
#include "render_settings.hpp"

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
        const double a = radians(v.camera.twistDegrees);
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
    const double pixel = 2 * distance * std::tan(radians(camera.fieldOfView / 2)) / options.height;
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
void renderDerivation(const Model& model, int steps, const RenderRequest& request,
                      const Destination& destination) {
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
    const std::optional<ImageFormat> format = imageFormatFor(destination.path());
    writeDerivationDiagram(strings, model.lsystem.symbols, render,
                           format.value_or(ImageFormat::Svg), destination);
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
    return drawn(model, std::move(shown), request);
}

RenderResult renderTo(const Model& model, const RenderRequest& request, FileFormat fileFormat,
                      const Destination& destination) {
    const std::optional<FileFormat> format = fileFormat;
    const bool picture = fileFormatInfo(*format).kind == FormatKind::Picture;

    RenderResult result;
    result.steps = requestedSteps(model, request);
    const int steps = result.steps;
    if (request.derivationDiagram) {
        request.cancel.check();
        warnLineArtIgnores(result, request, model, false);
        renderDerivation(model, steps, request, destination);
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
                                !drawsSplines(model, request) && !request.kolamDots &&
                                !model.view.kolam.dots;
        if ((pixelBound && plainLines) ||
            shouldStream(model, steps, request, png2D, true, pixelBound, result.notes)) {
            warnLineArtIgnores(result, request, model, false);
            RenderOptions render = request.picture;
            double fill = std::clamp(model.view.camera.scaleFactor / 100.0, 0.01, 1.0);
            render.margin = 0.5 - (0.5 - render.margin) * fill;
            renderStreamedPng(model, steps, derivationOptions(model, request), render, destination);
            result.route = RenderRoute::StreamedPicture;
            return result;
        }
    }
    Derived derivedModel = derived(model, request);
    ModuleString shown = shownString(model, derivedModel, request);
    derivedModel.modules = ModuleString{};
    // cpfg writes the text of @L("...") into its picture; graftal draws no text. Said once.
    if (hasLabels(shown)) addNote(result, request, model, "labels (@L) are not drawn");
    Scene scene = drawn(model, std::move(shown), request);

    if (picture && scene.segments.empty() && scene.polygonCount() == 0 && scene.surfaces.empty() &&
        scene.discs.empty() && scene.spheres.empty()) {
        // No turtle meaning (Anabaena's cells, the Fibonacci words): the derivation is
        // the picture the book draws for such systems.
        addNote(result, request, model, "the string draws nothing; drawing its derivation instead");
        warnLineArtIgnores(result, request, model, false);
        renderDerivation(model, steps, request, destination);
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
        writeImage(scene, lineArtOptions(model, request), *format, destination);
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
    MeshSetup setup = meshSetup(model, request, picture ? MeshPurpose::Picture : MeshPurpose::File);
    if (picture)
        setPictureRadii(setup.options, scene.bounds(), raytraceOptions(model.view, request));
    std::vector<Diagnostic> meshNotes;
    const MeshScene mesh = meshed(model, std::move(scene), setup, meshNotes);
    for (Diagnostic& d : meshNotes) {
        if (request.notify) request.notify(d);
        result.notes.push_back(std::move(d));
    }
    scene = Scene{};  // the meshes hold everything now: its memory goes before the render
    request.cancel.check();
    result.route = RenderRoute::Mesh;
    switch (*format) {
        case FileFormat::Obj: {
            // The materials beside the OBJ: a file's .mtl, else a name the OBJ points to.
            std::filesystem::path mtlName = destination.path();
            mtlName.replace_extension(".mtl");
            if (destination.kind() == Destination::Kind::File) {
                if (mtlName == destination.path())
                    throw fileError(destination.path(), "cannot write OBJ: the materials go to '" +
                                                            mtlName.string() +
                                                            "'; use the extension .obj");
                writeObj(mesh, destination, Destination::file(mtlName));
            } else {
                writeObj(mesh, destination, Destination::memory(result.materials, mtlName));
            }
            break;
        }
        case FileFormat::Ply:
            writePly(mesh, destination);
            break;
        case FileFormat::Glb:
            writeGlb(mesh, destination, request.glb);
            break;
        case FileFormat::Png:
        case FileFormat::Svg:
        case FileFormat::Pdf:
            // Only a 3D scene drawn as a PNG gets here: it is ray traced.
            if (destination.kind() == Destination::Kind::File) {
                // A file's folder is checked before the tracing.
                renderRaytraced(mesh, raytraceOptions(model.view, request), destination.path());
            } else {
                const RaytraceOptions options = raytraceOptions(model.view, request);
                writeRgbaPng(RgbaImage::fromRgb(renderRaytracedPixels(mesh, options), options.width,
                                                options.height),
                             destination);
            }
            result.route = RenderRoute::RayTraced;
            break;
    }
    return result;
}

RenderResult render(const Model& model, const RenderRequest& request) {
    checkRenderRequest(request);
    ExportRequest exportRequest;
    static_cast<RenderRequest&>(exportRequest) = request;
    return exportModel(model, Destination::file(request.output), exportRequest);
}

}  // namespace graftal
