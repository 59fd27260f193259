// A model's development as a sequence of frames: every derivation step derived once, drawn
// by one fixed camera framed on all the frames together, so the plant grows in place. 2D
// models are line art, 3D models ray traced as `graftal render` draws them. The frames come
// one by one to a callback (a player shows them as they come) or all at once, and
// writeAnimationFile() encodes them as GIF, WebP, MP4 or a folder of PNG frames.
//
// Continuous development: a model that declares the ages of its modules (`age: I(i)` in
// the .l file, docs/language.md) is drawn at fractional ages between steps when more
// than one frame per step is asked for; the strings stay the L-system's own.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "graftal/lang/model.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/pipeline/pipeline.hpp"

namespace graftal {

// RenderRequest's picture, camera and derivation settings, with the sequence's own. The
// output, when set, names the file for writeAnimationFile(); derivationDiagram and
// stream = Always do not apply (a sequence needs every step's string).
struct AnimationRequest : RenderRequest {
    int from = 0;                 // first step drawn
    std::optional<int> to;        // last step drawn; empty: `steps`, else the file's length
    int framesPerStep = 1;        // frames from one step to the next (ages in between)
    int lastFrames = 1;           // frames of the last step (the turntable keeps turning)
    double turntableDegrees = 0;  // the camera turns by this about the up axis per frame
    double fps = 10;
    double holdSeconds = 0;      // added to the last frame's time on screen
    bool globalPalette = false;  // GIF: one palette for all frames
    bool dither = false;         // GIF: error diffusion when a frame has over 256 colours
    // Called after every frame drawn, with the frame count so far and in all.
    std::function<void(int done, int total)> frameProgress;
};

struct AnimationFrame {
    int index = 0;       // from 0
    int step = 0;        // the derivation step whose string is drawn
    double age = 0;      // the time drawn, in steps: step + the fraction between steps
    double seconds = 0;  // time on screen
    RgbaImage image;
};

struct AnimationResult {
    int from = 0, to = 0;
    int frames = 0;
    RenderRoute route = RenderRoute::LineArt;  // LineArt or RayTraced
    bool continuous = false;                   // in-between frames drawn at fractional ages
    Bounds frame;                              // the region the fixed camera frames (model units)
    std::vector<Diagnostic> notes;
};

// The option checks that need no derivation (steps, rates, sizes; the output's format when
// an output is set). Throws Error.
void checkAnimationRequest(const AnimationRequest& request);

// Derives and draws the frames in order, handing each to `frame`. Throws Error (Cancelled
// when request.cancel is raised, checked between frames).
AnimationResult animate(const Model& model, const AnimationRequest& request,
                        const std::function<void(const AnimationFrame&)>& frame);

// Every frame in memory.
std::vector<AnimationFrame> animationFrames(const Model& model, const AnimationRequest& request,
                                            AnimationResult* result = nullptr);

// Encodes the frames into request.output by its name (.gif .webp .mp4, or a folder of
// PNG frames), atomically: on an error or when cancelled no partial output is left.
AnimationResult writeAnimationFile(const Model& model, const AnimationRequest& request);
// The same in `format` to a file, a stream or memory (request.output is not read).
AnimationResult writeAnimationTo(const Model& model, const AnimationRequest& request,
                                 AnimationFormat format, const Destination& destination);

}  // namespace graftal
