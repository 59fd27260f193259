// A curve read as a score (LSFP ch. 6.3): horizontal runs are notes, heights are pitches.
#include <cmath>
#include <sstream>

#include "graftal/core/diagnostics.hpp"
#include "graftal/music/music.hpp"
#include "graftal/turtle/turtle.hpp"

namespace graftal {

namespace {

Error musicError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

std::string formatPoint(double x, double y) {
    std::ostringstream os;
    os << "(" << x << ", " << y << ")";
    return os.str();
}

void checkOptions(const MusicOptions& o) {
    if (o.scale.empty() || o.scale.front() != 0)
        throw musicError("the scale must start at 0, its root");
    for (std::size_t i = 0; i < o.scale.size(); ++i) {
        if (o.scale[i] < 0 || o.scale[i] > 11)
            throw musicError("scale offset " + std::to_string(o.scale[i]) +
                             " is outside one octave (expected 0 to 11)");
        if (i > 0 && o.scale[i] <= o.scale[i - 1])
            throw musicError("the scale must be increasing, but " + std::to_string(o.scale[i]) +
                             " follows " + std::to_string(o.scale[i - 1]));
    }
    if (o.root < 0 || o.root > 127)
        throw musicError("the root " + std::to_string(o.root) +
                         " is outside MIDI's notes 0 to 127");
    // A MIDI file holds a beat of at most 2^24 microseconds: 3.6 beats per minute.
    if (!(o.tempo >= 4 && o.tempo <= 1000)) {
        std::ostringstream got;
        got << o.tempo;
        throw musicError(
            "the tempo is beats per minute, from 4 (the slowest a MIDI file holds) "
            "to 1000, got " +
            got.str());
    }
    if (o.instrument < 1 || o.instrument > 128)
        throw musicError("the instrument is a General MIDI program from 1 to 128, got " +
                         std::to_string(o.instrument));
    if (!(o.unit > 0) || o.unit > 64)
        throw musicError("the unit is the beats of one step, above 0 and at most 64");
    if (o.velocity < 1 || o.velocity > 127) throw musicError("the velocity is from 1 to 127");
}

// The pitch `degree` steps of the scale above the root (below when negative).
long pitchOfDegree(const MusicOptions& o, long degree) {
    const long n = static_cast<long>(o.scale.size());
    long octave = degree >= 0 ? degree / n : -((-degree + n - 1) / n);
    long index = degree - octave * n;
    return o.root + 12 * octave + o.scale[static_cast<std::size_t>(index)];
}

}  // namespace

double Score::beats() const {
    double end = 0;
    for (const Note& n : notes) end = std::max(end, n.start + n.duration);
    return end;
}

double Score::seconds() const {
    return beats() * 60.0 / tempo;
}

MusicOptions musicOptions(const ViewSettings& view) {
    MusicOptions o;
    const MusicSettings& m = view.music;
    if (m.scale) o.scale = *m.scale;
    if (m.root) o.root = *m.root;
    if (m.tempo) o.tempo = *m.tempo;
    if (m.instrument) o.instrument = *m.instrument;
    if (m.pitchFromX) o.pitchFromX = *m.pitchFromX;
    if (m.unit) o.unit = *m.unit;
    return o;
}

Score scoreFromScene(const Scene& scene, double stepLength, const MusicOptions& options) {
    checkOptions(options);
    if (!(stepLength > 0)) throw musicError("the step length must be positive");
    Score score;
    score.tempo = options.tempo;
    score.instrument = options.instrument;

    const double eps = 1e-6 * stepLength;
    // time: the coordinate that advances the music; height: the one that picks the pitch.
    auto timeOf = [&](const Vec3& p) { return options.pitchFromX ? p.y : p.x; };
    auto heightOf = [&](const Vec3& p) { return options.pitchFromX ? p.x : p.y; };

    bool haveReference = false;
    double reference = 0;  // the height of the first note: the root
    bool inRun = false;    // the previous segment was horizontal and continues here
    double runHeight = 0;
    Vec3 lastEnd{};
    double clock = 0;
    for (const Segment& s : scene.segments) {
        double dt = std::abs(timeOf(s.b) - timeOf(s.a));
        double dh = std::abs(heightOf(s.b) - heightOf(s.a));
        if (dt <= eps && dh <= eps) continue;  // a point: neither time nor pitch
        bool connected =
            inRun && std::abs(s.a.x - lastEnd.x) <= eps && std::abs(s.a.y - lastEnd.y) <= eps;
        lastEnd = s.b;
        if (dh > eps) {  // vertical (or slanted): changes the pitch, takes no time
            inRun = false;
            continue;
        }
        double height = heightOf(s.a);
        // The turtle's sines and cosines leave lengths like 0.9999999999999999 steps; beats
        // are kept to a billionth so that a score of whole steps adds up exactly.
        double beats = std::round(dt / stepLength * options.unit * 1e9) / 1e9;
        if (connected && std::abs(height - runHeight) <= eps) {
            score.notes.back().duration += beats;
        } else {
            if (!haveReference) {
                haveReference = true;
                reference = height;
            }
            long degree = std::lround((height - reference) / stepLength);
            long pitch = pitchOfDegree(options, degree);
            if (pitch < 0 || pitch > 127)
                throw musicError(
                    "note " + std::to_string(score.notes.size() + 1) + " at " +
                    formatPoint(s.a.x, s.a.y) + " is " + std::to_string(degree) +
                    (std::abs(degree) == 1 ? " scale step" : " scale steps") +
                    " from the first note: MIDI pitch " + std::to_string(pitch) +
                    ", outside MIDI's range 0 to 127 (expected a smaller curve, a lower "
                    "derivation length, another root or a scale with more notes per octave)");
            score.notes.push_back(Note{static_cast<int>(pitch), clock, beats, options.velocity});
        }
        clock += beats;
        inRun = true;
        runHeight = height;
    }
    if (score.notes.empty())
        throw musicError(
            std::string("the curve has no ") + (options.pitchFromX ? "vertical" : "horizontal") +
            " segments, so it has no notes (fractal music plays the " +
            (options.pitchFromX ? "vertical" : "horizontal") + " runs of a curve drawn with F" +
            (options.pitchFromX ? "" : "; try --axis x") + ")");
    return score;
}

Score scoreFromModel(const Model& model, int steps, const MusicOptions& options,
                     DerivationOptions derivation) {
    if (!derivation.queryResolver) derivation.queryResolver = turtleQueryResolver(model.view);
    ModuleString modules = derive(model, steps, derivation);
    Scene scene = interpret(model, applyHomomorphism(model.lsystem, modules, derivation));
    if (scene.is3D)
        throw Error(SourceLocation{model.lsystem.file, 0, 0},
                    "the curve leaves the plane; fractal music reads 2D curves");
    try {
        Score score = scoreFromScene(scene, model.view.turtle.stepLength, options);
        score.title = std::filesystem::path(model.lsystem.file).stem().string();
        return score;
    } catch (const Error& e) {
        throw Error(SourceLocation{model.lsystem.file, 0, 0}, e.messages());
    }
}

}  // namespace graftal
