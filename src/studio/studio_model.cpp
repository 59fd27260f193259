// The studio's computations, each through the pipeline's stages (stages.hpp) and its
// export registry (export.hpp): the studio turns a page's request into the pipeline's
// request and the result into bytes for the page, and assembles nothing of its own.
#include "graftal/studio/studio_model.hpp"

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

#include "graftal/core/destination.hpp"
#include "graftal/geometry/projection.hpp"
#include "graftal/lang/source_text.hpp"
#include "graftal/maps/map_lsystem.hpp"
#include "graftal/output/output.hpp"
#include "graftal/output/streamed_picture.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/studio/zip_archive.hpp"
#include "graftal/turtle/polyline_scene.hpp"

namespace graftal::studio {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Model parseOrThrow(const ModelInput& input) {
    ParseResult result = parseInput(input);
    if (!result.ok()) throw Error(result.errors());
    return std::move(result.model);
}

// The pipeline's request for a page's model: its steps, the studio's limits, the model's
// file for what it names (surfaces, colour maps).
ExportRequest pipelineRequest(const ModelInput& input, const StudioLimits& limits,
                              const CancellationToken& cancel) {
    ExportRequest request;
    request.steps = input.steps;
    request.maxSteps = limits.maxSteps;
    request.audio.memoryLimit = limits.memoryLimit;
    request.sourceFile = input.file;
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

nlohmann::json boundsJson(const Bounds& b) {
    if (b.empty()) return nullptr;
    return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
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
    if (isMapLSystemText(input.text)) {
        // A map L-system: its diagnostics, and a model that only names it (derivePicture
        // derives the map itself).
        MapParseResult map = parseMapLSystem(input.text, options);
        ParseResult result;
        result.diagnostics = std::move(map.diagnostics);
        result.model.lsystem.file = input.file.string();
        result.model.lsystem.derivationLength = map.system.derivationLength;
        return result;
    }
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

namespace {

// A map L-system's cell layer (LSFP ch. 5) as the page draws it: its walls as lines.
StudioPicture deriveMapPicture(const ModelInput& input, StudioPicture picture) {
    const ExportRequest& request = picture.request;
    ParseOptions options;
    options.fileName = input.file.string();
    options.defines = input.defines;
    const MapLSystem system = parseMapLSystem(input.text, options).orThrow();
    const auto start = Clock::now();
    const DerivedMap map = derivedMap(system, request.steps, request.map, request.cancel);
    picture.steps = map.map.step;
    Scene scene = drawnMap(map, request.map);
    const double deriveMs = millisecondsSince(start);
    picture.segments = scene.segments.size();
    picture.stats = {{"steps", picture.steps},
                     {"modules", map.map.cellCount()},
                     {"segments", scene.segments.size()},
                     {"polygons", scene.polygonCount()},
                     {"bbox", boundsJson(scene.bounds())},
                     {"is3D", false},
                     {"deriveMs", deriveMs},
                     {"drawMs", 0.0},
                     {"summarised", false}};
    picture.lines = encodeLines(scene);
    picture.mapScene = std::move(scene);
    return picture;
}

}  // namespace

StudioPicture derivePicture(const ModelInput& input, Model parsed, const StudioLimits& limits,
                            const CancellationToken& cancel, const fs::path& /*scratch*/) {
    StudioPicture picture;
    picture.model = std::move(parsed);
    picture.request = pipelineRequest(input, limits, cancel);
    const ExportRequest& request = picture.request;
    if (isMapLSystemText(input.text)) return deriveMapPicture(input, std::move(picture));
    const Model& model = picture.model;
    picture.steps = requestedSteps(model, request);
    const int steps = picture.steps;
    const auto start = Clock::now();

    std::vector<Diagnostic> notes;
    const bool pixelBound = streamedPictureIsSummarised(model, steps, request.memoryLimit);
    if (shouldStream(model, steps, request, true, true, pixelBound, notes)) {
        // Too large to hold: the streamed picture render() draws, as a PNG.
        ExportRequest png = request;
        png.format = "png";
        exportModel(model, Destination::memory(picture.summaryPng, "picture.png"), png);
        for (const Diagnostic& d : notes) picture.notes.push_back(d.message);
        picture.notes.push_back("the string is too large to draw here: a summarised picture");
        picture.stats = {
            {"steps", steps}, {"summarised", true}, {"deriveMs", millisecondsSince(start)}};
        return picture;
    }

    Derived derivedModel = derived(model, request);
    const double deriveMs = millisecondsSince(start);
    const ModuleString& modules = derivedModel.modules;
    for (std::size_t i = 0; i < modules.size() && i < limits.stringHeadModules; ++i)
        appendModuleText(picture.stringHead, model.lsystem.symbols, modules.symbol(i),
                         modules.params(i));
    ModuleString shown = shownString(model, derivedModel, request);

    // The turtle writes polylines into a workspace of an earlier request (no Scene of 88
    // bytes a segment, no fresh pages); a smoothed model is drawn as its scene.
    const auto drawStart = Clock::now();
    std::unique_ptr<PolylineScene> lines = takeWorkspace();
    drawnLines(model, shown, request, *lines);
    const double drawMs = millisecondsSince(drawStart);
    cancel.check();
    const Scene& rest = lines->rest;
    picture.segments = lines->segments;

    const std::size_t organs =
        rest.polygonCount() + rest.surfaces.size() + rest.discs.size() + rest.spheres.size();
    picture.stats = {{"steps", steps},
                     {"modules", derivedModel.moduleCount},
                     {"segments", lines->segments},
                     {"polygons", organs},
                     {"bbox", boundsJson(lines->bounds())},
                     {"is3D", rest.is3D},
                     {"deriveMs", deriveMs},
                     {"drawMs", drawMs},
                     {"summarised", false}};
    if (lines->segments > limits.segmentBudget) {
        // Over the budget the browser gets a picture, not the segments.
        const Scene scene = drawn(model, shown, request);
        RenderOptions render;
        if (model.view.camera.background) render.background = *model.view.camera.background;
        writeImage(scene.is3D ? projectScene(scene, ViewDirection::Front) : scene, render,
                   ImageFormat::Png, Destination::memory(picture.summaryPng, "picture.png"));
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
    picture.modules = std::move(shown);
    return picture;
}

Scene pictureScene(const StudioPicture& picture) {
    if (picture.mapScene) return *picture.mapScene;
    return drawn(picture.model, picture.modules, picture.request);
}

std::string meshGlb(const StudioPicture& picture, const fs::path& /*scratch*/) {
    const MeshSetup setup = meshSetup(picture.model, picture.request, MeshPurpose::Viewer);
    std::vector<Diagnostic> notes;
    const MeshScene mesh = meshed(picture.model, pictureScene(picture), setup, notes);
    // Repeated organs (leaves, flowers) once each, placed by EXT_mesh_gpu_instancing, the
    // buffers compressed by EXT_meshopt_compression: the page's loader reads both.
    std::string glb;
    writeGlb(mesh, Destination::memory(glb, "view.glb"),
             GlbOptions{.instancing = true, .compression = true});
    return glb;
}

const std::vector<const ExportFormat*>& studioExportFormats() {
    // The derived string as text is left out: the page shows the string itself, and a
    // download of all of it may be far larger than the studio's limits.
    static const std::vector<const ExportFormat*> formats = [] {
        std::vector<const ExportFormat*> rows;
        for (const ExportFormat& f : graftal::exportFormats())
            if (!f.fileOnly && f.kind != ExportKind::String) rows.push_back(&f);
        return rows;
    }();
    return formats;
}

ExportedFile exportFile(const ModelInput& input, const std::string& format,
                        const StudioLimits& limits, const CancellationToken& cancel,
                        const fs::path& /*scratch*/) {
    const auto& formats = studioExportFormats();
    const auto found = std::find_if(formats.begin(), formats.end(),
                                    [&](const ExportFormat* f) { return f->name == format; });
    if (found == formats.end())
        throw Error(SourceLocation{"studio", 0, 0}, "unknown export format '" + format + "'");
    const Model model = parseOrThrow(input);
    const std::string stem = input.file.stem().string();
    const ExportFormat* entry = *found;
    ExportRequest request = pipelineRequest(input, limits, cancel);
    request.format = format;
    // An animation is every step from 0 to the slider's, one fixed camera.
    const std::string name = stem + std::string(entry->extension);
    ExportedFile file{name, {}};
    const Destination memory = Destination::memory(file.bytes, name);
    if (isMapLSystemText(input.text)) {
        ParseOptions options;
        options.fileName = input.file.string();
        options.defines = input.defines;
        exportMap(parseMapLSystem(input.text, options).orThrow(), memory, request);
        return file;
    }
    const ExportResult result = exportModel(model, memory, request);
    if (format != "obj") return file;
    // The OBJ names its materials by file name: both go in one archive, named after the
    // model, so that they unpack side by side.
    return {stem + "-obj.zip",
            storedZip({{stem + ".obj", file.bytes}, {stem + ".mtl", result.materials}})};
}

std::string thumbnailPng(const fs::path& file, const fs::path& viewFile, int size,
                         const StudioLimits& limits, const fs::path& /*scratch*/) {
    ParseOptions options;
    options.viewFile = viewFile.string();
    ParseResult parsed = loadModel(file, options);
    if (!parsed.ok()) throw Error(parsed.errors());
    ExportRequest request = pipelineRequest(ModelInput{{}, file, std::nullopt, {}, {}, {}}, limits,
                                            CancellationToken{});
    request.format = "png";
    request.picture.width = request.picture.height = size;
    request.samplesPerPixel = 1;
    std::string png;
    exportModel(parsed.model, Destination::memory(png, "thumbnail.png"), request);
    return png;
}

}  // namespace graftal::studio
