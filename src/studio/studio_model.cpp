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
#include <sstream>

#include "graftal/animation.hpp"
#include "graftal/bspline.hpp"
#include "graftal/color_map.hpp"
#include "graftal/mesh.hpp"
#include "graftal/mesh_scene.hpp"
#include "graftal/music.hpp"
#include "graftal/output.hpp"
#include "graftal/parser_target.hpp"
#include "graftal/pipeline.hpp"
#include "graftal/projection.hpp"
#include "graftal/streamed_picture.hpp"
#include "graftal/surface.hpp"
#include "graftal/turtle.hpp"
#include "graftal/view_file.hpp"
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
    for (const auto& decl : view.surfaces) {
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

template <typename T>
void appendRaw(std::string& out, const T* data, std::size_t count) {
    out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

// R, G, B, A bytes in memory order (a little-endian uint32).
std::uint32_t rgbaBytes(const Rgb& c) {
    auto byte = [](double v) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
    };
    return byte(c.r) | byte(c.g) << 8 | byte(c.b) << 16 | 0xFF000000u;
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
    ParseResult result = parse(input.text, options);
    if (input.viewFile.empty()) return result;
    DiagnosticList diagnostics;
    ModelBuilder builder(diagnostics);
    builder.model() = std::move(result.model);
    parseViewFileInto(input.viewText, input.viewFile.string(), builder, diagnostics);
    result.model = std::move(builder.model());
    for (const Diagnostic& d : diagnostics.items()) result.diagnostics.push_back(d);
    return result;
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
    const ParseResult result = parseInput(input);
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
    StudioPicture picture;
    picture.model = parseOrThrow(input);
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

    const auto drawStart = Clock::now();
    Scene scene = model.lsystem.homomorphism.empty()
                      ? interpret(model, modules)
                      : interpret(model, applyHomomorphism(model.lsystem, modules, options));
    modules = ModuleString{};
    cancel.check();
    if (int n = model.view.splineSubdivisions; n > 0) scene = smoothSegments(scene, n);
    if (!model.view.colorMap.empty())
        scene.palette = loadColorMap(input.file.parent_path() / model.view.colorMap);
    const double drawMs = millisecondsSince(drawStart);

    const std::size_t organs =
        scene.polygonCount() + scene.surfaces.size() + scene.discs.size() + scene.spheres.size();
    picture.stats = {{"steps", steps},
                     {"modules", moduleCount},
                     {"segments", scene.segments.size()},
                     {"polygons", organs},
                     {"bbox", boundsJson(scene.bounds())},
                     {"is3D", scene.is3D},
                     {"deriveMs", deriveMs},
                     {"drawMs", drawMs},
                     {"summarised", false}};
    if (scene.segments.size() > limits.segmentBudget) {
        // Over the budget the browser gets a picture, not the segments.
        RenderOptions render;
        if (model.view.background) render.background = *model.view.background;
        const fs::path png = scratchFile(scratch, "png");
        writeImage(scene.is3D ? projectScene(scene, ViewDirection::Front) : scene, render, png);
        picture.summaryPng = readAndRemove(png);
        picture.notes.push_back(std::to_string(scene.segments.size()) +
                                " segments are over the studio's budget of " +
                                std::to_string(limits.segmentBudget) + ": a summarised picture");
        picture.stats["summarised"] = true;
        scene = Scene{};
    }
    picture.scene = std::move(scene);
    return picture;
}

std::string encodeLines(const Scene& scene) {
    // The segments as polylines: each point once, as 16-bit fractions of the bounding box
    // (a 65536th of the picture is far below a pixel until zoomed 80 times), and runs of
    // links sharing a width and a colour. A turtle's path is mostly joined, so a flat
    // segment costs 4 bytes and a few per run instead of two end points each; bytes are
    // what it costs to move a picture into the page.
    const std::size_t n = scene.segments.size();
    const std::size_t dims = scene.is3D ? 3 : 2;
    const Bounds b = scene.bounds();
    const bool empty = b.empty();
    const Vec3 origin = empty ? Vec3{} : b.min;
    const Vec3 size = empty ? Vec3{} : b.max - b.min;
    auto quantizer = [](double extent) { return extent > 0 ? 65535.0 / extent : 0.0; };
    const double qx = quantizer(size.x), qy = quantizer(size.y), qz = quantizer(size.z);
    auto q = [](double v, double scale) {
        return static_cast<std::uint16_t>(std::clamp(std::lround(v * scale), 0L, 65535L));
    };
    float maxWidth = 0;
    for (const Segment& s : scene.segments) maxWidth = std::max(maxWidth, s.width);
    const double widthScale = maxWidth > 0 ? 65535.0 / maxWidth : 0.0;
    const std::size_t paletteSize = std::clamp<std::size_t>(scene.palette.size(), 1, 65535);

    struct Run {
        std::uint32_t links;
        std::uint16_t width, color;  // color kJump: the pen moves, nothing is drawn
    };
    constexpr std::uint16_t kJump = 0xFFFF;
    std::vector<std::uint16_t> points;
    points.reserve(dims * (n + n / 8 + 1));
    std::vector<Run> runs;
    auto link = [&](std::uint16_t width, std::uint16_t color) {
        if (!runs.empty() && runs.back().width == width && runs.back().color == color)
            ++runs.back().links;
        else
            runs.push_back({1, width, color});
    };
    std::uint16_t last[3] = {0, 0, 0};
    double ink = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Segment& s = scene.segments[i];
        const Vec3 a = s.a - origin, e = s.b - origin;
        const std::uint16_t from[3] = {q(a.x, qx), q(a.y, qy), q(a.z, qz)};
        const std::uint16_t to[3] = {q(e.x, qx), q(e.y, qy), q(e.z, qz)};
        if (points.empty() || !std::equal(from, from + dims, last)) {
            if (!points.empty()) link(0, kJump);
            points.insert(points.end(), from, from + dims);
        }
        link(q(s.width, widthScale), static_cast<std::uint16_t>(s.color % paletteSize));
        points.insert(points.end(), to, to + dims);
        std::copy(to, to + 3, last);
        ink += inkLength(s, scene.baseWidth);
    }

    std::vector<std::uint32_t> palette;
    for (std::size_t k = 0; k < paletteSize; ++k)
        palette.push_back(rgbaBytes(scene.colorOf(static_cast<std::uint16_t>(k))));

    std::vector<float> triangles;
    std::vector<std::uint32_t> triangleColors;
    auto addOutline = [&](const std::vector<Vec3>& outline, const Rgb& color) {
        const std::vector<std::uint32_t> index = triangulatePolygon(outline);
        for (std::size_t i = 0; i + 2 < index.size(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = outline[index[i + k]];
                triangles.insert(triangles.end(), {float(p.x), float(p.y), float(p.z)});
            }
            triangleColors.push_back(rgbaBytes(color));
        }
    };
    for (std::size_t k = 0; k < scene.polygonCount(); ++k) {
        const auto poly = scene.polygon(k);
        addOutline(std::vector<Vec3>(poly.begin(), poly.end()),
                   scene.colorOf(scene.polygonColor[k]));
    }
    for (const Disc& d : scene.discs) addOutline(discOutline(d, 24), scene.colorOf(d.color));
    for (const Sphere& s : scene.spheres)
        addOutline(discOutline(Disc{s.centre, {0, 0, 1}, s.radius, s.color}, 24),
                   scene.colorOf(s.color));

    const std::uint32_t header[6] = {0x334C4647u,
                                     static_cast<std::uint32_t>(n),
                                     static_cast<std::uint32_t>(triangleColors.size()),
                                     scene.is3D ? 1u : 0u,
                                     static_cast<std::uint32_t>(points.size() / dims),
                                     static_cast<std::uint32_t>(runs.size())};
    const float lineWidth = float(defaultLineWidth(ink, n > 0, b, RenderOptions{}));
    const float extent[9] = {float(origin.x),
                             float(origin.y),
                             float(origin.z),
                             float(origin.x + size.x),
                             float(origin.y + size.y),
                             float(origin.z + size.z),
                             lineWidth,
                             scene.baseWidth,
                             maxWidth};
    const std::uint32_t paletteCount = static_cast<std::uint32_t>(palette.size());
    std::string out;
    out.reserve(64 + 4 * palette.size() + 2 * points.size() + 4 + 8 * runs.size() +
                4 * (triangles.size() + triangleColors.size()));
    appendRaw(out, header, 6);
    appendRaw(out, extent, 9);
    appendRaw(out, &paletteCount, 1);
    appendRaw(out, palette.data(), palette.size());
    appendRaw(out, points.data(), points.size());
    out.append((4 - out.size() % 4) % 4, '\0');
    for (const Run& r : runs) {
        appendRaw(out, &r.links, 1);
        appendRaw(out, &r.width, 1);
        appendRaw(out, &r.color, 1);
    }
    appendRaw(out, triangles.data(), triangles.size());
    appendRaw(out, triangleColors.data(), triangleColors.size());
    return out;
}

std::string meshGlb(const StudioPicture& picture, const fs::path& scratch) {
    Scene scene = picture.scene;
    if (picture.model.view.colorMap.empty()) scene.palette = defaultPalette3D();
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
