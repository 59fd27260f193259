// animate(): a model's development as frames. Every step is derived once; the pictures of
// all frames are made first (scenes for line art, meshes for ray tracing), so that the one
// camera can be framed on all of them together, and then drawn in order.
#include "graftal/pipeline/animation.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <string>

#include "graftal/core/parallel.hpp"
#include "graftal/geometry/bspline.hpp"
#include "graftal/geometry/color_map.hpp"
#include "graftal/geometry/material_file.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/projection.hpp"
#include "graftal/output/derivation_diagram.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/render3d.hpp"
#include "graftal/pipeline/stages.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/turtle/turtle.hpp"
#include "module_ages.hpp"
#include "render_settings.hpp"

namespace graftal {

namespace {

Error requestError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

// One frame to draw: the string of `step` at `fraction` of the way to the next step.
struct FramePlan {
    int step = 0;
    int between = 0;  // fraction = between / framesPerStep
    double seconds = 0;
};

std::vector<FramePlan> planFrames(int from, int to, const AnimationRequest& r) {
    std::vector<FramePlan> plan;
    const double frameTime = 1.0 / r.fps;
    for (int s = from; s < to; ++s)
        for (int j = 0; j < r.framesPerStep; ++j) plan.push_back({s, j, frameTime});
    for (int k = 0; k < r.lastFrames; ++k) plan.push_back({to, 0, frameTime});
    plan.back().seconds += r.holdSeconds;
    return plan;
}

bool drawsNothing(const Scene& s) {
    return s.segments.empty() && s.polygonCount() == 0 && s.surfaces.empty() && s.discs.empty() &&
           s.spheres.empty();
}

// Turns every point of the scene about the vertical axis through `centre` (x, z): the 2D
// turntable, as if the camera walked around the plant.
Scene turnedScene(Scene scene, const Vec3& centre, double degrees) {
    if (degrees == 0) return scene;
    const double a = radians(degrees), c = std::cos(a), s = std::sin(a);
    auto point = [&](Vec3& p) {
        const double x = p.x - centre.x, z = p.z - centre.z;
        p.x = centre.x + c * x + s * z;
        p.z = centre.z - s * x + c * z;
    };
    auto direction = [&](Vec3& v) {
        const double x = v.x, z = v.z;
        v.x = c * x + s * z;
        v.z = -s * x + c * z;
    };
    for (Segment& g : scene.segments) {
        point(g.a);
        point(g.b);
        direction(g.up);
    }
    for (Vec3& p : scene.polygonVertices) point(p);
    for (SurfaceInstance& i : scene.surfaces) {
        point(i.origin);
        direction(i.heading);
        direction(i.left);
        direction(i.up);
    }
    for (Disc& d : scene.discs) {
        point(d.centre);
        direction(d.normal);
    }
    for (Sphere& p : scene.spheres) point(p.centre);
    scene.is3D = scene.is3D || a != 0;
    return scene;
}

// The box a set of boxes covers when seen from `view` (the projections are axis swaps and
// flips, so the corners of the box give the projected box exactly).
Bounds projectedBounds(const Bounds& b, std::optional<ViewDirection> view) {
    if (b.empty() || !view) return b;
    Scene corners;
    for (int k = 0; k < 8; ++k) {
        const Vec3 p{k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                     k & 4 ? b.max.z : b.min.z};
        corners.segments.push_back(Segment{p, p});
    }
    corners.is3D = true;
    return projectScene(corners, *view).bounds();
}

// The box every turn of the turntable stays inside: the vertical cylinder about `centre`
// through the farthest corner.
Bounds turntableBounds(const Bounds& b, const Vec3& centre) {
    if (b.empty()) return b;
    double radius = 0;
    for (int k = 0; k < 4; ++k) {
        const double x = (k & 1 ? b.max.x : b.min.x) - centre.x;
        const double z = (k & 2 ? b.max.z : b.min.z) - centre.z;
        radius = std::max(radius, std::hypot(x, z));
    }
    Bounds out;
    out.extend(Vec3{centre.x - radius, b.min.y, centre.z - radius});
    out.extend(Vec3{centre.x + radius, b.max.y, centre.z + radius});
    return out;
}

Vec3 rotatedAbout(const Vec3& p, const Vec3& centre, Vec3 axis, double degrees) {
    axis = unitOrZero(axis);
    const double a = radians(degrees);
    const Vec3 v = p - centre;
    return centre + v * std::cos(a) + cross(axis, v) * std::sin(a) +
           axis * (dot(axis, v) * (1 - std::cos(a)));
}

void addNote(AnimationResult& result, const AnimationRequest& request, const Model& model,
             std::string message) {
    Diagnostic d{Severity::Note, SourceLocation{model.lsystem.file, 0, 0}, std::move(message)};
    if (request.notify) request.notify(d);
    result.notes.push_back(std::move(d));
}

// The derivation diagram of all the steps drawn, laid out once so that every frame keeps
// its cells where the last one has them; rows are numbered by their derivation step.
DerivationDiagram animatedDiagram(const Model& model, const AnimationRequest& request,
                                  const std::vector<ModuleString>& strings) {
    RenderOptions o = request.picture;
    if (request.background)
        o.background = *request.background;
    else if (model.view.camera.background)
        o.background = *model.view.camera.background;
    DerivationDiagram d = layoutDerivationDiagram(strings, model.lsystem.symbols, o);
    for (DiagramRow& row : d.rows) row.step += request.from;
    return d;
}

// The frame of `step`: the rows of the steps up to it.
DerivationDiagram diagramUpTo(const DerivationDiagram& all, int step) {
    DerivationDiagram d = all;
    std::erase_if(d.rows, [step](const DiagramRow& row) { return row.step > step; });
    return d;
}

// The sequence as it is made: the strings, then the scenes of every distinct frame.
class Sequence {
  public:
    Sequence(const Model& model, const AnimationRequest& request, int from, int to)
        : model_(model), request_(request), from_(from), ages_(moduleAges(model)) {
        const DerivationOptions options = derivationOptions(model, request);
        Derivation derivation(model, options);
        for (int s = 0; s <= to; ++s) {
            if (s > 0) derivation.step();
            if (s >= from) strings_.push_back(derivation.current());
        }
        derivation.finish();
    }

    bool continuous() const { return !ages_.empty(); }
    const std::vector<ModuleString>& strings() const { return strings_; }

    // The scene of `step` at `fraction` of the way to the next one, drawn as render() draws
    // a step (the pipeline's drawn()).
    Scene scene(int step, double fraction) const {
        const ModuleString& modules = strings_[std::size_t(step - from_)];
        const DerivationOptions options = derivationOptions(model_, request_);
        if (fraction > 0 && continuous())
            return drawn(
                model_,
                applyHomomorphism(model_.lsystem, agedString(modules, ages_, fraction), options),
                request_);
        return drawn(model_, applyHomomorphism(model_.lsystem, modules, options), request_);
    }

  private:
    const Model& model_;
    const AnimationRequest& request_;
    int from_;
    std::vector<ModuleAge> ages_;
    std::vector<ModuleString> strings_;
};

}  // namespace

void checkAnimationRequest(const AnimationRequest& r) {
    if (r.from < 0)
        throw requestError("--from " + std::to_string(r.from) + ": expected a step from 0");
    if (r.to && *r.to < 0)
        throw requestError("--to " + std::to_string(*r.to) + ": expected a step from 0");
    if (r.to && r.from > *r.to)
        throw requestError("--from " + std::to_string(r.from) + " is after --to " +
                           std::to_string(*r.to) +
                           ": the first step drawn must not come after the last");
    if (!(r.fps > 0) || r.fps > 1000) throw requestError("--fps must be above 0 and at most 1000");
    if (!(r.holdSeconds >= 0) || r.holdSeconds > 3600)
        throw requestError("--hold must be from 0 to 3600 seconds");
    if (r.framesPerStep < 1 || r.framesPerStep > 1000)
        throw requestError("--frames-per-step must be from 1 to 1000");
    if (r.lastFrames < 1 || r.lastFrames > 100000)
        throw requestError("--frames must be from 1 to 100000");
    if (!std::isfinite(r.turntableDegrees))
        throw requestError("--turntable must be a number of degrees");
    if (r.picture.width < 1 || r.picture.height < 1 || r.picture.width > 16384 ||
        r.picture.height > 16384)
        throw requestError("--size must be from 1x1 to 16384x16384 for an animation");
    if (r.derivationDiagram && r.turntableDegrees != 0)
        throw requestError("a derivation diagram does not turn: leave out --turntable");
    if (r.stream == StreamPolicy::Always)
        throw requestError("an animation needs every step's string; it cannot stream");
    if (!r.output.empty()) {
        const auto format = animationFormatFor(r.output);
        if (!format)
            throw requestError("-o " + r.output.string() + ": unknown animation format (use " +
                               animationFormatList() + ")");
    }
}

AnimationResult animate(const Model& model, const AnimationRequest& request,
                        const std::function<void(const AnimationFrame&)>& deliver) {
    checkAnimationRequest(request);
    AnimationResult result;
    result.from = request.from;
    result.to = request.to ? *request.to : requestedSteps(model, request);
    if (result.from > result.to)
        throw requestError("--from " + std::to_string(result.from) + " is after the last step, " +
                           std::to_string(result.to) + " (the derivation length; set --to)");
    const std::vector<FramePlan> plan = planFrames(result.from, result.to, request);
    result.frames = int(plan.size());

    request.cancel.check();
    const Sequence sequence(model, request, result.from, result.to);
    result.continuous = sequence.continuous() && request.framesPerStep > 1;
    if (request.framesPerStep > 1 && !sequence.continuous() && result.to > result.from)
        addNote(result, request, model,
                "the model declares no module ages (age: in the .l file), so the " +
                    std::to_string(request.framesPerStep - 1) + " frames between steps " +
                    (request.turntableDegrees != 0 ? "show the camera's motion only"
                                                   : "repeat each step's picture"));

    // Every distinct picture, made once: keyed by (step, between).
    const int K = request.framesPerStep;
    auto key = [&](const FramePlan& f) {
        return std::size_t(f.step - result.from) * K + (result.continuous ? f.between : 0);
    };
    std::vector<std::optional<Scene>> scenes(std::size_t(result.to - result.from + 1) * K);
    bool threeD = false, anything = false;
    for (const FramePlan& f : plan) {
        auto& slot = scenes[key(f)];
        if (slot) continue;
        request.cancel.check();
        slot = sequence.scene(f.step, result.continuous ? double(f.between) / K : 0.0);
        threeD = threeD || slot->is3D;
        anything = anything || !drawsNothing(*slot);
    }
    if (!anything && !request.derivationDiagram) {
        if (request.turntableDegrees != 0)
            throw Error(SourceLocation{model.lsystem.file, 0, 0},
                        "the string draws nothing at any step, and its derivation diagram does "
                        "not turn: leave out --turntable");
        addNote(result, request, model,
                "the string draws nothing; animating its derivation instead (a row more each "
                "step)");
    }
    if (!anything || request.derivationDiagram) {
        result.route = RenderRoute::DerivationDiagram;
        const DerivationDiagram diagram = animatedDiagram(model, request, sequence.strings());
        const int total = result.frames;
        std::vector<std::optional<RgbaImage>> images(std::size_t(result.to - result.from + 1));
        for (std::size_t index = 0; index < plan.size(); ++index) {
            request.cancel.check();
            const FramePlan& f = plan[index];
            auto& image = images[std::size_t(f.step - result.from)];
            if (!image) image = drawDerivationDiagram(diagramUpTo(diagram, f.step));
            AnimationFrame frame;
            frame.index = int(index);
            frame.step = f.step;
            frame.age = f.step;
            frame.seconds = f.seconds;
            frame.image = *image;
            deliver(frame);
            if (request.frameProgress) request.frameProgress(int(index) + 1, total);
        }
        return result;
    }
    const bool rayTraced = threeD && !request.view;
    result.route = rayTraced ? RenderRoute::RayTraced : RenderRoute::LineArt;
    const int total = result.frames;
    int done = 0;
    auto handOver = [&](const FramePlan& f, int index, RgbaImage image) {
        AnimationFrame frame;
        frame.index = index;
        frame.step = f.step;
        frame.age = f.step + double(f.between) / K;
        frame.seconds = f.seconds;
        frame.image = std::move(image);
        deliver(frame);
        ++done;
        if (request.frameProgress) request.frameProgress(done, total);
    };

    if (!rayTraced) {
        // Line art: the scenes as seen (projected when 3D), the frame their union, one line
        // width for all (that of the largest picture, so lines do not thin as it grows).
        // Discs and spheres (a kolam's dots) are drawn as their projected outlines, as
        // render() draws them.
        const bool roundShapes = std::any_of(scenes.begin(), scenes.end(), [](const auto& s) {
            return s && (!s->discs.empty() || !s->spheres.empty());
        });
        std::optional<ViewDirection> view;
        if (threeD || request.turntableDegrees != 0 || roundShapes)
            view = request.view.value_or(ViewDirection::Front);
        Bounds all;
        for (const auto& s : scenes)
            if (s) all.extend(s->bounds());
        const Vec3 centre = all.empty() ? Vec3{} : (all.min + all.max) * 0.5;
        const Bounds turning = request.turntableDegrees != 0 ? turntableBounds(all, centre) : all;
        result.frame = projectedBounds(turning, view);
        RenderOptions options = lineArtOptions(model, request);
        if (options.lineWidth <= 0) {
            const Scene& last = *scenes[key(plan.back())];
            const Scene seen = view ? projectScene(last, *view) : last;
            double ink = 0;
            for (const Segment& s : seen.segments) ink += inkLength(s, seen.baseWidth);
            options.lineWidth =
                defaultLineWidth(ink, !seen.segments.empty(), result.frame, options);
        }
        auto draw = [&](std::size_t index) {
            const FramePlan& f = plan[index];
            const Scene& scene = *scenes[key(f)];
            const double degrees = request.turntableDegrees * double(index);
            if (!view) return drawLineArt(scene, options, result.frame);
            return drawLineArt(projectScene(turnedScene(scene, centre, degrees), *view), options,
                               result.frame);
        };
        // Frames are drawn in parallel, a batch of one per thread, and handed over in order.
        const unsigned threads = request.threads ? request.threads : defaultThreadCount();
        for (std::size_t begin = 0; begin < plan.size(); begin += threads) {
            request.cancel.check();
            const std::size_t end = std::min(plan.size(), begin + threads);
            std::vector<std::future<RgbaImage>> batch;
            for (std::size_t i = begin + 1; i < end; ++i)
                batch.push_back(std::async(std::launch::async, draw, i));
            RgbaImage first = draw(begin);
            handOver(plan[begin], int(begin), std::move(first));
            for (std::size_t i = begin + 1; i < end; ++i) {
                request.cancel.check();
                handOver(plan[i], int(i), batch[i - begin - 1].get());
            }
        }
        return result;
    }

    // Ray tracing: meshes of every distinct picture, the camera framed on all of them.
    RaytraceOptions options = raytraceOptions(model.view, request);
    Bounds sceneBounds;
    for (const auto& s : scenes)
        if (s) sceneBounds.extend(s->bounds());
    MeshSetup setup = meshSetup(model, request, MeshPurpose::Picture);
    // Thin stems as in render(), for the pixel size of the camera framed on every frame.
    setPictureRadii(setup.options, sceneBounds, options);
    std::vector<Diagnostic> meshNotes;
    std::vector<std::optional<MeshScene>> meshes(scenes.size());
    std::vector<const MeshScene*> shown;
    Bounds all;
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        if (!scenes[k]) continue;
        request.cancel.check();
        meshes[k] = meshed(model, std::move(*scenes[k]), setup, meshNotes);
        scenes[k] = Scene{};
        all.extend(meshes[k]->bounds());
        shown.push_back(&*meshes[k]);
    }
    // Each frame's warnings (an undeclared surface) are said once.
    for (Diagnostic& d : meshNotes)
        if (std::none_of(result.notes.begin(), result.notes.end(),
                         [&](const Diagnostic& n) { return n.message == d.message; })) {
            if (request.notify) request.notify(d);
            result.notes.push_back(std::move(d));
        }
    result.frame = all;
    Camera camera;
    if (request.turntableDegrees != 0 && !all.empty()) {
        // The camera turns about its target: the box the turning plant sweeps is framed
        // around the plant's centre, so that every turn stays in the picture.
        Camera turning = options.camera;
        if (!turning.target) turning.target = (all.min + all.max) * 0.5;
        camera = framedCamera(turning, turntableBounds(all, *turning.target), request.picture.width,
                              request.picture.height);
    } else {
        camera = framedCamera(options.camera, shown, request.picture.width, request.picture.height);
    }
    for (std::size_t index = 0; index < plan.size(); ++index) {
        request.cancel.check();
        const FramePlan& f = plan[index];
        RaytraceOptions o = options;
        o.camera = camera;
        if (request.turntableDegrees != 0)
            o.camera.viewpoint = rotatedAbout(*camera.viewpoint, *camera.target, camera.up,
                                              request.turntableDegrees * double(index));
        handOver(f, int(index),
                 RgbaImage::fromRgb(renderRaytracedPixels(*meshes[key(f)], o), o.width, o.height));
    }
    return result;
}

std::vector<AnimationFrame> animationFrames(const Model& model, const AnimationRequest& request,
                                            AnimationResult* result) {
    std::vector<AnimationFrame> frames;
    AnimationResult r =
        animate(model, request, [&](const AnimationFrame& f) { frames.push_back(f); });
    if (result) *result = std::move(r);
    return frames;
}

AnimationResult writeAnimationFile(const Model& model, const AnimationRequest& request) {
    checkAnimationRequest(request);
    if (request.output.empty()) throw requestError("an animation needs an output (-o)");
    return writeAnimationTo(model, request, *animationFormatFor(request.output),
                            Destination::file(request.output));
}

AnimationResult writeAnimationTo(const Model& model, const AnimationRequest& request,
                                 AnimationFormat format, const Destination& destination) {
    checkAnimationRequest(request);
    AnimationEncoding encoding;
    encoding.width = request.picture.width;
    encoding.height = request.picture.height;
    encoding.fps = request.fps;
    encoding.globalPalette = request.globalPalette;
    encoding.dither = request.dither;
    AnimationResult result;
    writeAnimation(destination, format, encoding, [&](AnimationEncoder& encoder) {
        result = animate(model, request, [&](const AnimationFrame& frame) {
            encoder.add(frame.image, frame.seconds);
        });
    });
    return result;
}

}  // namespace graftal
