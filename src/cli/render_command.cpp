// graftal render: a picture (SVG, PNG, PDF) or a 3D file (OBJ, PLY, glTF binary).
// 2D scenes become line art; 3D scenes become ray-traced PNGs and meshes, or line art
// seen from a --view.
#include <algorithm>
#include <filesystem>

#include "commands.hpp"
#include "graftal/bspline.hpp"
#include "graftal/color_map.hpp"
#include "graftal/derivation.hpp"
#include "graftal/derivation_diagram.hpp"
#include "graftal/file_format.hpp"
#include "graftal/mesh.hpp"
#include "graftal/projection.hpp"
#include "graftal/render3d.hpp"
#include "graftal/streamed_picture.hpp"
#include "graftal/surface.hpp"
#include "graftal/turtle.hpp"

namespace graftal::cli {

namespace {

// Surfaces a file declares (`surface: l leaf.s 0.5`) are read relative to the file; a
// name without a file on disk falls back to the built-in surfaces (leaf, petal).
SurfaceLibrary surfacesFor(const ViewSettings& view, const std::string& file) {
    SurfaceLibrary lib = SurfaceLibrary::builtin();
    std::filesystem::path dir = std::filesystem::path(file).parent_path();
    for (const auto& decl : view.surfaces) {
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

RaytraceOptions raytraceOptions(const ViewSettings& v, const RenderCommandOptions& out,
                                unsigned threads) {
    RaytraceOptions r;
    r.width = out.render.width;
    r.height = out.render.height;
    r.samplesPerPixel = out.samplesPerPixel;
    r.threads = threads;
    r.background =
        out.backgroundGiven ? out.render.background : v.background.value_or(out.render.background);
    r.camera.viewpoint = out.viewpoint ? out.viewpoint : v.viewpoint;
    r.camera.target = out.target ? out.target : v.viewReferencePoint;
    if (auto up = out.up ? out.up : v.upVector) r.camera.up = *up;
    if (auto fov = out.fieldOfView ? out.fieldOfView : v.fieldOfView) r.camera.fieldOfView = *fov;
    r.camera.orthographic = v.parallelProjection;
    if (auto light = out.light ? out.light : v.lightDirection) r.lighting.sunDirection = *light;
    return r;
}

// The derivation as a diagram: the axiom and the string after every step.
void renderDerivation(const Model& model, int steps, const InputOptions& in,
                      const RenderCommandOptions& out) {
    const LSystem& ls = model.lsystem;
    std::vector<ModuleString> strings;
    Derivation derivation(model, derivationOptions(in, model));
    strings.push_back(derivation.current());
    for (int k = 0; k < steps; ++k) {
        derivation.step();
        strings.push_back(derivation.current());
    }
    derivation.finish();
    endProgressLine();
    RenderOptions render = out.render;
    if (!out.backgroundGiven && model.view.background) render.background = *model.view.background;
    writeDerivationDiagram(strings, ls.symbols, render, out.output);
}

}  // namespace

int runRender(const InputOptions& in, const RenderCommandOptions& out) {
    const std::optional<FileFormat> format = fileFormatFor(out.output);
    if (!format)
        throw Error(SourceLocation{"graftal", 0, 0},
                    "-o " + out.output + ": unknown format (use " + extensionList() + ")");
    const bool picture = fileFormatInfo(*format).kind == FormatKind::Picture;
    std::optional<ViewDirection> view;
    if (!out.view.empty()) {
        view = viewDirectionFromName(out.view);
        if (!view)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "--view '" + out.view + "': expected front, back, side or top");
        if (!picture)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "--view draws 2D line art; it applies to " +
                            extensionList(FormatKind::Picture, ", ", " and ") + ", not 3D files");
    }

    Loaded l = loadInput(in);
    if (out.derivation) {
        if (!picture)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "--derivation draws a picture; use .svg, .png or .pdf");
        renderDerivation(l.model, l.steps, in, out);
        return 0;
    }

    {
        // A 2D PNG can be drawn while the derivation streams; everything else needs the scene.
        bool png2D = *format == FileFormat::Png;
        bool pixelBound = png2D && streamedPictureIsSummarised(l.model, l.steps, in.memoryLimit);
        if (chooseStreaming(l, in, png2D, true, pixelBound)) {
            RenderOptions render = out.render;
            double fill = std::clamp(l.model.view.scaleFactor / 100.0, 0.01, 1.0);
            render.margin = 0.5 - (0.5 - render.margin) * fill;
            renderStreamedPng(l.model, l.steps, derivationOptions(in, l.model), render, out.output);
            return 0;
        }
    }
    Derived d = deriveLoaded(std::move(l), in);
    Scene scene =
        interpret(d.model, applyHomomorphism(d.model.lsystem, d.modules, derivationOptions(in, d.model)));
    if (int n = out.spline.value_or(d.model.view.splineSubdivisions); n > 0)
        scene = smoothSegments(scene, n);
    if (!d.model.view.colorMap.empty()) {
        std::filesystem::path map =
            std::filesystem::path(in.file).parent_path() / d.model.view.colorMap;
        scene.palette = loadColorMap(map);
    }

    if (picture && scene.segments.empty() && scene.polygonCount() == 0 &&
        scene.surfaces.empty() && scene.discs.empty() && scene.spheres.empty()) {
        // No turtle meaning (Anabaena's cells, the Fibonacci words): the derivation is
        // the picture the book draws for such systems.
        note(in, "the string draws nothing; drawing its derivation instead");
        renderDerivation(d.model, d.steps, in, out);
        return 0;
    }

    bool threeD = scene.is3D && !view;
    if (picture && !(threeD && *format == FileFormat::Png)) {
        // Line art: 2D scenes as they are, 3D scenes seen from the front unless told; discs
        // and spheres are drawn as their projected outlines.
        if (scene.is3D || !scene.discs.empty() || !scene.spheres.empty())
            scene = projectScene(scene, view.value_or(ViewDirection::Front));
        RenderOptions render = out.render;
        // pfg's scale factor: the picture fills that share of the frame (100 = all of it).
        double fill = std::clamp(d.model.view.scaleFactor / 100.0, 0.01, 1.0);
        render.margin = 0.5 - (0.5 - render.margin) * fill;
        if (!out.backgroundGiven && d.model.view.background)
            render.background = *d.model.view.background;
        writeImage(scene, render, out.output);
        return 0;
    }

    // Uncoloured 3D plants are bark brown, not line art's ink, so their shading shows.
    if (d.model.view.colorMap.empty()) scene.palette = defaultPalette3D();
    SurfaceLibrary surfaces = surfacesFor(d.model.view, in.file);
    MeshOptions mo;
    mo.tubeSides = out.tubeSides;
    mo.cylinders = d.model.view.lineStyle == LineStyle::Cylinders;
    if (picture) {
        // In a picture, a stem thinner than a pixel would vanish between the rays: draw it at
        // least about a pixel wide, as line art would. 3D files keep the true widths.
        Bounds b = scene.bounds();
        if (!b.empty()) {
            double extent = std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
            double pixel = extent / (0.6 * std::min(out.render.width, out.render.height));
            mo.minimumRadius = 0.5 * pixel;
        }
    }
    Mesh mesh = buildMesh(scene, mo, &surfaces);
    switch (*format) {
        case FileFormat::Obj:
            writeObj(mesh, out.output);
            break;
        case FileFormat::Ply:
            writePly(mesh, out.output);
            break;
        case FileFormat::Glb:
            writeGlb(mesh, out.output);
            break;
        case FileFormat::Png:
        case FileFormat::Svg:
        case FileFormat::Pdf:
            // Only a 3D scene drawn as a PNG gets here: it is ray traced.
            renderRaytraced(mesh, raytraceOptions(d.model.view, out, in.threads), out.output);
            break;
    }
    return 0;
}

}  // namespace graftal::cli
