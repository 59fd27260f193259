// The WebAssembly engine's entry points (docs/web.md): a front end like the command and the
// studio's server. Each call turns JavaScript's arguments into a pipeline request, calls the
// pipeline's stages, the export registry or the studio's computations, and hands back what
// they made as JSON and typed arrays. Errors come back as {error, diagnostics} objects,
// which the package's JavaScript throws as exceptions; nothing here assembles work.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "graftal/core/destination.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/studio/studio_model.hpp"

namespace graftal::web {

namespace {

using emscripten::val;
using nlohmann::json;

// A tab's memory is bounded: a derivation's strings stay well below the 2 GB the module may
// grow to, and over this it ends with the library's message.
constexpr std::size_t kMemoryLimit = std::size_t(512) << 20;
constexpr int kMaxSteps = 10'000;

// The page's or the caller's model: its text, a name for messages, steps and -D values.
studio::ModelInput modelInput(const std::string& text, const json& options) {
    studio::ModelInput input;
    input.text = text;
    input.file = options.value("fileName", std::string("model.l"));
    if (options.contains("steps") && options["steps"].is_number())
        input.steps = options["steps"].get<int>();
    if (options.contains("defines") && options["defines"].is_object())
        for (const auto& [name, value] : options["defines"].items())
            input.defines[name] = value.is_string() ? value.get<std::string>() : value.dump();
    return input;
}

studio::StudioLimits limits(const json& options) {
    studio::StudioLimits l;
    l.memoryLimit = options.value("memoryLimit", kMemoryLimit);
    l.maxSteps = options.value("maxSteps", kMaxSteps);
    l.deriveSeconds = options.value("seconds", 60.0);
    return l;
}

json parseOptions(const std::string& text) {
    if (text.empty()) return json::object();
    json options = json::parse(text, nullptr, false);
    return options.is_object() ? options : json::object();
}

Model parsedModel(const studio::ModelInput& input) {
    ParseResult result = studio::parseInput(input);
    if (!result.ok()) throw Error(result.errors());
    return std::move(result.model);
}

ExportRequest pipelineRequest(const studio::ModelInput& input, const json& options) {
    const studio::StudioLimits l = limits(options);
    ExportRequest request;
    request.steps = input.steps;
    request.maxSteps = l.maxSteps;
    request.memoryLimit = l.memoryLimit;
    request.threads = 1;
    request.sourceFile = input.file;
    return request;
}

// A typed array of `T` holding a copy of `data` (the module's memory may move later).
template <class T>
val typedArray(const T* data, std::size_t count) {
    return val(emscripten::typed_memory_view(count, data)).call<val>("slice");
}

val bytesArray(const std::string& bytes) {
    return typedArray(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
}

val failure(const std::vector<Diagnostic>& diagnostics, const std::string& message) {
    val out = val::object();
    out.set("error", message);
    out.set("diagnostics", studio::diagnosticsJson(diagnostics).dump());
    return out;
}

// Runs `work`, turning the library's errors (and an exhausted memory) into a failure.
template <class Work>
val guarded(Work&& work) {
    try {
        return work();
    } catch (const Cancelled& e) {
        val out = failure(e.diagnostics(), e.messages());
        out.set("cancelled", true);
        return out;
    } catch (const Error& e) {
        return failure(e.diagnostics(), e.messages());
    } catch (const std::bad_alloc&) {
        return failure({}, "out of memory: the derivation needs more than the page may use");
    } catch (const std::exception& e) {
        return failure({}, e.what());
    }
}

// ---- the npm package's calls -----------------------------------------------------------

// {ok, diagnostics, defines, derivationLength, name}, as the studio reports a parse.
std::string parse(const std::string& text, const std::string& optionsText) {
    return studio::parseReport(modelInput(text, parseOptions(optionsText))).dump();
}

// A derivation the package's JavaScript holds (its Derivation object): the string stays in
// the module's memory, and its text, symbols and parameters are handed over only when asked
// for, since turning 10^8 modules into a JavaScript string or a copy costs more than the
// derivation itself. Released by the object's release() or when JavaScript collects it.
struct KeptDerivation {
    std::shared_ptr<const Model> model;
    ModuleString modules;
    std::string text;  // the text while JavaScript decodes it
};
std::unordered_map<int, KeptDerivation> gDerivations;
int gNextDerivation = 0;

KeptDerivation& kept(int handle) {
    auto it = gDerivations.find(handle);
    if (it == gDerivations.end())
        throw Error(SourceLocation{"derive", 0, 0}, "the derivation was released");
    return it->second;
}

// {handle, steps, moduleCount, symbolNames, notes}: the derivation stays in the module.
val derive(const std::string& text, const std::string& optionsText) {
    return guarded([&] {
        const json options = parseOptions(optionsText);
        const studio::ModelInput input = modelInput(text, options);
        auto model = std::make_shared<const Model>(parsedModel(input));
        const ExportRequest request = pipelineRequest(input, options);
        Derived d = derived(*model, request);
        const SymbolTable& symbols = model->lsystem.symbols;
        val out = val::object();
        out.set("steps", d.steps);
        out.set("moduleCount", static_cast<double>(d.modules.size()));
        json notes = json::array();
        for (const Diagnostic& n : d.notes) notes.push_back(n.message);
        out.set("notes", notes.dump());
        json names = json::array();
        for (std::size_t s = 0; s < symbols.size(); ++s) names.push_back(symbols.name(Symbol(s)));
        out.set("symbolNames", names.dump());
        const int handle = ++gNextDerivation;
        gDerivations.emplace(handle, KeptDerivation{std::move(model), std::move(d.modules), {}});
        out.set("handle", handle);
        return out;
    });
}

void release(int handle) { gDerivations.erase(handle); }

// {name: count} of the symbols the string holds.
std::string derivationCounts(int handle) {
    const KeptDerivation& k = kept(handle);
    const SymbolTable& symbols = k.model->lsystem.symbols;
    const std::vector<std::uint64_t> counts = countSymbols(k.modules, symbols.size(), 1);
    json countsJson = json::object();
    for (std::size_t s = 0; s < counts.size(); ++s)
        if (counts[s] > 0) countsJson[symbols.name(Symbol(s))] = counts[s];
    return countsJson.dump();
}

// The text of the first `limit` modules as bytes in the module's memory, for JavaScript to
// decode at once (the view is valid until the module's memory grows). A string without
// parameters whose symbols all print as their own one character is its text already.
val derivationText(int handle, double limit) {
    KeptDerivation& k = kept(handle);
    const ModuleString& m = k.modules;
    const SymbolTable& symbols = k.model->lsystem.symbols;
    const std::size_t count = std::min(m.size(), static_cast<std::size_t>(std::max(0.0, limit)));
    // Ids from 128 are multi-letter names; below, a name is its character.
    Symbol highest = 0;
    for (std::size_t i = 0; i < count; ++i) highest |= m.symbol(i);
    bool plain = !m.hasParameters() && highest < kFirstNamedSymbol;
    for (std::size_t s = 0; plain && s < kFirstNamedSymbol && s < symbols.size(); ++s) {
        const std::string& name = symbols.name(Symbol(s));
        plain = name.size() == 1 && name[0] == static_cast<char>(s);
    }
    if (plain) return val(emscripten::typed_memory_view(count, m.symbols().data()));
    k.text.clear();
    for (std::size_t i = 0; i < count; ++i)
        appendModuleText(k.text, symbols, m.symbol(i), m.params(i));
    return val(emscripten::typed_memory_view(k.text.size(),
                                             reinterpret_cast<const unsigned char*>(k.text.data())));
}

// Frees the text derivationText() made, once JavaScript has decoded it.
void releaseText(int handle) { std::string().swap(kept(handle).text); }

// One symbol id a module (copied into a Uint8Array).
val derivationSymbols(int handle) {
    const ModuleString& m = kept(handle).modules;
    return typedArray(m.symbols().data(), m.size());
}

// {offsets, parameters} (Uint32Array, Float64Array), or {} when no module has parameters.
val derivationParameters(int handle) {
    const ModuleString& m = kept(handle).modules;
    val out = val::object();
    if (!m.hasParameters()) return out;
    const auto& starts = m.paramStarts();
    out.set("offsets", typedArray(starts.data(), m.size() + 1));
    std::vector<double> params(m.paramCount());
    for (std::size_t i = 0; i < m.size(); ++i) {
        const ParamView p = m.params(i);
        for (std::size_t k = 0; k < p.size(); ++k) params[starts[i] + k] = p[k];
    }
    out.set("parameters", typedArray(params.data(), params.size()));
    return out;
}

// The turtle's drawing: segments (x0 y0 z0 x1 y1 z1), their widths and colours, polygons
// as triangles (9 floats each) with their colours, the palette and the bounds.
val interpret(const std::string& text, const std::string& optionsText) {
    return guarded([&] {
        const json options = parseOptions(optionsText);
        const studio::ModelInput input = modelInput(text, options);
        const Model model = parsedModel(input);
        const ExportRequest request = pipelineRequest(input, options);
        Derived d = derived(model, request);
        const Scene scene = drawn(model, shownString(model, d, request), request);
        std::vector<float> segments, widths;
        std::vector<std::uint16_t> colors;
        segments.reserve(6 * scene.segments.size());
        for (const Segment& s : scene.segments) {
            segments.insert(segments.end(), {float(s.a.x), float(s.a.y), float(s.a.z),
                                             float(s.b.x), float(s.b.y), float(s.b.z)});
            widths.push_back(s.width);
            colors.push_back(s.color);
        }
        std::vector<float> triangles;
        std::vector<std::uint16_t> triangleColors;
        for (std::size_t p = 0; p + 1 < scene.polygonStart.size(); ++p) {
            const std::vector<Vec3> outline(
                scene.polygonVertices.begin() + scene.polygonStart[p],
                scene.polygonVertices.begin() + scene.polygonStart[p + 1]);
            const std::vector<std::uint32_t> corners = triangulatePolygon(outline);
            for (std::uint32_t c : corners)
                triangles.insert(triangles.end(),
                                 {float(outline[c].x), float(outline[c].y), float(outline[c].z)});
            for (std::size_t t = 0; t < corners.size() / 3; ++t)
                triangleColors.push_back(p < scene.polygonColor.size() ? scene.polygonColor[p] : 0);
        }
        json palette = json::array();
        for (const Rgb& c : scene.palette) palette.push_back({c.r, c.g, c.b});
        const Bounds b = scene.bounds();
        val out = val::object();
        out.set("steps", d.steps);
        out.set("is3D", scene.is3D);
        out.set("segments", typedArray(segments.data(), segments.size()));
        out.set("widths", typedArray(widths.data(), widths.size()));
        out.set("colors", typedArray(colors.data(), colors.size()));
        out.set("triangles", typedArray(triangles.data(), triangles.size()));
        out.set("triangleColors", typedArray(triangleColors.data(), triangleColors.size()));
        out.set("palette", palette.dump());
        out.set("bounds", b.empty() ? std::string("null")
                                    : json{{"min", {b.min.x, b.min.y, b.min.z}},
                                           {"max", {b.max.x, b.max.y, b.max.z}}}
                                          .dump());
        return out;
    });
}

// A file of the export registry (svg, obj, glb, ...) written in memory: {bytes, materials}.
val exportAs(const std::string& text, const std::string& optionsText, const std::string& format) {
    return guarded([&] {
        const json options = parseOptions(optionsText);
        const studio::ModelInput input = modelInput(text, options);
        const Model model = parsedModel(input);
        ExportRequest request = pipelineRequest(input, options);
        request.format = format;
        if (options.contains("width")) request.picture.width = options["width"].get<int>();
        if (options.contains("height")) request.picture.height = options["height"].get<int>();
        std::string bytes;
        const ExportResult result =
            exportModel(model, Destination::memory(bytes, "model." + format), request);
        val out = val::object();
        out.set("bytes", bytesArray(bytes));
        out.set("materials", result.materials);
        return out;
    });
}

// ---- the studio page's calls (the server's /api/derive, /api/mesh, /api/export) --------

studio::ModelInput studioInput(const json& body) {
    json options = json::object();
    options["fileName"] = body.value("path", std::string("untitled.l"));
    if (body.contains("steps")) options["steps"] = body["steps"];
    if (body.contains("defines")) options["defines"] = body["defines"];
    return modelInput(body.value("text", std::string()), options);
}

// The page keeps one picture: the last one, reused by the mesh of the 3D view.
std::string gKeptKey;
std::shared_ptr<const studio::StudioPicture> gKept;

double epochMilliseconds() {
    using namespace std::chrono;
    return duration<double, std::milli>(system_clock::now().time_since_epoch()).count();
}

// The same answer as the server's /api/derive: a 4-byte JSON length, the JSON, padding
// to 4 bytes, the line buffer; {error, diagnostics, report} when the model has errors.
val studioDerive(const std::string& bodyText) {
    return guarded([&]() -> val {
        const double receivedAt = epochMilliseconds();
        const json body = parseOptions(bodyText);
        const studio::ModelInput input = studioInput(body);
        const std::string key = studio::pictureKey(input);
        const std::string tag = studio::pictureTag(key);
        ParseResult parsed = studio::parseInput(input);
        const json report = studio::parseReport(input, parsed);
        if (!parsed.ok()) {
            val out = failure(parsed.errors(), Error(parsed.errors()).messages());
            out.set("report", report.dump());
            return out;
        }
        const bool reused = gKept && gKeptKey == key;
        const bool unchanged = reused && body.value("have", "") == tag;
        studio::StudioLimits l = limits(json::object());
        l.memoryLimit = kMemoryLimit;
        if (!reused) {
            try {
                gKept = std::make_shared<studio::StudioPicture>(studio::derivePicture(
                    input, std::move(parsed.model), l, CancellationToken{}, {}));
                gKeptKey = key;
            } catch (const Error& e) {
                val out = failure(e.diagnostics(), e.messages());
                out.set("report", report.dump());
                return out;
            }
        }
        const studio::StudioPicture& picture = *gKept;
        const bool summarised = !picture.summaryPng.empty();
        json stats = picture.stats;
        stats["reused"] = reused;
        stats["serverMs"] = epochMilliseconds() - receivedAt;
        stats["receivedAt"] = receivedAt;
        stats["answeredAt"] = epochMilliseconds();
        const json meta = {{"stats", stats},
                           {"report", report},
                           {"steps", picture.steps},
                           {"tag", tag},
                           {"unchanged", unchanged},
                           {"string", unchanged ? std::string() : picture.stringHead},
                           {"notes", picture.notes},
                           {"geometry", unchanged ? "none" : summarised ? "png" : "lines"},
                           {"meshAvailable", !summarised && picture.segments <= l.meshSegmentBudget}};
        std::string out(4, '\0');
        const std::string metaText = meta.dump();
        const auto length = static_cast<std::uint32_t>(metaText.size());
        std::memcpy(out.data(), &length, 4);
        out += metaText;
        out.append((4 - out.size() % 4) % 4, ' ');
        if (!unchanged) out += summarised ? picture.summaryPng : picture.lines;
        val answer = val::object();
        answer.set("bytes", bytesArray(out));
        return answer;
    });
}

// The 3D view's glTF of the picture the last derive made (derived again if it was another).
val studioMesh(const std::string& bodyText) {
    return guarded([&]() -> val {
        const json body = parseOptions(bodyText);
        const studio::ModelInput input = studioInput(body);
        const std::string key = studio::pictureKey(input);
        studio::StudioLimits l = limits(json::object());
        l.memoryLimit = kMemoryLimit;
        if (!gKept || gKeptKey != key) {
            gKept = std::make_shared<studio::StudioPicture>(
                studio::derivePicture(input, l, CancellationToken{}, {}));
            gKeptKey = key;
        }
        if (!gKept->summaryPng.empty() || gKept->segments > l.meshSegmentBudget)
            throw Error(SourceLocation{"studio", 0, 0},
                        "over the mesh budget of " + std::to_string(l.meshSegmentBudget) +
                            " segments: the 3D view draws lines");
        val answer = val::object();
        answer.set("bytes", bytesArray(studio::meshGlb(*gKept, {})));
        return answer;
    });
}

// A download through the studio's exportFile (an OBJ comes as a .zip with its .mtl).
val studioExport(const std::string& bodyText) {
    return guarded([&]() -> val {
        const json body = parseOptions(bodyText);
        studio::StudioLimits l = limits(json::object());
        l.memoryLimit = kMemoryLimit;
        const studio::ExportedFile file = studio::exportFile(
            studioInput(body), body.value("format", std::string()), l, CancellationToken{}, {});
        val answer = val::object();
        answer.set("name", file.fileName);
        answer.set("bytes", bytesArray(file.bytes));
        return answer;
    });
}

}  // namespace

EMSCRIPTEN_BINDINGS(graftal_engine) {
    emscripten::function("parse", &parse);
    emscripten::function("derive", &derive);
    emscripten::function("release", &release);
    emscripten::function("derivationCounts", &derivationCounts);
    emscripten::function("derivationText", &derivationText);
    emscripten::function("releaseText", &releaseText);
    emscripten::function("derivationSymbols", &derivationSymbols);
    emscripten::function("derivationParameters", &derivationParameters);
    emscripten::function("interpret", &interpret);
    emscripten::function("exportAs", &exportAs);
    emscripten::function("studioDerive", &studioDerive);
    emscripten::function("studioMesh", &studioMesh);
    emscripten::function("studioExport", &studioExport);
}

}  // namespace graftal::web
