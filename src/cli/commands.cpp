#include "commands.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <iostream>
#include <nlohmann/json.hpp>

#include "graftal/derivation.hpp"
#include "graftal/lsystem.hpp"
#include "graftal/turtle.hpp"

namespace graftal::cli {

namespace {

Error usageError(const std::string& message) { return Error(SourceLocation{"graftal", 0, 0}, message); }

void printWarnings(const LSystem& ls) {
    for (const auto& w : ls.warnings) std::cerr << w.toString() << '\n';
}

struct Derived {
    LSystem lsystem;
    ModuleString modules;
    int steps = 0;
};

Derived loadAndDerive(const InputOptions& in) {
    ParseOptions po;
    po.defines = in.defines;
    Derived d{loadLSystem(in.file, po), {}, 0};
    printWarnings(d.lsystem);
    if (in.steps && *in.steps < 0)
        throw usageError("-n " + std::to_string(*in.steps) +
                         ": the derivation length must be 0 or more");
    d.steps = in.steps.value_or(d.lsystem.derivationLength);
    DerivationOptions opts;
    opts.memoryLimit = in.memoryLimit;
    opts.seed = in.seed;
    opts.threads = in.threads;
    d.modules = derive(d.lsystem, d.steps, opts);
    return d;
}

nlohmann::ordered_json point(const Vec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

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
    if (unit == "K") k = 1024.0;
    else if (unit == "M") k = 1024.0 * 1024;
    else if (unit == "G") k = 1024.0 * 1024 * 1024;
    else if (unit == "T") k = 1024.0 * 1024 * 1024 * 1024;
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
        throw usageError("--size '" + text + "': expected WIDTHxHEIGHT in pixels, e.g. 800x600 "
                         "(each from 1 to 32767)");
    width = w;
    height = h;
}

Rgb parseColor(const std::string& text) {
    static const std::map<std::string, Rgb> named = {
        {"black", {0, 0, 0}},       {"white", {1, 1, 1}},          {"red", {0.8f, 0.1f, 0.1f}},
        {"green", {0.1f, 0.5f, 0.15f}}, {"blue", {0.1f, 0.2f, 0.7f}}, {"none", {1, 1, 1}},
    };
    if (auto it = named.find(text); it != named.end()) return it->second;
    std::string hex = text[0] == '#' ? text.substr(1) : text;
    unsigned v = 0;
    auto r = std::from_chars(hex.data(), hex.data() + hex.size(), v, 16);
    if (hex.size() != 6 || r.ec != std::errc() || r.ptr != hex.data() + hex.size())
        throw usageError("'" + text + "' is not a colour (expected #rrggbb or a name such as black)");
    return {((v >> 16) & 255) / 255.0f, ((v >> 8) & 255) / 255.0f, (v & 255) / 255.0f};
}

int runDerive(const InputOptions& in, bool homomorphism) {
    Derived d = loadAndDerive(in);
    if (homomorphism) d.modules = applyHomomorphism(d.lsystem, d.modules);
    d.modules.print(std::cout, d.lsystem.symbols);
    std::cout << '\n';
    std::cout.flush();
    return std::cout ? 0 : 1;
}

int runStats(const InputOptions& in, bool geometry) {
    Derived d = loadAndDerive(in);
    std::vector<std::size_t> counts(d.lsystem.symbols.size(), 0);
    for (Symbol s : d.modules.symbols()) ++counts[s];
    std::vector<Symbol> present;
    for (std::size_t s = 0; s < counts.size(); ++s)
        if (counts[s]) present.push_back(static_cast<Symbol>(s));
    std::sort(present.begin(), present.end(), [&](Symbol a, Symbol b) {
        return d.lsystem.symbols.name(a) < d.lsystem.symbols.name(b);
    });
    nlohmann::ordered_json j;
    j["file"] = in.file;
    j["steps"] = d.steps;
    j["modules"] = d.modules.size();
    nlohmann::ordered_json symbols = nlohmann::ordered_json::object();
    for (Symbol s : present) symbols[d.lsystem.symbols.name(s)] = counts[s];
    j["symbols"] = symbols;
    if (geometry) {
        Scene scene = interpret(d.lsystem, applyHomomorphism(d.lsystem, d.modules));
        j["segments"] = scene.segments.size();
        j["polygons"] = scene.polygonCount();
        Bounds b = scene.bounds();
        if (b.empty()) b.extend(Vec3{});  // nothing drawn: the turtle's start
        j["bbox"] = {{"min", point(b.min)}, {"max", point(b.max)}};
    }
    std::cout << j.dump(2) << '\n';
    return 0;
}

int runRender(const InputOptions& in, const RenderCommandOptions& out) {
    if (!imageFormatFor(out.output))
        throw usageError("-o " + out.output + ": unknown picture format (use .svg, .png or .pdf)");
    Derived d = loadAndDerive(in);
    Scene scene = interpret(d.lsystem, applyHomomorphism(d.lsystem, d.modules));
    RenderOptions render = out.render;
    // pfg's scale factor: the picture fills that percentage of the frame (100 = all of it).
    double fill = std::clamp(d.lsystem.view.scaleFactor / 100.0, 0.01, 1.0);
    render.margin = 0.5 - (0.5 - render.margin) * fill;
    writeImage(scene, render, out.output);
    return 0;
}

}  // namespace graftal::cli
