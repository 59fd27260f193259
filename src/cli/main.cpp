// The graftal command: formats the library's errors, the library itself never prints.
#include <array>
#include <cctype>
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <iostream>

#include "animate_command.hpp"
#include "commands.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/core/file_format.hpp"
#include "map_commands.hpp"
#include "music_command.hpp"
#include "studio_command.hpp"

namespace {

void addInputOptions(CLI::App& cmd, graftal::cli::InputOptions& in, std::string& memoryLimit) {
    cmd.add_option("file", in.file,
                   "L-system file (.l), a model folder with one .l and .v, or - for standard "
                   "input")
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
    cmd.add_option("--random", in.random,
                   "whose random numbers: cpfg (cpfg's generators in cpfg's order: cpfg's "
                   "string; the default for a model read with a view file) or graftal "
                   "(graftal's streams: the same string for any thread count)")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, graftal::RandomStreams>{
                {"cpfg", graftal::RandomStreams::Cpfg},
                {"graftal", graftal::RandomStreams::Graftal}},
            CLI::ignore_case)
                       .description("{cpfg, graftal}"));
    cmd.add_option("--memory-limit", memoryLimit, "largest string memory, e.g. 2G (default 2G)");
    cmd.add_option("--threads", in.threads, "worker threads (default: all cores)");
    cmd.add_flag("--stream", in.stream,
                 "expand depth-first into the output, never holding the string "
                 "(L-systems without context; chosen by itself when the string would not fit)");
    cmd.add_flag("-q,--quiet", in.quiet, "no notes or warnings on stderr");
    cmd.add_option("--stream-limit", in.streamLimit,
                   "most modules a streamed run expands one by one (1e11); a picture drawn "
                   "from subtree summaries expands a few per pixel");
    cmd.add_option("--precision", in.precision,
                   "how parameters are stored: single (32-bit floats, as cpfg; default) or double")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, graftal::Precision>{{"single", graftal::Precision::Single},
                                                      {"double", graftal::Precision::Double}},
            CLI::ignore_case)
                       // The values are one-byte enums, which the default text prints as
                       // raw bytes: the help names the choices instead.
                       .description("{single, double}"));
}

// What an option's value must be, in the words of its message.
std::string expectedValue(const std::string& longName) {
    if (longName == "--steps") return "a whole number of steps";
    if (longName == "--threads") return "a whole number of threads";
    if (longName == "--seed" || longName == "--spp" || longName == "--tube-sides" ||
        longName == "--spline")
        return "a whole number";
    if (longName == "--stream-limit") return "a number of modules";
    return "a number";
}

// CLI11's own messages name an option by its long name and list unexpected arguments in
// reverse; this checks the command line first and says what was typed and what was
// expected. Empty when the command line looks right (CLI11 then parses it).
std::string usageProblem(CLI::App& app, int argc, char** argv) {
    if (argc < 2) return {};
    const std::string first = argv[1];
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({}))
        names += (names.empty() ? "" : ", ") + sub->get_name();
    if (first.empty() || first[0] != '-') {
        CLI::App* sub = nullptr;
        for (CLI::App* s : app.get_subcommands({}))
            if (s->get_name() == first) sub = s;
        if (!sub) return "unknown subcommand '" + first + "' (subcommands: " + names + ")";
        for (int i = 2; i < argc; ++i) {
            const std::string arg = argv[i];
            if (arg == "--") break;
            if (arg.size() < 2 || arg[0] != '-') continue;
            const std::string name = arg.substr(0, arg[1] == '-' ? arg.find('=') : 2);
            if (name == "-h" || name == "--help") return {};
            const CLI::Option* opt = sub->get_option_no_throw(name);
            if (!opt)
                return "unknown option '" + name + "' for " + first + " (see graftal " + first +
                       " --help)";
            if (opt->get_expected_max() == 0 || opt->get_type_size_max() == 0) continue;
            // The value: after '=', glued to a short name (-n5), or the next argument.
            std::string value;
            if (name.size() < arg.size())
                value = arg.substr(name.size() + (arg[name.size()] == '=' ? 1 : 0));
            else if (i + 1 < argc)
                value = argv[++i];
            else
                return name + ": expected " +
                       expectedValue(opt->get_lnames().empty() ? name
                                                               : "--" + opt->get_lnames()[0]);
            const std::string longName =
                opt->get_lnames().empty() ? name : "--" + opt->get_lnames()[0];
            // The choices of the one-byte enums, whose values CLI11's message would print
            // as raw bytes.
            for (const auto& [option, choices] :
                 {std::pair{"--precision", std::array{"single", "double"}},
                  std::pair{"--random", std::array{"cpfg", "graftal"}}}) {
                if (longName != option) continue;
                std::string lowered = value;
                for (char& c : lowered) c = static_cast<char>(std::tolower(c));
                if (lowered != choices[0] && lowered != choices[1])
                    return name + " " + value + ": expected " + choices[0] + " or " + choices[1];
            }
            const std::string expected = expectedValue(longName);
            if (expected.rfind("a whole number", 0) == 0 || expected.rfind("a number", 0) == 0) {
                if (opt->get_type_name().find("INT") == std::string::npos &&
                    opt->get_type_name().find("FLOAT") == std::string::npos &&
                    opt->get_type_name().find("UINT") == std::string::npos)
                    continue;
                char* end = nullptr;
                const bool whole = expected.rfind("a whole number", 0) == 0;
                if (whole)
                    (void)std::strtoll(value.c_str(), &end, 10);
                else
                    (void)std::strtod(value.c_str(), &end);
                if (value.empty() || *end != '\0')
                    return name + " " + value + ": expected " + expected;
            }
        }
    }
    return {};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"graftal: Lindenmayer systems, derived and drawn"};
    app.require_subcommand(1);
    app.footer(
        "Each subcommand has its own options: graftal SUBCOMMAND --help.\n"
        "Documentation: docs/ (docs/cli.md for this command); examples to start from: "
        "examples/.");
    app.set_version_flag("--version", "graftal 0.1.0");

    graftal::cli::InputOptions in;
    std::string memoryLimit;
    graftal::cli::RenderCommandOptions out;
    bool noGeometry = false, homomorphism = false, predict = false;
    std::string size, background, color, viewpoint, target, up, light;

    auto* derive = app.add_subcommand("derive", "print the derived module string");
    addInputOptions(*derive, in, memoryLimit);
    graftal::cli::MapOptions mapOptions;
    graftal::cli::addMapOptions(*derive, mapOptions, false);
    derive->add_flag("--homo", homomorphism, "print the string after the homomorphism");
    std::string deriveFormat = "text";
    derive
        ->add_option("--format", deriveFormat,
                     "text (as the L-system file writes modules) or json (one object per "
                     "module with its parameters; docs/cli.md)")
        ->check(CLI::IsMember({"text", "json"}));

    auto* stats = app.add_subcommand("stats", "print counts and bounds as JSON");
    addInputOptions(*stats, in, memoryLimit);
    graftal::cli::addMapOptions(*stats, mapOptions, false);
    stats->add_flag("--no-geometry", noGeometry, "derive and count only, no turtle");
    stats->add_flag("--predict", predict,
                    "module counts per step from the productions, without deriving");

    auto* render = app.add_subcommand(
        "render", "draw the L-system: pictures (" +
                      graftal::extensionList(graftal::FormatKind::Picture, " ", " ") +
                      ") or 3D files (" +
                      graftal::extensionList(graftal::FormatKind::Mesh, " ", " ") + ")");
    addInputOptions(*render, in, memoryLimit);
    graftal::cli::addMapOptions(*render, mapOptions, true);
    render
        ->add_option("-o,--output", out.output,
                     "output file: " + graftal::extensionList(std::nullopt, " ", " ") +
                         "; - for standard output")
        ->required();
    render->add_option("--format", out.outputFormat,
                       "format written by -o -: svg (default) or obj; png pdf ply glb only "
                       "into a pipe or file");
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
    render->add_option("--quality", out.quality,
                       "3D mesh resolution: low, medium (default), high, or N (3-64) for N "
                       "tube sides and N surface divisions");
    render->add_flag("--ground", out.ground, "3D: a floor under the plant, with its shadow");
    render
        ->add_option("--spline", out.spline,
                     "draw turtle paths as B-splines with N points per segment (0: straight)")
        ->check(CLI::Range(0, 64));
    render->add_flag("--spline-path", out.splinePath,
                     "B-spline through every turtle position, f moves included, drawn whole "
                     "(kolams; --spline 8 unless given)");
    render->add_flag("--dots", out.kolamDots, "draw the dots a kolam's loops surround (pulli)");
    render->add_flag("--no-instancing", out.noInstancing,
                     ".glb: copy repeated organs instead of EXT_mesh_gpu_instancing (for "
                     "viewers without it)");
    render->add_flag("--compress", out.compress,
                     ".glb: compress with EXT_meshopt_compression (viewers need its decoder)");

    graftal::cli::MusicCommandOptions musicOut;
    auto* music = app.add_subcommand(
        "music",
        "play the curve: horizontal runs as notes (.mid .wav .ly .pdf .png .svg .musicxml)");
    addInputOptions(*music, in, memoryLimit);
    graftal::cli::addMusicOptions(*music, musicOut);

    graftal::cli::StudioCommandOptions studio;
    graftal::cli::addStudioCommand(app, studio);

    graftal::cli::AnimateCommand animate(
        app, [&](CLI::App& cmd) { addInputOptions(cmd, in, memoryLimit); });

    if (std::string problem = usageProblem(app, argc, argv); !problem.empty()) {
        std::cerr << "graftal: error: " << problem << "\n";
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version are "errors" that exit 0; every real usage error exits 2.
        int status = app.exit(e);
        return status == 0 ? 0 : 2;
    }

    try {
        if (!memoryLimit.empty()) in.memoryLimit = graftal::cli::parseByteSize(memoryLimit);
        if (*studio.command) return graftal::cli::runStudio(studio);
        const bool map = graftal::cli::isMapInput(in);
        if (*derive && map) return graftal::cli::runMapDerive(in, mapOptions);
        if (*stats && map) return graftal::cli::runMapStats(in, mapOptions);
        if (*derive)
            return graftal::cli::runDerive(in, homomorphism,
                                           deriveFormat == "json"
                                               ? graftal::cli::DeriveFormat::Json
                                               : graftal::cli::DeriveFormat::Text);
        if (*stats) return graftal::cli::runStats(in, !noGeometry, predict);
        if (*music) return graftal::cli::runMusic(in, musicOut);
        if (animate.chosen()) return animate.run(in);
        if (!size.empty()) graftal::cli::parseImageSize(size, out.render.width, out.render.height);
        if (!background.empty()) out.render.background = graftal::cli::parseColor(background);
        out.backgroundGiven = !background.empty();
        if (!viewpoint.empty()) out.viewpoint = graftal::cli::parseVector("--viewpoint", viewpoint);
        if (!target.empty()) out.target = graftal::cli::parseVector("--target", target);
        if (!up.empty()) out.up = graftal::cli::parseVector("--up", up);
        if (!light.empty()) out.light = graftal::cli::parseVector("--light", light);
        if (!color.empty()) out.render.lineColor = graftal::cli::parseColor(color);
        if (map) return graftal::cli::runMapRender(in, out, mapOptions);
        return graftal::cli::runRender(in, out);
    } catch (const graftal::Error& e) {
        for (const auto& d : e.diagnostics()) std::cerr << graftal::cli::describe(d) << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "graftal: error: out of memory (lower -n or --memory-limit)\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "graftal: error: " << e.what() << '\n';
        return 1;
    }
}
