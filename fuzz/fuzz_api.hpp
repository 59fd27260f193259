// Every call the fuzz targets make into graftal, in one place: when the library's API
// changes (the parser returning its diagnostics instead of throwing, say), this header is
// the only file of fuzz/ to adapt. Each function takes untrusted bytes, treats a rejection
// with graftal::Error as the normal outcome, and aborts on anything the library promises
// never to do (an Error without a message, streamed and stored derivations that differ).
// Any other exception is left to escape: libFuzzer and the replay driver report it.
#pragma once

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "graftal/geometry/contour_points.hpp"
#include "graftal/graftal.hpp"
#include "graftal/lang/contour_file.hpp"

namespace graftal_fuzz {

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// A broken promise of the library: reported like a crash, with what was expected.
[[noreturn]] inline void finding(const std::string& what) {
    std::fprintf(stderr, "graftal fuzz check failed: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

// A rejection must say what is wrong: at least one diagnostic, each with a message.
inline void checkRejection(const graftal::Error& e, const char* stage) {
    if (e.diagnostics().empty()) finding(std::string(stage) + ": Error without diagnostics");
    for (const graftal::Diagnostic& d : e.diagnostics())
        if (d.message.empty()) finding(std::string(stage) + ": diagnostic without a message");
}

// ---- .l text ------------------------------------------------------------------------

// The model of `text`, or nullopt when the parser rejected it. The parser returns its
// diagnostics as values: a rejection must carry at least one error, each with a message.
inline std::optional<graftal::Model> parseModel(
    std::string_view text, std::vector<graftal::Diagnostic>* warnings = nullptr) {
    graftal::ParseOptions options;
    options.fileName = "fuzz.l";
    graftal::ParseResult result = graftal::parse(text, options);
    for (const graftal::Diagnostic& d : result.diagnostics)
        if (d.message.empty()) finding("parse: diagnostic without a message");
    if (!result.ok()) {
        if (result.errors().empty()) finding("parse: rejected without an error");
        return std::nullopt;
    }
    if (warnings) *warnings = result.warnings();
    return std::move(result.model);
}

// Parses and prints the model back (the printer walks every part the parser filled in).
inline void parseAndPrint(std::string_view text) {
    std::vector<graftal::Diagnostic> warnings;
    std::optional<graftal::Model> model = parseModel(text, &warnings);
    if (!model) return;
    std::ostringstream printed;
    printed << *model;
    for (const graftal::Diagnostic& d : warnings) printed << d << '\n';
}

// ---- derivation, interpretation, writers ---------------------------------------------

// Small enough that one input runs in milliseconds, large enough to reach every stage.
struct RunLimits {
    int maxSteps = 6;                                // derivation steps at most
    std::size_t memoryLimit = std::size_t(8) << 20;  // bytes of module string
    std::size_t maxModules = 20000;                  // no further step once the string is longer
    std::chrono::milliseconds budget{300};           // no further step once this is spent
    // Pixels of the PNG and SVG: the command's default, since what Cairo does with an
    // extreme stroke depends on the picture's size (a 48-pixel PNG hides some).
    int imageSize = 800;
};

// Answers ?E with zeros: stands in for the `process` environment, which would run the
// fuzzer's text as a shell command.
class QuietEnvironment : public graftal::Environment {
  public:
    std::string name() const override { return "fuzz"; }
    void respond(int, std::span<graftal::CommunicationRequest> requests) override {
        for (auto& r : requests)
            for (double& p : r.params) p = 0;
    }
};

inline bool asksForProcess(const graftal::LSystem& model) {
    for (const graftal::EnvironmentLine& line : model.environment)
        if (line.text.find("process") != std::string::npos) return true;
    return false;
}

inline bool sameNumber(double a, double b) {
    return a == b || (std::isnan(a) && std::isnan(b));
}

// Compares a streamed derivation with the stored string, module by module.
class ComparingSink : public graftal::ModuleSink {
  public:
    explicit ComparingSink(const graftal::ModuleString& expected) : expected_(expected) {}
    void module(graftal::Symbol symbol, std::span<const double> params) override {
        if (next_ >= expected_.size()) finding("streamed derivation has more modules");
        graftal::ParamView want = expected_.params(next_);
        bool same = expected_.symbol(next_) == symbol && want.size() == params.size();
        for (std::size_t i = 0; same && i < params.size(); ++i)
            same = sameNumber(want[i], params[i]);
        if (!same) finding("streamed derivation differs at module " + std::to_string(next_));
        ++next_;
    }
    void finish() const {
        if (next_ != expected_.size()) finding("streamed derivation has fewer modules");
    }

  private:
    const graftal::ModuleString& expected_;
    std::size_t next_ = 0;
};

inline std::filesystem::path scratchImage(const char* extension) {
    return std::filesystem::temp_directory_path() /
           ("graftal-fuzz-" + std::to_string(::getpid()) + extension);
}

// Draws `scene` the ways `graftal render` does: SVG in memory, PNG to a scratch file, and
// the 3D mesh in memory.
inline void drawScene(const graftal::Scene& scene, const RunLimits& limits) {
    graftal::RenderOptions render;
    render.width = render.height = limits.imageSize;
    std::ostringstream svg;
    graftal::writeSvg(scene, render, svg);
    std::filesystem::path png = scratchImage(".png");
    graftal::writeImage(scene, render, png);
    std::filesystem::remove(png);
    static const graftal::SurfaceLibrary surfaces = graftal::SurfaceLibrary::builtin();
    graftal::MeshOptions mesh;
    mesh.tubeSides = 3;
    mesh.surfaceDivisions = 2;
    (void)graftal::buildMesh(scene, mesh, &surfaces);
}

// Parses, predicts growth, derives step by step within `limits`, compares a streamed
// derivation with the stored one, applies the homomorphism, interprets and draws.
inline void deriveAndDraw(std::string_view text, const RunLimits& limits = {}) {
    std::optional<graftal::Model> parsed = parseModel(text);
    if (!parsed) return;
    const graftal::LSystem* model = &parsed->lsystem;
    const auto start = std::chrono::steady_clock::now();
    const int steps = model->derivationLength > 0
                          ? std::min(model->derivationLength, limits.maxSteps)
                          : limits.maxSteps / 2;
    QuietEnvironment quiet;
    graftal::DerivationOptions options;
    options.memoryLimit = limits.memoryLimit;
    options.threads = 1;
    if (asksForProcess(*model)) options.environment = &quiet;
    try {
        graftal::GrowthPrediction growth = graftal::predictGrowth(*model, steps);
        graftal::Derivation derivation(*parsed, options);
        while (derivation.stepsDone() < steps && derivation.current().size() <= limits.maxModules &&
               std::chrono::steady_clock::now() - start < limits.budget)
            derivation.step();
        const graftal::ModuleString& derived = derivation.current();
        const int done = derivation.stepsDone();
        if (graftal::streamingObstacle(*model).empty()) {
            ComparingSink sink(derived);
            try {
                graftal::streamDerivation(*model, done, sink, options);
            } catch (const graftal::Error& e) {
                finding("streamed derivation failed where the stored one succeeded: " +
                        std::string(e.what()));
            }
            sink.finish();
        }
        graftal::ModuleString seen = graftal::applyHomomorphism(*model, derived, options);
        (void)graftal::measureModules(*parsed, seen);
        graftal::Scene scene = graftal::interpret(*parsed, seen);
        drawScene(scene, limits);
        // Last, so that a wrong count does not hide what the stages above would find.
        if (growth.exact && growth.modules.size() > std::size_t(done)) {
            std::optional<std::uint64_t> predicted = growth.modules[done].toUint64();
            if (!predicted || *predicted != derived.size())
                finding("predicted " + growth.modules[done].toString() + " modules after " +
                        std::to_string(done) + " steps, derived " + std::to_string(derived.size()));
        }
    } catch (const graftal::Error& e) {
        checkRejection(e, "derive");
    }
}

// ---- .s surface files ------------------------------------------------------------------

// Parses a surface, evaluates its patches and tessellates it placed in a scene.
inline void parseSurfaceFile(std::string_view text) {
    graftal::Surface surface;
    try {
        surface = graftal::parseSurface(text, "fuzz.s");
    } catch (const graftal::Error& e) {
        checkRejection(e, "surface");
        return;
    }
    for (const graftal::BezierPatch& patch : surface.patches)
        for (double s : {0.0, 0.5, 1.0}) {
            graftal::Vec3 normal;
            (void)graftal::evaluatePatch(patch, s, 1 - s, &normal);
        }
    try {
        graftal::SurfaceLibrary library;
        surface.name = "fuzz";
        library.add(surface);
        graftal::Scene scene;
        scene.surfaceNames.push_back("fuzz");
        scene.surfaces.push_back(graftal::SurfaceInstance{});
        graftal::MeshOptions mesh;
        mesh.surfaceDivisions = 3;
        (void)graftal::buildMesh(scene, mesh, &library);
    } catch (const graftal::Error& e) {
        checkRejection(e, "surface mesh");
    }
}

// ---- view and data files ------------------------------------------------------------

// The files a cpfg model names besides its .l: the view file (.v) read with a small fixed
// L-system and then drawn, and the contour (.con, .cset), function (.func, .fset), curve,
// material (.mat) and colour map (.map) readers. The first byte picks the reader (modulo 8,
// so the digits 0 to 7 in a seed); the rest is its input.
// The view is named inside an empty scratch folder, so relative file names find nothing.
inline void readDataFile(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return;
    const std::string_view text = asText(data + 1, size - 1);
    const std::span<const std::uint8_t> bytes(data + 1, size - 1);
    try {
        switch (data[0] % 8) {
            case 0: {
                static const std::string folder = [] {
                    auto f = std::filesystem::temp_directory_path() /
                             ("graftal-fuzz-view-" + std::to_string(::getpid()));
                    std::filesystem::create_directories(f);
                    return f.string();
                }();
                graftal::ParseOptions options;
                options.fileName = folder + "/fuzz.l";
                graftal::ParseResult result = graftal::parse(
                    "derivation length: 2\naxiom: F(1)A\nA --> [+F(1)~l]&F(1)/A\n"
                    "endlsystem\n",
                    text, folder + "/fuzz.v", options);
                for (const graftal::Diagnostic& d : result.diagnostics)
                    if (d.message.empty()) finding("view: diagnostic without a message");
                if (!result.ok()) {
                    if (result.errors().empty()) finding("view: rejected without an error");
                    return;
                }
                std::ostringstream printed;
                printed << result.model;
                graftal::DerivationOptions derive;
                derive.threads = 1;
                graftal::Derivation derivation(result.model, derive);
                derivation.step();
                derivation.step();
                graftal::Scene scene = graftal::interpret(result.model, derivation.current());
                RunLimits limits;
                limits.imageSize = 200;
                drawScene(scene, limits);
                return;
            }
            case 1: {
                graftal::Contour contour = graftal::parseContourFile(text, "fuzz.con", 1);
                for (int sides : {3, 8}) (void)graftal::contourPoints(contour, sides);
                return;
            }
            case 2: {
                graftal::GraphicalFunction f = graftal::parseFunctionFile(text, "fuzz.func", 20);
                for (double x : {-1.0, 0.0, 0.25, 1.0, 2.0}) (void)f.value(x);
                return;
            }
            case 3: {
                for (const graftal::GraphicalFunction& f :
                     graftal::parseFunctionSet(text, "fuzz.fset"))
                    (void)f.value(0.5);
                return;
            }
            case 4:
                (void)graftal::materialPalette(graftal::parseMaterials(bytes, "fuzz.mat"));
                return;
            case 5:
                (void)graftal::parseColorMap(bytes, "fuzz.map");
                return;
            case 6: {
                graftal::CurveXYZ curve = graftal::parseCurveFile(text, "fuzz.crv", 20);
                for (double t : {0.0, 0.3, 1.0}) {
                    (void)curve.atLength(t);
                    (void)curve.atParameter(t);
                }
                return;
            }
            default:
                for (const graftal::Contour& c : graftal::parseContourSet(text, "fuzz.cset"))
                    (void)graftal::contourPoints(c, 6);
                return;
        }
    } catch (const graftal::Error& e) {
        checkRejection(e, "data file");
    }
}

// ---- expressions -----------------------------------------------------------------------

// Compiles `text` with three variables and a few defines, then evaluates it at a few
// points (with a deterministic ran()) and as a constant expression.
inline void compileAndEvaluate(std::string_view text) {
    static const std::map<std::string, std::string> defines = {
        {"N", "3"}, {"R", "2*N"}, {"SQ", "x*x"}, {"PI", "3.14159"}};
    graftal::ExpressionScope scope;
    scope.variables = {"x", "y", "z"};
    scope.defines = &defines;
    const graftal::SourceLocation where{"fuzz", 1, 1};
    graftal::DiagnosticList diags;
    graftal::Expression e = graftal::compileExpression(text, where, scope, diags);
    if (diags.hasErrors() != e.empty())
        finding(diags.hasErrors() ? "an expression with errors was compiled"
                                  : "an expression without errors compiled to nothing");
    for (const graftal::Diagnostic& d : diags.items())
        if (d.message.empty()) finding("expression: diagnostic without a message");
    if (!e.empty()) {
        std::uint64_t state = 0x9e3779b97f4a7c15u;
        graftal::EvalContext context;
        context.uniform = [&state] {
            state = state * 6364136223846793005u + 1442695040888963407u;
            return double(state >> 11) * 0x1.0p-53;
        };
        const double points[][3] = {{0, 0, 0}, {1.5, -2, 0.25}, {-1e300, 1e-300, 7}};
        for (const auto& p : points) {
            try {
                (void)e.evaluate(std::span<const double>(p, 3), &context);
            } catch (const graftal::Error& err) {
                checkRejection(err, "evaluate");
            }
        }
        std::ostringstream printed;
        e.print(printed);
    }
    try {
        (void)graftal::evaluateConstant(text, where, defines);
    } catch (const graftal::Error& err) {
        checkRejection(err, "constant");
    }
}

}  // namespace graftal_fuzz
