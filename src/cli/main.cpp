// The graftal command: formats the library's errors, the library itself never prints.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"
#include "graftal/diagnostics.hpp"
#include "graftal/file_format.hpp"

namespace {

void addInputOptions(CLI::App& cmd, graftal::cli::InputOptions& in, std::string& memoryLimit) {
    cmd.add_option("file", in.file, "L-system file (.l), or a model folder with one .l and .v")
        ->required();
    cmd.add_option("view", in.viewFile, "cpfg view file (.v); its settings win over the .l's");
    cmd.add_option("-n,--steps", in.steps, "derivation length (overrides the file)");
    cmd.add_option(
           "-D,--define",
           [&in](const CLI::results_t& rs) {
               for (const auto& r : rs) {
                   auto eq = r.find('=');
                   if (eq == std::string::npos || eq == 0)
                       throw CLI::ValidationError("-D", "expected NAME=VALUE, got '" + r + "'");
                   in.defines[r.substr(0, eq)] = r.substr(eq + 1);
               }
               return true;
           },
           "set a #define constant, NAME=VALUE (repeatable)")
        ->type_name("NAME=VALUE")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd.add_option("--seed", in.seed, "random seed for stochastic L-systems")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--memory-limit", memoryLimit, "largest string memory, e.g. 2G (default 2G)");
    cmd.add_option("--threads", in.threads, "worker threads (default: all cores)");
    cmd.add_flag("--stream", in.stream,
                 "expand depth-first into the output, never holding the string "
                 "(L-systems without context; chosen by itself when the string would not fit)");
    cmd.add_flag("-q,--quiet", in.quiet, "no notes or warnings on stderr");
    cmd.add_option("--stream-limit", in.streamLimit,
                   "largest string (modules) streamed when it does not fit in memory (1e11)");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"graftal: Lindenmayer systems, derived and drawn"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "graftal 0.1.0");

    graftal::cli::InputOptions in;
    std::string memoryLimit;
    graftal::cli::RenderCommandOptions out;
    bool noGeometry = false, homomorphism = false, predict = false;
    std::string size, background, color, viewpoint, target, up, light;

    auto* derive = app.add_subcommand("derive", "print the derived module string");
    addInputOptions(*derive, in, memoryLimit);
    derive->add_flag("--homo", homomorphism, "print the string after the homomorphism");

    auto* stats = app.add_subcommand("stats", "print counts and bounds as JSON");
    addInputOptions(*stats, in, memoryLimit);
    stats->add_flag("--no-geometry", noGeometry, "derive and count only, no turtle");
    stats->add_flag("--predict", predict,
                    "module counts per step from the productions, without deriving");

    auto* render = app.add_subcommand(
        "render", "draw the L-system: pictures (" +
                      graftal::extensionList(graftal::FormatKind::Picture, " ", " ") +
                      ") or 3D files (" +
                      graftal::extensionList(graftal::FormatKind::Mesh, " ", " ") + ")");
    addInputOptions(*render, in, memoryLimit);
    render
        ->add_option("-o,--output", out.output,
                     "output file: " + graftal::extensionList(std::nullopt, " ", " "))
        ->required();
    render->add_option("--size", size, "picture size WxH in pixels (default 800x800)");
    render->add_option("--line-width", out.render.lineWidth, "line width in pixels (0: automatic)")
        ->check(CLI::Range(0.0, 1000.0));
    render->add_option("--background", background, "background colour, #rrggbb");
    render->add_option("--color", color, "line colour, #rrggbb (default: the palette)");
    render->add_option("--margin", out.render.margin, "margin, fraction of the picture")
        ->check(CLI::Range(0.0, 0.45));
    render->add_flag("--derivation", out.derivation,
                     "draw the derivation: one row of labelled cells per step (.svg .png .pdf)");
    render->add_option("--view", out.view,
                       "draw a 3D model as 2D line art: front, back, side, top");
    render->add_option("--viewpoint", viewpoint, "3D camera position x,y,z (default: framed)");
    render->add_option("--target", target, "3D point the camera looks at, x,y,z");
    render->add_option("--up", up, "3D camera up vector x,y,z (default 0,1,0)");
    render->add_option("--fov", out.fieldOfView, "3D vertical field of view, degrees")
        ->check(CLI::Range(0.01, 179.99));
    render->add_option("--light", light, "3D direction towards the sun, x,y,z");
    render->add_option("--spp", out.samplesPerPixel, "3D samples per pixel (antialiasing)")
        ->check(CLI::Range(1, 1024));
    render->add_option("--tube-sides", out.tubeSides, "3D cylinder cross-section vertices")
        ->check(CLI::Range(3, 64));
    render
        ->add_option("--spline", out.spline,
                     "draw turtle paths as B-splines with N points per segment (0: straight)")
        ->check(CLI::Range(0, 64));

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version are "errors" that exit 0; every real usage error exits 2.
        int status = app.exit(e);
        return status == 0 ? 0 : 2;
    }

    try {
        if (!memoryLimit.empty()) in.memoryLimit = graftal::cli::parseByteSize(memoryLimit);
        if (*derive) return graftal::cli::runDerive(in, homomorphism);
        if (*stats) return graftal::cli::runStats(in, !noGeometry, predict);
        if (!size.empty()) graftal::cli::parseImageSize(size, out.render.width, out.render.height);
        if (!background.empty()) out.render.background = graftal::cli::parseColor(background);
        out.backgroundGiven = !background.empty();
        if (!viewpoint.empty()) out.viewpoint = graftal::cli::parseVector("--viewpoint", viewpoint);
        if (!target.empty()) out.target = graftal::cli::parseVector("--target", target);
        if (!up.empty()) out.up = graftal::cli::parseVector("--up", up);
        if (!light.empty()) out.light = graftal::cli::parseVector("--light", light);
        if (!color.empty()) out.render.lineColor = graftal::cli::parseColor(color);
        return graftal::cli::runRender(in, out);
    } catch (const graftal::Error& e) {
        for (const auto& d : e.diagnostics()) std::cerr << d.toString() << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "graftal: error: out of memory (lower -n or --memory-limit)\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "graftal: error: " << e.what() << '\n';
        return 1;
    }
}
