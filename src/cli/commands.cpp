#include "commands.hpp"

#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/pipeline/statistics.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/rewrite/growth.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"
#include "graftal/turtle/turtle.hpp"
#include "progress_line.hpp"
#include "standard_streams.hpp"

namespace graftal::cli {

namespace {

Error usageError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

void printWarnings(const ParseResult& parsed) {
    for (const auto& w : parsed.warnings()) std::cerr << w.toString() << '\n';
}

nlohmann::ordered_json point(const Vec3& p) {
    return {p.x, p.y, p.z};
}

// The "bbox" of stats, in cpfg's convention: a dimension thinner than 1e-5 (a flat or
// straight plant) gets max = min + 1e-5, as cpfg's box line has it. An empty box is the
// turtle's start.
nlohmann::ordered_json bboxJson(Bounds b) {
    if (b.empty()) b.extend(Vec3{});
    constexpr double kThinnest = 1e-5;
    for (auto axis : {&Vec3::x, &Vec3::y, &Vec3::z})
        if (b.max.*axis - b.min.*axis < kThinnest) b.max.*axis = b.min.*axis + kThinnest;
    return {{"min", point(b.min)}, {"max", point(b.max)}};
}

}  // namespace

namespace {
// The progress line of this run (on a terminal only).
ProgressLine progressLine;
}  // namespace

void endProgressLine() {
    progressLine.end();
}

std::string remedyAsFlag(Remedy r) {
    switch (r) {
        case Remedy::LowerSteps:
            return "lower -n";
        case Remedy::RaiseMemoryLimit:
            return "raise --memory-limit";
        case Remedy::Stream:
            return "use --stream";
        case Remedy::RaiseStreamLimit:
            return "raise --stream-limit";
    }
    return {};
}

std::string settingAsFlag(const std::string& field) {
    static const std::map<std::string, std::string> flags = {{"viewpoint", "--viewpoint"},
                                                             {"target", "--target"},
                                                             {"up", "--up"},
                                                             {"light", "--light"},
                                                             {"fieldOfView", "--fov"},
                                                             {"samplesPerPixel", "--spp"},
                                                             {"tubeSides", "--tube-sides"},
                                                             {"glbInstancing", "--no-instancing"},
                                                             {"glbCompression", "--compress"},
                                                             {"surfaceDivisions", "--quality"},
                                                             {"ground", "--ground"},
                                                             {"lineWidth", "--line-width"},
                                                             {"lineColor", "--color"},
                                                             {"margin", "--margin"},
                                                             {"steps", "-n"},
                                                             {"memoryLimit", "--memory-limit"},
                                                             {"streamLimit", "--stream-limit"},
                                                             {"view", "--view"},
                                                             {"derivationDiagram", "--derivation"}};
    auto it = flags.find(field);
    return it == flags.end() ? field : it->second;
}

std::string describe(const Diagnostic& d) {
    return d.toString(remedyAsFlag, settingAsFlag);
}

void note(const InputOptions& in, const std::string& message) {
    if (!in.quiet) std::cerr << "graftal: note: " << message << '\n';
}

std::string fileName(const InputOptions& in) {
    return in.file == "-" ? std::string(kStdinName) : in.file;
}

bool showsProgress(const InputOptions& in) {
    return !in.quiet && ::isatty(2);
}

Loaded loadInput(const InputOptions& in) {
    ParseOptions po;
    po.defines = in.defines;
    po.viewFile = in.viewFile;
    std::optional<ScratchFile> input;
    std::filesystem::path path = in.file;
    if (in.file == "-") {
        // Standard input, kept in a scratch file; its diagnostics name <stdin>.
        input.emplace("stdin.l");
        saveStandardInput(*input);
        path = input->path();
        po.fileName = kStdinName;
    }
    ParseResult parsed = loadModel(path, po);
    if (!parsed.ok()) throw Error(parsed.errors());
    if (!in.quiet) printWarnings(parsed);
    Loaded l{std::move(parsed.model), 0};
    // The library checks the count (its message names the field, worded here as -n).
    DeriveRequest steps;
    steps.steps = in.steps;
    l.steps = requestedSteps(l.model, steps);
    // Percent done needs the work ahead: the predicted size of every step's string.
    if (showsProgress(in))
        progressLine.expect(predictGrowth(l.model.lsystem, l.steps).expectedModules);
    return l;
}

DeriveRequest deriveRequest(const InputOptions& in) {
    DeriveRequest r;
    r.steps = in.steps;
    r.seed = in.seed;
    r.random = in.random;
    r.threads = in.threads;
    r.memoryLimit = in.memoryLimit;
    r.stream = in.stream ? StreamPolicy::Always : StreamPolicy::Auto;
    r.streamLimit = in.streamLimit;
    r.precision = in.precision;
    // printf in a model writes to standard error, as cpfg's does (standard output may
    // carry the derived string).
    r.print = [](std::string_view text) {
        endProgressLine();
        std::cerr << text << std::flush;
    };
    // Progress for long derivations, only where a person watches (a terminal), and only
    // once a derivation has taken more than a second.
    if (showsProgress(in))
        r.progress = [](int step, std::size_t modules) { progressLine.report(step, modules); };
    r.notify = [&in](const Diagnostic& d) {
        endProgressLine();
        // Notes and warnings about the run, not about a place in the file: "graftal: note:";
        // those about a line of the file keep it.
        Diagnostic run = d;
        if (run.location.line <= 0) run.location = SourceLocation{"graftal", 0, 0};
        if (!in.quiet) std::cerr << describe(run) << '\n';
    };
    return r;
}

DerivationOptions derivationOptions(const InputOptions& in, const Model& model) {
    return graftal::derivationOptions(model, deriveRequest(in));
}

bool chooseStreaming(const Loaded& l, const InputOptions& in, bool canStream, bool countGeometry,
                     bool pixelBound) {
    std::vector<Diagnostic> notes;
    return shouldStream(l.model, l.steps, deriveRequest(in), canStream, countGeometry, pixelBound,
                        notes);
}

Derived deriveLoaded(Loaded loaded, const InputOptions& in) {
    DeriveRequest request = deriveRequest(in);
    request.steps = loaded.steps;
    graftal::Derived derived = graftal::derived(loaded.model, request);
    endProgressLine();
    return Derived{std::move(loaded.model), std::move(derived.modules), derived.steps};
}

Vec3 parseVector(const std::string& option, const std::string& text) {
    double v[3];
    const char* p = text.c_str();
    for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        v[k] = std::strtod(p, &end);
        if (end == p || !std::isfinite(v[k]))
            throw usageError(option + " '" + text + "': expected three numbers x,y,z");
        p = end;
        if (k < 2) {
            if (*p != ',')
                throw usageError(option + " '" + text + "': expected three numbers x,y,z");
            ++p;
        }
    }
    if (*p) throw usageError(option + " '" + text + "': expected three numbers x,y,z");
    return {v[0], v[1], v[2]};
}

std::size_t parseByteSize(const std::string& text) {
    double value = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), value);
    if (r.ec != std::errc() || value < 0)
        throw usageError("'" + text + "' is not a size (expected e.g. 2G, 512M, 1000000)");
    std::string unit(r.ptr, text.data() + text.size());
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (!unit.empty() && unit.back() == 'B') unit.pop_back();
    if (!unit.empty() && unit.back() == 'I') unit.pop_back();
    double k = 1;
    if (unit == "K")
        k = 1024.0;
    else if (unit == "M")
        k = 1024.0 * 1024;
    else if (unit == "G")
        k = 1024.0 * 1024 * 1024;
    else if (unit == "T")
        k = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty())
        throw usageError("'" + text + "': unknown size unit (use K, M, G or T)");
    return static_cast<std::size_t>(value * k);
}

void parseImageSize(const std::string& text, int& width, int& height) {
    auto x = text.find_first_of("xX");
    int w = 0, h = 0;
    bool ok = x != std::string::npos;
    if (ok) {
        auto r1 = std::from_chars(text.data(), text.data() + x, w);
        auto r2 = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
        ok = r1.ec == std::errc() && r1.ptr == text.data() + x && r2.ec == std::errc() &&
             r2.ptr == text.data() + text.size();
    }
    if (!ok || w < 1 || h < 1 || w > 32767 || h > 32767)
        throw usageError("--size '" + text +
                         "': expected WIDTHxHEIGHT in pixels, e.g. 800x600 "
                         "(each from 1 to 32767)");
    width = w;
    height = h;
}

Rgb parseColor(const std::string& text) {
    static const std::map<std::string, Rgb> named = {
        {"black", {0, 0, 0}},           {"white", {1, 1, 1}},         {"red", {0.8f, 0.1f, 0.1f}},
        {"green", {0.1f, 0.5f, 0.15f}}, {"blue", {0.1f, 0.2f, 0.7f}}, {"none", {1, 1, 1}},
    };
    if (auto it = named.find(text); it != named.end()) return it->second;
    std::string hex = text[0] == '#' ? text.substr(1) : text;
    unsigned v = 0;
    auto r = std::from_chars(hex.data(), hex.data() + hex.size(), v, 16);
    if (hex.size() != 6 || r.ec != std::errc() || r.ptr != hex.data() + hex.size())
        throw usageError("'" + text +
                         "' is not a colour (expected #rrggbb or a name such as black)");
    return {((v >> 16) & 255) / 255.0f, ((v >> 8) & 255) / 255.0f, (v & 255) / 255.0f};
}

namespace {

// Exact counts as JSON numbers while a double holds them exactly, as decimal strings after.
nlohmann::ordered_json countJson(const BigCount& c) {
    auto v = c.toUint64();
    if (v && *v <= (std::uint64_t(1) << 53)) return *v;
    return c.toString();
}

nlohmann::ordered_json symbolsJson(const SymbolTable& table,
                                   const std::vector<std::uint64_t>& counts) {
    std::vector<Symbol> present;
    for (std::size_t s = 0; s < counts.size(); ++s)
        if (counts[s]) present.push_back(static_cast<Symbol>(s));
    std::sort(present.begin(), present.end(),
              [&](Symbol a, Symbol b) { return table.name(a) < table.name(b); });
    nlohmann::ordered_json symbols = nlohmann::ordered_json::object();
    for (Symbol s : present) symbols[table.name(s)] = counts[s];
    return symbols;
}

int printPrediction(const InputOptions& in, const Loaded& l) {
    GrowthPrediction g = predictGrowth(l.model.lsystem, l.steps);
    if (!g.exact && !g.expected)
        throw Error(SourceLocation{l.model.lsystem.file, 0, 0},
                    "cannot predict the growth: " + g.reason);
    nlohmann::ordered_json j;
    j["file"] = fileName(in);
    j["steps"] = l.steps;
    j["prediction"] = g.exact ? "exact" : "expected";
    if (g.exact) {
        j["modules"] = countJson(g.modules.back());
        nlohmann::ordered_json per = nlohmann::ordered_json::array();
        for (const auto& c : g.modules) per.push_back(countJson(c));
        j["modules_per_step"] = per;
        nlohmann::ordered_json symbols = nlohmann::ordered_json::object();
        for (std::size_t s = 0; s < g.symbolsAtEnd.size(); ++s)
            if (!(g.symbolsAtEnd[s] == BigCount()))
                symbols[l.model.lsystem.symbols.name(static_cast<Symbol>(s))] =
                    countJson(g.symbolsAtEnd[s]);
        j["symbols"] = symbols;
    } else {
        j["modules"] = g.expectedModules.back();
        j["modules_per_step"] = g.expectedModules;
    }
    std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    return 0;
}

}  // namespace

int runStats(const InputOptions& in, bool geometry, bool predict) {
    Loaded l = loadInput(in);
    if (predict) return printPrediction(in, l);
    DeriveRequest request = deriveRequest(in);
    request.steps = l.steps;
    const ModelStatistics stats = measured(l.model, request, geometry);
    endProgressLine();
    nlohmann::ordered_json j;
    j["file"] = fileName(in);
    j["steps"] = stats.steps;
    j["modules"] = stats.modules;
    j["symbols"] = symbolsJson(l.model.lsystem.symbols, stats.symbolCounts);
    if (stats.measured) {
        j["segments"] = stats.segments;
        j["polygons"] = stats.polygons;
        j["bbox"] = bboxJson(stats.bounds);
    }
    std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    return 0;
}

}  // namespace graftal::cli
