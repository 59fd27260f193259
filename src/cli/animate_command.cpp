// graftal animate: the options become an AnimationRequest; the library derives every step
// once, draws the frames with one fixed camera and encodes them.
#include "animate_command.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>

namespace graftal::cli {

AnimateCommand::AnimateCommand(CLI::App& app,
                               const std::function<void(CLI::App&)>& addInputOptions) {
    command_ = app.add_subcommand(
        "animate", "the development as an animation: .gif .webp .mp4, or a folder of PNG frames");
    CLI::App& c = *command_;
    addInputOptions(c);
    c.add_option("-o,--output", output_,
                 "output: .gif, .webp, .mp4, or a folder name for numbered PNG frames")
        ->required();
    c.add_option("--from", request_.from, "first step drawn (default 0)");
    c.add_option("--to", to_, "last step drawn (default: -n, else the derivation length)");
    c.add_option("--fps", request_.fps, "frames per second (default 10)");
    c.add_option("--hold", request_.holdSeconds, "seconds the last frame stays (default 0)");
    c.add_option("--frames", frames_,
                 "frames of the last step (default 1; with --turntable the camera keeps turning)");
    c.add_option("--frames-per-step", request_.framesPerStep,
                 "frames from one step to the next; models with 'age:' grow between steps "
                 "(default 1)");
    c.add_option("--turntable", request_.turntableDegrees,
                 "turn the camera by DEG about the up axis every frame");
    c.add_flag("--derivation", request_.derivationDiagram,
               "animate the derivation diagram (a row of cells more each step; chosen by itself "
               "when the string draws nothing)");
    c.add_flag("--global-palette", request_.globalPalette, "GIF: one palette for all frames");
    c.add_flag("--dither", request_.dither,
               "GIF: error diffusion for frames of more than 256 colours");
    c.add_option("--size", size_, "picture size WxH in pixels (default 800x800)");
    c.add_option("--line-width", request_.picture.lineWidth,
                 "line width in pixels (0: automatic, the same in every frame)")
        ->check(CLI::Range(0.0, 1000.0));
    c.add_option("--background", background_, "background colour, #rrggbb");
    c.add_option("--color", color_, "line colour, #rrggbb (default: the palette)");
    c.add_option("--margin", request_.picture.margin, "margin, fraction of the picture")
        ->check(CLI::Range(0.0, 0.45));
    c.add_option("--view", view_, "draw a 3D model as 2D line art: front, back, side, top");
    c.add_option("--viewpoint", viewpoint_, "3D camera position x,y,z (default: framed)");
    c.add_option("--target", target_, "3D point the camera looks at, x,y,z");
    c.add_option("--up", up_, "3D camera up vector x,y,z (default 0,1,0)");
    c.add_option("--fov", request_.fieldOfView, "3D vertical field of view, degrees")
        ->check(CLI::Range(0.01, 179.99));
    c.add_option("--light", light_, "3D direction towards the sun, x,y,z");
    c.add_option("--spp", request_.samplesPerPixel, "3D samples per pixel (antialiasing)")
        ->check(CLI::Range(1, 1024));
    c.add_option("--tube-sides", tubeSides_, "3D cylinder cross-section vertices")
        ->check(CLI::Range(3, 64));
    c.add_option("--quality", quality_,
                 "3D mesh resolution: low, medium (default), high, or N (3-64) for N tube sides "
                 "and N surface divisions");
    c.add_flag("--ground", request_.ground, "3D: a floor under the plant, with its shadow");
    c.add_option("--spline", request_.spline,
                 "draw turtle paths as B-splines with N points per segment (0: straight)")
        ->check(CLI::Range(0, 64));
}

int AnimateCommand::run(const InputOptions& in) {
    ExportRequest request;
    static_cast<AnimationRequest&>(request) = request_;
    static_cast<DeriveRequest&>(request) = deriveRequest(in);
    request.output = output_;
    // A model folder's files are beside its .l, the model's own file.
    if (!std::filesystem::is_directory(in.file)) request.sourceFile = in.file;
    request.to = to_;
    if (frames_) request.lastFrames = *frames_;
    if (!size_.empty()) parseImageSize(size_, request.picture.width, request.picture.height);
    if (!background_.empty()) request.background = parseColor(background_);
    if (!color_.empty()) request.picture.lineColor = parseColor(color_);
    if (!view_.empty()) request.view = parseViewOption(view_);
    if (!viewpoint_.empty()) request.viewpoint = parseVector("--viewpoint", viewpoint_);
    if (!target_.empty()) request.target = parseVector("--target", target_);
    if (!up_.empty()) request.up = parseVector("--up", up_);
    if (!light_.empty()) request.light = parseVector("--light", light_);
    applyMeshQuality(request, quality_, tubeSides_);
    // Option errors and an output that cannot be written, before the file is read.
    checkAnimationRequest(request);
    checkAnimationOutput(request.output, *animationFormatFor(request.output));

    bool shown = false;
    if (!in.quiet && ::isatty(2)) {
        const auto start = std::chrono::steady_clock::now();
        request.frameProgress = [start, &shown](int done, int total) {
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cerr << "\rgraftal: frame " << done << "/" << total << " (" << int(seconds)
                      << " s)   " << std::flush;
            shown = true;
        };
    }
    Loaded l = loadInput(in);
    if (!request.steps) request.steps = l.steps;
    try {
        exportModel(l.model, Destination::file(output_), request);
    } catch (...) {
        if (shown) std::cerr << '\n';
        throw;
    }
    if (shown) std::cerr << '\n';
    endProgressLine();
    return 0;
}

}  // namespace graftal::cli
