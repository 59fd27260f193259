// The studio's computations, each through the library's own calls: parse(), the
// pipeline's stream decision and derivation options, interpret(), buildMeshScene() and
// render().
#include "studio/studio_model.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>

#include "graftal/animation.hpp"
#include "graftal/bspline.hpp"
#include "graftal/color_map.hpp"
#include "graftal/mesh.hpp"
#include "graftal/mesh_scene.hpp"
#include "graftal/music.hpp"
#include "graftal/output.hpp"
#include "graftal/pipeline.hpp"
#include "graftal/polyline_scene.hpp"
#include "graftal/projection.hpp"
#include "graftal/streamed_picture.hpp"
#include "graftal/surface.hpp"
#include "graftal/turtle.hpp"
#include "lang/source_text.hpp"
#include "studio/zip_archive.hpp"

namespace graftal::studio {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A fresh file name in the scratch folder: requests run at the same time.
fs::path scratchFile(const fs::path& scratch, const std::string& extension) {
    static std::atomic<unsigned long> counter{0};
    return scratch / ("s" + std::to_string(counter.fetch_add(1)) + "." + extension);
}

std::string readAndRemove(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    std::error_code ec;
    fs::remove(path, ec);
    return bytes.str();
}

Model parseOrThrow(const ModelInput& input) {
    ParseResult result = parseInput(input);
    if (!result.ok()) throw Error(result.errors());
    return std::move(result.model);
}

DeriveRequest deriveRequest(const ModelInput& input, const StudioLimits& limits,
                            const CancellationToken& cancel) {
    DeriveRequest request;
    request.steps = input.steps;
    request.memoryLimit = limits.memoryLimit;
    request.streamLimit = limits.streamLimit;
    request.cancel = cancel;
    // A derivation that runs too long is stopped like a superseded one.
    const auto deadline =
        Clock::now() + std::chrono::milliseconds(static_cast<long>(limits.deriveSeconds * 1000));
    CancellationToken token = cancel;
    request.progress = [deadline, token](int, std::size_t) mutable {
        if (Clock::now() > deadline) token.cancel();
    };
    return request;
}

int checkedSteps(const Model& model, const DeriveRequest& request, const StudioLimits& limits) {
    const int steps = requestedSteps(model, request);
    if (steps > limits.maxSteps)
        throw Error(SourceLocation{model.lsystem.file, 0, 0},
                    "derivation length " + std::to_string(steps) +
                        " is over the studio's limit of " + std::to_string(limits.maxSteps));
    return steps;
}

nlohmann::json boundsJson(const Bounds& b) {
    if (b.empty()) return nullptr;
    return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
}

// Surfaces a file declares are read beside it; unknown files fall back to the built-ins
// (as render() does).
SurfaceLibrary surfacesFor(const ViewSettings& view, const fs::path& folder) {
    SurfaceLibrary lib = SurfaceLibrary::builtin();
    for (const auto& decl : view.materials.surfaces) {
        Surface s;
        const fs::path path = folder / decl.file;
        if (fs::exists(path)) {
            s = loadSurface(path);
        } else if (const Surface* builtin = lib.find(fs::path(decl.file).stem().string())) {
            s = *builtin;
        } else {
            throw Error(decl.location, "surface file '" + decl.file + "' not found");
        }
        s.name = decl.name;
        s.size *= decl.scale;
        lib.add(std::move(s));
    }
    return lib;
}

// The turtle's polylines of earlier requests, kept with their memory: a keystroke then
// writes into pages it has written before instead of faulting in fresh ones.
std::mutex workspaceMutex;
std::vector<std::unique_ptr<PolylineScene>> workspaces;

std::unique_ptr<PolylineScene> takeWorkspace() {
    std::lock_guard lock(workspaceMutex);
    if (workspaces.empty()) return std::make_unique<PolylineScene>();
    std::unique_ptr<PolylineScene> w = std::move(workspaces.back());
    workspaces.pop_back();
    return w;
}

void returnWorkspace(std::unique_ptr<PolylineScene> w) {
    constexpr std::size_t kKept = 2;  // as many as derivations run at once, about
    w->rest = Scene{};
    std::lock_guard lock(workspaceMutex);
    if (workspaces.size() < kKept) workspaces.push_back(std::move(w));
}

// What interpret() draws of a derived (and homomorphism-applied) string, smoothed and
// coloured as the view file says.
Scene sceneOf(const Model& model, const ModuleString& modules) {
    Scene scene = interpret(model, modules);
    if (int n = model.view.kolam.splineSubdivisions; n > 0) scene = smoothSegments(scene, n);
    if (!model.view.materials.colorMap.empty())
        scene.palette = loadColorMap(fs::path(model.lsystem.file).parent_path() /
                                     model.view.materials.colorMap);
    return scene;
}

}  // namespace

fs::path viewFileBeside(const fs::path& modelFile) {
    std::error_code ec;
    const fs::path same = fs::path(modelFile).replace_extension(".v");
    if (fs::is_regular_file(same, ec)) return same;
    fs::path onlyView;
    int models = 0, views = 0;
    for (const auto& e : fs::directory_iterator(modelFile.parent_path(), ec)) {
        if (!e.is_regular_file(ec)) continue;
        if (e.path().extension() == ".l") ++models;
        if (e.path().extension() == ".v") ++views, onlyView = e.path();
        if (models > 1 || views > 1) return {};
    }
    return models == 1 && views == 1 ? onlyView : fs::path();
}

ParseResult parseInput(const ModelInput& input) {
    ParseOptions options;
    options.fileName = input.file.string();
    options.defines = input.defines;
    if (input.viewFile.empty()) return parse(input.text, options);
    return parse(input.text, input.viewText, input.viewFile.string(), options);
}

std::string pictureKey(const ModelInput& input) {
    std::string key =
        input.file.string() + '\n' + (input.steps ? std::to_string(*input.steps) : "-") + '\n';
    for (const auto& [name, value] : input.defines) key += name + '=' + value + '\n';
    key += input.viewFile.string() + '\n' + input.viewText + "\n--\n";
    SourceText source;
    DiagnosticList diagnostics;
    if (input.text.find("#include") != std::string::npos ||
        !prepareSource(input.text, input.file.string(), source, diagnostics)) {
        static std::atomic<unsigned long> unique{0};
        return key + std::to_string(unique.fetch_add(1)) + '\n' + input.text;
    }
    for (const SourceLine& line : source.lines) {
        key += std::to_string(line.number) + ':';
        const std::string& t = line.text;
        std::size_t i = t.find_first_not_of(" \t\r");
        if (i == std::string::npos)
            i = t.size();  // a blank line (a comment's, perhaps)
        else
            key.append(t, 0, i);  // leading blanks kept: a line starting with TAB continues
        bool blank = false;
        for (; i < t.size(); ++i) {
            const char c = t[i];
            if (c == ' ' || c == '\t' || c == '\r') {
                blank = true;
                continue;
            }
            if (blank) key += ' ';
            blank = false;
            const std::size_t end = std::min(skipStringLiteral(t, i), t.size() - 1);
            key.append(t, i, end - i + 1);  // a string literal keeps its blanks
            i = end;
        }
        key += '\n';
    }
    return key;
}

std::string pictureTag(const std::string& key) {
    char tag[17];
    std::snprintf(tag, sizeof tag, "%016zx", std::hash<std::string>{}(key));
    return tag;
}

std::vector<NumericDefine> numericDefines(const std::string& text) {
    std::vector<NumericDefine> defines;
    std::istringstream lines(text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
        std::istringstream words(line);
        std::string directive, name, value;
        if (!(words >> directive >> name >> value) || directive != "#define") continue;
        const char* begin = value.c_str();
        char* end = nullptr;
        const double v = std::strtod(begin, &end);
        if (end == begin || *end != '\0' || !std::isfinite(v)) continue;
        std::string rest;
        if (words >> rest && rest.rfind("/*", 0) != 0) continue;  // an expression, not a number
        defines.push_back({name, v, number, value.find_first_of(".eE") == std::string::npos});
    }
    return defines;
}

nlohmann::json diagnosticsJson(const std::vector<Diagnostic>& diagnostics) {
    nlohmann::json list = nlohmann::json::array();
    for (const Diagnostic& d : diagnostics) {
        const char* severity = d.severity == Severity::Error     ? "error"
                               : d.severity == Severity::Warning ? "warning"
                                                                 : "note";
        list.push_back({{"severity", severity},
                        {"line", d.location.line},
                        {"column", d.location.column},
                        {"endLine", d.location.endLine},
                        {"endColumn", d.location.endColumn},
                        {"message", d.message},
                        {"file", fs::path(d.location.file).filename().string()},
                        {"text", d.toString()}});
    }
    return list;
}

nlohmann::json parseReport(const ModelInput& input) {
    return parseReport(input, parseInput(input));
}

nlohmann::json parseReport(const ModelInput& input, const ParseResult& result) {
    nlohmann::json defines = nlohmann::json::array();
    for (const NumericDefine& d : numericDefines(input.text))
        defines.push_back(
            {{"name", d.name}, {"value", d.value}, {"line", d.line}, {"integer", d.integer}});
    return {{"ok", result.ok()},
            {"diagnostics", diagnosticsJson(result.diagnostics)},
            {"viewFile", input.viewFile.filename().string()},
            {"defines", defines},
            {"derivationLength", result.model.lsystem.derivationLength},
            {"name", result.model.lsystem.name}};
}

StudioPicture derivePicture(const ModelInput& input, const StudioLimits& limits,
                            const CancellationToken& cancel, const fs::path& scratch) {
    return derivePicture(input, parseOrThrow(input), limits, cancel, scratch);
}

StudioPicture derivePicture(const ModelInput& input, Model parsed, const StudioLimits& limits,
                            const CancellationToken& cancel, const fs::path& scratch) {
    StudioPicture picture;
    picture.model = std::move(parsed);
    const Model& model = picture.model;
    const DeriveRequest request = deriveRequest(input, limits, cancel);
    picture.steps = checkedSteps(model, request, limits);
    const int steps = picture.steps;
    const auto start = Clock::now();

    std::vector<Diagnostic> notes;
    const bool pixelBound = streamedPictureIsSummarised(model, steps, request.memoryLimit);
    if (shouldStream(model, steps, request, true, true, pixelBound, notes)) {
        // Too large to hold: the streamed picture render() draws, as a PNG.
        RenderRequest render;
        static_cast<DeriveRequest&>(render) = request;
        render.steps = steps;
        render.output = scratchFile(scratch, "png");
        render.sourceFile = input.file;
        graftal::render(model, render);
        picture.summaryPng = readAndRemove(render.output);
        for (const Diagnostic& d : notes) picture.notes.push_back(d.message);
        picture.notes.push_back("the string is too large to draw here: a summarised picture");
        picture.stats = {
            {"steps", steps}, {"summarised", true}, {"deriveMs", millisecondsSince(start)}};
        return picture;
    }

    const DerivationOptions options = derivationOptions(model, request);
    ModuleString modules = derive(model, steps, options);
    const double deriveMs = millisecondsSince(start);
    cancel.check();
    for (std::size_t i = 0; i < modules.size() && i < limits.stringHeadModules; ++i)
        appendModuleText(picture.stringHead, model.lsystem.symbols, modules.symbol(i),
                         modules.params(i));
    const std::size_t moduleCount = modules.size();

    if (!model.lsystem.homomorphism.empty())
        modules = applyHomomorphism(model.lsystem, modules, options);
    cancel.check();

    // The turtle writes polylines into a workspace of an earlier request (no Scene of 88
    // bytes a segment, no fresh pages); a smoothed model needs the scene's segments.
    const auto drawStart = Clock::now();
    std::unique_ptr<PolylineScene> lines = takeWorkspace();
    if (model.view.kolam.splineSubdivisions > 0) {
        const Scene scene = sceneOf(model, modules);
        lines->clear();
        lines->rest = scene;  // the summary and the stats read it; encoded as a scene
        lines->segments = scene.segments.size();
        lines->segmentBounds = scene.bounds();
    } else {
        interpretPolylines(model, modules, *lines);
        if (!model.view.materials.colorMap.empty())
            lines->rest.palette =
                loadColorMap(input.file.parent_path() / model.view.materials.colorMap);
    }
    const double drawMs = millisecondsSince(drawStart);
    cancel.check();
    const Scene& rest = lines->rest;
    picture.segments = lines->segments;

    const std::size_t organs =
        rest.polygonCount() + rest.surfaces.size() + rest.discs.size() + rest.spheres.size();
    picture.stats = {{"steps", steps},
                     {"modules", moduleCount},
                     {"segments", lines->segments},
                     {"polygons", organs},
                     {"bbox", boundsJson(lines->bounds())},
                     {"is3D", rest.is3D},
                     {"deriveMs", deriveMs},
                     {"drawMs", drawMs},
                     {"summarised", false}};
    if (lines->segments > limits.segmentBudget) {
        // Over the budget the browser gets a picture, not the segments.
        const Scene scene = sceneOf(model, modules);
        RenderOptions render;
        if (model.view.camera.background) render.background = *model.view.camera.background;
        const fs::path png = scratchFile(scratch, "png");
        writeImage(scene.is3D ? projectScene(scene, ViewDirection::Front) : scene, render, png);
        picture.summaryPng = readAndRemove(png);
        picture.notes.push_back(std::to_string(scene.segments.size()) +
                                " segments are over the studio's budget of " +
                                std::to_string(limits.segmentBudget) + ": a summarised picture");
        picture.stats["summarised"] = true;
        returnWorkspace(std::move(lines));
        return picture;
    }
    const auto encodeStart = Clock::now();
    picture.lines = rest.segments.empty() ? encodeLines(*lines) : encodeLines(rest);
    picture.stats["encodeMs"] = millisecondsSince(encodeStart);
    returnWorkspace(std::move(lines));
    picture.modules = std::move(modules);
    return picture;
}

Scene pictureScene(const StudioPicture& picture) {
    return sceneOf(picture.model, picture.modules);
}

std::string meshGlb(const StudioPicture& picture, const fs::path& scratch) {
    Scene scene = pictureScene(picture);
    if (picture.model.view.materials.colorMap.empty()) scene.palette = defaultPalette3D();
    const SurfaceLibrary surfaces =
        surfacesFor(picture.model.view, fs::path(picture.model.lsystem.file).parent_path());
    MeshOptions options;
    options.tubeSides = 6;
    // Stems thinner than about a pixel of an 800-pixel view are widened so that they show.
    if (const Bounds b = scene.bounds(); !b.empty()) {
        const double extent = std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
        options.minimumRadius = 0.5 * extent / 500.0;
    }
    // Repeated organs (leaves, flowers) once each, placed by EXT_mesh_gpu_instancing, the
    // buffers compressed by EXT_meshopt_compression: the page's loader reads both.
    options.instancing = true;
    const MeshScene mesh = buildMeshScene(scene, options, &surfaces);
    const fs::path glb = scratchFile(scratch, "glb");
    writeGlb(mesh, glb, GlbOptions{.instancing = true, .compression = true});
    return readAndRemove(glb);
}

const std::vector<std::string>& exportFormats() {
    static const std::vector<std::string> formats = {"png", "svg",      "pdf",  "glb", "obj",
                                                     "ply", "gif",      "webp", "mp4", "mid",
                                                     "wav", "musicxml", "ly"};
    return formats;
}

ExportedFile exportFile(const ModelInput& input, const std::string& format,
                        const StudioLimits& limits, const CancellationToken& cancel,
                        const fs::path& scratch) {
    const auto& formats = exportFormats();
    if (std::find(formats.begin(), formats.end(), format) == formats.end())
        throw Error(SourceLocation{"studio", 0, 0}, "unknown export format '" + format + "'");
    const Model model = parseOrThrow(input);
    const std::string stem = input.file.stem().string();
    const fs::path output = scratchFile(scratch, format);
    const DeriveRequest derive = deriveRequest(input, limits, cancel);
    const int steps = checkedSteps(model, derive, limits);

    auto oneOf = [&](std::initializer_list<const char*> list) {
        return std::any_of(list.begin(), list.end(), [&](const char* f) { return format == f; });
    };
    if (oneOf({"gif", "webp", "mp4"})) {
        // graftal animate: every step from 0 to the slider's, one fixed camera.
        AnimationRequest request;
        static_cast<DeriveRequest&>(request) = derive;
        request.steps = steps;
        request.output = output;
        request.sourceFile = input.file;
        checkAnimationRequest(request);
        writeAnimationFile(model, request);
        return {stem + "." + format, readAndRemove(output)};
    }
    if (oneOf({"mid", "wav", "musicxml", "ly"})) {  // not png, svg, pdf: those are pictures
        // graftal music: the curve at the slider's step, the file's `music` settings.
        const Score score = scoreFromModel(model, steps, musicOptions(model.view),
                                           derivationOptions(model, derive));
        cancel.check();
        writeScore(score, output);
        return {stem + "." + format, readAndRemove(output)};
    }
    RenderRequest request;
    static_cast<DeriveRequest&>(request) = derive;
    request.output = output;
    request.sourceFile = input.file;
    checkRenderRequest(request);
    render(model, request);
    if (format != "obj") return {stem + "." + format, readAndRemove(output)};
    // The OBJ names its material library by file name: both go in one archive, renamed
    // after the model, so that they unpack side by side.
    std::string obj = readAndRemove(output);
    const std::string mtl = readAndRemove(fs::path(output).replace_extension(".mtl"));
    const std::string scratchName = "mtllib " + output.stem().string() + ".mtl";
    if (const auto at = obj.find(scratchName); at != std::string::npos)
        obj.replace(at, scratchName.size(), "mtllib " + stem + ".mtl");
    return {stem + "-obj.zip", storedZip({{stem + ".obj", obj}, {stem + ".mtl", mtl}})};
}

std::string thumbnailPng(const fs::path& file, const fs::path& viewFile, int size,
                         const StudioLimits& limits, const fs::path& scratch) {
    ParseOptions options;
    options.viewFile = viewFile.string();
    ParseResult parsed = loadModel(file, options);
    if (!parsed.ok()) throw Error(parsed.errors());
    RenderRequest request;
    static_cast<DeriveRequest&>(request) =
        deriveRequest(ModelInput{{}, file, std::nullopt, {}, {}, {}}, limits, CancellationToken{});
    checkedSteps(parsed.model, request, limits);
    request.output = scratchFile(scratch, "png");
    request.picture.width = request.picture.height = size;
    request.samplesPerPixel = 1;
    render(parsed.model, request);
    return readAndRemove(request.output);
}

}  // namespace graftal::studio
