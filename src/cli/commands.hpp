// The graftal subcommands. Each returns the process exit status; errors propagate as
// graftal::Error and are formatted by main().
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "graftal/core/destination.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/output/output.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal::cli {

struct InputOptions {
    std::string file;
    std::string viewFile;      // cpfg view file (.v), the second positional argument
    std::optional<int> steps;  // -n
    std::map<std::string, std::string> defines;  // -D NAME=VALUE
    std::optional<std::uint64_t> seed;
    std::optional<RandomStreams> random;  // --random cpfg|graftal
    std::size_t memoryLimit = std::size_t(2) << 30;
    unsigned threads = 0;
    bool stream = false;  // --stream: expand depth-first, never hold the string
    bool quiet = false;   // --quiet: no notes or warnings on stderr
    std::uint64_t streamLimit = 100'000'000'000ull;  // --stream-limit: most modules expanded
    Precision precision = Precision::Single;         // --precision single|double
};

struct RenderCommandOptions {
    std::string output;        // "-": standard output
    std::string outputFormat;  // --format, for -o - (default svg)
    RenderOptions render;
    std::string view;  // --view front|back|side|top: 3D as 2D line art
    std::optional<Vec3> viewpoint, target, up, light;
    std::optional<double> fieldOfView;
    int samplesPerPixel = 4;
    std::optional<int> tubeSides;  // --tube-sides, over what --quality gives
    std::string quality;           // --quality low|medium|high|N
    std::optional<int> spline;     // --spline N: B-spline subdivisions (0: off)
    bool splinePath = false;       // --spline-path: every turtle position, f included
    bool kolamDots = false;        // --dots: the kolam's dots
    bool ground = false;           // --ground: a floor under a ray-traced plant
    bool sizeGiven = false, backgroundGiven = false;
    bool derivation = false;    // --derivation: draw the derivation steps, not the turtle's picture
    bool noInstancing = false;  // --no-instancing: .glb repeated organs as copies
    bool compress = false;      // --compress: .glb buffers with EXT_meshopt_compression
};

enum class DeriveFormat { Text, Json };
int runDerive(const InputOptions& in, bool homomorphism, DeriveFormat format);
int runStats(const InputOptions& in, bool geometry, bool predict);
int runRender(const InputOptions& in, const RenderCommandOptions& out);
// The export request render's options make (derivation, picture, camera, mesh) and where
// the output goes: a file, or standard output for -o -. Throws Error for bad options.
ExportRequest renderRequest(const InputOptions& in, const RenderCommandOptions& out);
Destination renderDestination(const RenderCommandOptions& out);
// --view NAME as a direction; throws Error naming the choices.
ViewDirection parseViewOption(const std::string& name);
// --quality (low, medium, high, N) and then --tube-sides into the request's mesh resolution.
void applyMeshQuality(RenderRequest& request, const std::string& quality,
                      std::optional<int> tubeSides);

// The file read (once: its warnings are printed here) and the step count settled, nothing
// derived yet.
struct Loaded {
    Model model;
    int steps = 0;
};
Loaded loadInput(const InputOptions& in);
// The input's name in output: the file, or <stdin> for "-".
std::string fileName(const InputOptions& in);

// What derive, stats and render share: the parsed file, its derived string, the step count.
struct Derived {
    Model model;
    ModuleString modules;
    int steps = 0;
};
Derived deriveLoaded(Loaded loaded, const InputOptions& in);
// The library's request for these options: progress on a terminal, notes on stderr.
DeriveRequest deriveRequest(const InputOptions& in);
// The model's view places the turtle that answers query modules.
DerivationOptions derivationOptions(const InputOptions& in, const Model& model);
// graftal::shouldStream for these options; its note goes to stderr.
bool chooseStreaming(const Loaded& l, const InputOptions& in, bool canStream,
                     bool countGeometry = false, bool pixelBound = false);
void note(const InputOptions& in, const std::string& message);
// The library's remedies in the command's terms: "lower -n", "raise --memory-limit", ...
std::string remedyAsFlag(Remedy r);
// A diagnostic as printed on stderr, its remedies worded as flags.
std::string describe(const Diagnostic& d);
void endProgressLine();

// "2G", "512M", "1000000" -> bytes; throws Error on a malformed size.
std::size_t parseByteSize(const std::string& text);
// "800x600" -> width, height; throws Error.
void parseImageSize(const std::string& text, int& width, int& height);
// "#rrggbb", "rrggbb" or a few names (black, white, ...) -> colour; throws Error.
Rgb parseColor(const std::string& text);
// "x,y,z" -> vector; throws Error naming the option.
Vec3 parseVector(const std::string& option, const std::string& text);

}  // namespace graftal::cli
