// The turtle as a machine over a geometry sink: it walks modules one at a time and hands
// segments, polygons and surfaces to the sink, which may store them (a Scene), draw them
// straight into an image, or drop them (walking only, for query modules). One definition
// serves every use; the sink is a template parameter so the per-segment call inlines.
//
// Orientation is the frame H, L, U (heading, left, up; H x L = U). Each rotation turns one
// vector of the frame toward another, which is how LSFP ch. 2 describes them: + turns H
// toward L (left), & pitches H toward -U (down). The rolls follow cpfg: / turns L toward
// -U and \ toward U (cpfg calls -U its up vector, so / rolls L toward cpfg's up); pfg data
// files keep the book's names, \ rolling L toward -U. The book's printed matrices R_U,
// R_L, R_H are applied as [H L U] R^T.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "generalized_cylinder_track.hpp"
#include "graftal/core/bit_cast.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"

namespace graftal::turtle {

enum class TurtleOp : std::uint8_t {
    None,
    Forward,
    Move,
    ForwardNoVertex,
    MoveNoVertex,
    RecordVertex,
    TurnLeft,
    TurnRight,
    PitchDown,
    PitchUp,
    RollLeft,
    RollRight,
    TurnAround,
    RollToVertical,
    AtPrefix,  // @: the next module is an @-command (@v, @M, @R, @o, @c, @O, ...)
    Push,
    Pop,
    PolygonBegin,
    PolygonEnd,
    WidthDown,
    WidthUp,
    ColorNext,
    ColorPrevious,
    SurfacePrefix,  // ~: the next module names the surface (~l(0.5), ~leaf(2))
    Elasticity,     // cpfg's _: adds the elasticity increment, or _(e) sets the elasticity
};

// Turns between two Gram-Schmidt passes over the frame. It changes the doubles of every
// later step, so every walk that must agree with this one counts turns the same way.
inline constexpr std::uint64_t kOrthonormaliseEvery = 4096;

inline TurtleOp opFor(Symbol s) {
    switch (s) {
        case 'F':
            return TurtleOp::Forward;
        case 'f':
            return TurtleOp::Move;
        case 'G':
            return TurtleOp::ForwardNoVertex;
        case 'g':
            return TurtleOp::MoveNoVertex;
        case '.':
            return TurtleOp::RecordVertex;
        case '+':
            return TurtleOp::TurnLeft;
        case '-':
            return TurtleOp::TurnRight;
        case '&':
            return TurtleOp::PitchDown;
        case '^':
            return TurtleOp::PitchUp;
        case '\\':
            return TurtleOp::RollLeft;
        case '/':
            return TurtleOp::RollRight;
        case '|':
            return TurtleOp::TurnAround;
        // '$' ends a sub-L-system in cpfg, which graftal does not have: not a turtle symbol
        // (pfg data files keep the book's $, see opTable()).
        case '@':
            return TurtleOp::AtPrefix;
        case '~':
            return TurtleOp::SurfacePrefix;
        case '[':
            return TurtleOp::Push;
        case ']':
            return TurtleOp::Pop;
        case '{':
            return TurtleOp::PolygonBegin;
        case '}':
            return TurtleOp::PolygonEnd;
        case '!':
            return TurtleOp::WidthDown;
        case '#':
            return TurtleOp::WidthUp;
        case '\'':
        case ';':
            return TurtleOp::ColorNext;
        case ',':
            return TurtleOp::ColorPrevious;
        case '_':
            return TurtleOp::Elasticity;
        default:
            return TurtleOp::None;
    }
}

// What symbol `s` of `ls` does to the turtle: the one place that says it. The three walks
// (this machine, the planar walk of planar_measure.cpp and the subtree summaries) all
// switch on these operations; the planar walk keeps a switch of its own rather than
// calling into the machine, because a call in its loop would make it slower (see there).
// Characters get opFor() and in a pfg data file the book's $ rolls until L is horizontal.
inline TurtleOp opOf(const LSystem& ls, Symbol s) {
    if (s >= ls.symbols.size()) return TurtleOp::None;
    if (s == '$' && ls.legacyPfg) return TurtleOp::RollToVertical;
    return opFor(s);
}

inline std::array<TurtleOp, kMaxSymbols> opTable(const LSystem& ls) {
    std::array<TurtleOp, kMaxSymbols> ops{};
    for (std::size_t s = 0; s < ops.size(); ++s) ops[s] = opOf(ls, static_cast<Symbol>(s));
    return ops;
}

// Rotates v about the unit axis k by `radians` (Rodrigues).
inline Vec3 rotateAbout(Vec3 v, Vec3 k, double radians) {
    double c = std::cos(radians), s = std::sin(radians);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

struct TurtleState {
    Vec3 position;
    Vec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, 1};  // H x L = U
    float width = 1;
    std::uint16_t color = 0;
    std::uint32_t lastSegment = kNoSegment;  // the axis a new segment continues
    // The elasticity of the `tropism direction:` tropism; a branch keeps its own (cpfg).
    double elasticity = 0;
};

// a' = a cos + b sin, b' = b cos - a sin: turns a toward b.
inline void rotatePair(Vec3& a, Vec3& b, double c, double s) {
    Vec3 na = a * c + b * s;
    Vec3 nb = b * c + a * (-s);
    a = na;
    b = nb;
}

using Visitor = std::function<void(std::size_t, const TurtleFrame&)>;

// A Sink provides:
//   std::uint32_t segment(const Segment&)   -> the index later segments link to
//   void polygon(std::span<const Vec3>, std::uint16_t color)
//   void surface(const std::string& name, const SurfaceInstance&)
//   void disc(const Disc&), void sphere(const Sphere&)
//   void baseWidth(float), void finish(bool is3D)
template <class Sink>
class TurtleMachine {
  public:
    TurtleMachine(const Model& model, Sink& sink)
        : TurtleMachine(model.lsystem, model.view, sink) {}
    TurtleMachine(const LSystem& ls, const ViewSettings& view, Sink& sink)
        : ls_(ls),
          view_(view),
          sink_(sink),
          ops_(opTable(ls)),
          cylinders_(view.materials.contours, view.materials.contourSides) {
        const ViewSettings& v = view_;
        double delta = radians(v.turtle.angleDegrees);
        deltaCos_ = std::cos(delta);
        deltaSin_ = std::sin(delta);
        turnSign_ = v.turtle.clockwisePlus ? -1.0 : 1.0;
        // cpfg's / rolls L toward -U (its up vector is our -U); pfg data files keep the
        // book's / (L toward U).
        rollSign_ = v.turtle.clockwisePlus ? 1.0 : -1.0;
        double h = radians(v.turtle.initialHeading);
        rotatePair(state_.heading, state_.left, std::cos(h), std::sin(h));
        state_.width = static_cast<float>(v.turtle.initialWidth);
        state_.color = colorIndex(v.turtle.initialColor);
        // Elasticity is the turtle's: `_` changes it as the string is read (cpfg).
        if (v.turtle.tropism) {
            tropism_ = *v.turtle.tropism;
            state_.elasticity = v.turtle.elasticity;
            hasTropism_ = true;
        }
        // cpfg's movements before every move: the tropisms' sum and the torque.
        for (const auto& m : v.turtle.tropisms)
            movementTropism_ = movementTropism_ + m.direction * m.elasticity;
        hasMovementTropism_ = length(movementTropism_) > 0;
        if (v.turtle.torque) torque_ = *v.turtle.torque * v.turtle.torqueElasticity;
        for (const auto& m : v.turtle.torques) torque_ = torque_ + m.direction * m.elasticity;
        hasTorque_ = length(torque_) > 0;
        sink_.baseWidth(state_.width);
    }

    void run(const ModuleString& m, const std::vector<bool>* wanted = nullptr,
             const Visitor* visit = nullptr) {
        std::span<const Symbol> syms = m.symbols();
        bool params = m.hasParameters();
        for (std::size_t i = 0; i < syms.size(); ++i) {
            if (wanted && syms[i] < wanted->size() && (*wanted)[syms[i]])
                (*visit)(i, TurtleFrame{state_.position, state_.heading, state_.left, state_.up});
            module(syms[i], params ? m.params(i).doubles(scratch_) : std::span<const double>{}, i);
        }
        finish();
    }

    // One module of a string that arrives piece by piece (streamed derivations).
    void module(Symbol s, std::span<const double> args, std::size_t index) {
        if (atPending_) {
            atPending_ = false;
            atCommand(s, args);
            return;
        }
        if (cylinderPending_) {  // the module after @G says what it does
            cylinderPending_ = false;
            cylinderCommand(s, args);
            return;
        }
        TurtleOp op = ops_[s];
        if (surfacePending_) {  // the module after ~ names the surface
            surfacePending_ = false;
            // cpfg takes any module after ~ as a surface's name; a turtle command there
            // (a lone ~ before [ or /) still does what it says, and ~ alone draws nothing.
            if (op == TurtleOp::None) {
                placeSurface(s, args);
                return;
            }
        }
        if (op != TurtleOp::None) apply(op, args, index);
    }

    // The last module was @, @G or ~, which the next module completes: a walk that jumps
    // over subtrees must hand it that module (subtree_summaries.cpp).
    bool prefixPending() const { return atPending_ || cylinderPending_ || surfacePending_; }

    // Collects cpfg's view volume (the `box` of its output) from here on; see viewVolume().
    void trackViewVolume() { tracking_ = true; }
    // cpfg's view volume: the turtle's position wherever cpfg ends a segment (before every
    // move, at [ and before ] restores, at { } ~ and @, at the end), where @M lands, the
    // square of @o (at z = 0) and @c, the cube of @O. Line widths do not count.
    const Bounds& viewVolume() const { return viewVolume_; }

    // The state itself, for a walk that jumps over subtrees whose motion it knows
    // (subtree_summaries.hpp).
    TurtleState& state() { return state_; }

    void finish() {
        note(state_.position);
        if (!polygons_.empty())
            throw Error(SourceLocation{ls_.file, 0, 0},
                        "the derived string leaves a '{' open (module " +
                            std::to_string(polygonOpenedAt_.back()) + "): expected a matching '}'");
        sink_.finish(is3D_);
    }

  private:
    // Turns a toward b by the angle argument, or by delta (cos and sin precomputed).
    void turn(Vec3& a, Vec3& b, std::span<const double> args, double sign) {
        if (args.empty()) {
            rotatePair(a, b, deltaCos_, sign * deltaSin_);
        } else {
            const AngleMemo& m = cosSin(args[0]);
            rotatePair(a, b, m.cos, sign * m.sin);
        }
        if (++rotations_ % kOrthonormaliseEvery == 0) orthonormalise();
    }

    // A plant turns by a few angles over and over (a divergence angle, a branching
    // angle): their cosines and sines are remembered, the same values std::cos and
    // std::sin give, so the turtle's path does not change.
    struct AngleMemo {
        double degrees = 0, cos = 1, sin = 0;
    };
    const AngleMemo& cosSin(double degrees) {
        for (const AngleMemo& m : angles_)
            if (bitCast<std::uint64_t>(m.degrees) == bitCast<std::uint64_t>(degrees))
                return m;
        const double r = radians(degrees);
        AngleMemo& m = angles_[nextAngle_++ % angles_.size()];
        m = {degrees, std::cos(r), std::sin(r)};
        return m;
    }

    // Rounding drifts the frame after very many rotations; Gram-Schmidt puts it back.
    void orthonormalise() {
        state_.heading = normalized(state_.heading);
        state_.left = normalized(state_.left - state_.heading * dot(state_.left, state_.heading));
        state_.up = cross(state_.heading, state_.left);
    }

    void mark3D() { is3D_ = true; }

    // LSFP ch. 3.1 and SIGGRAPH '88 §3: after each segment the heading bends toward T by
    // alpha = e |H x T| (away from T when e < 0), a torque-like heuristic.
    void applyTropism() {
        if (view_.turtle.cpfgTropism) {
            applyCpfgTropism();
            return;
        }
        if (state_.elasticity == 0) return;
        Vec3 axis = cross(state_.heading, tropism_);
        double n = length(axis);
        if (n < 1e-12) return;
        double alpha = state_.elasticity * n;
        axis = axis * (1 / n);
        state_.heading = normalized(rotateAbout(state_.heading, axis, alpha));
        state_.left = normalized(rotateAbout(state_.left, axis, alpha));
        state_.up = cross(state_.heading, state_.left);
    }

    // cpfg's tropism of a view file's `tropism direction:` line: H pitches toward T, then
    // turns toward it, each by the angle whose sine is e times T's share along U, then L.
    void applyCpfgTropism() {
        auto bend = [&](Vec3& toward, double sine) {
            sine = std::clamp(sine, -1.0, 1.0);
            rotatePair(state_.heading, toward, std::sqrt(1 - sine * sine), sine);
        };
        bend(state_.up, state_.elasticity * dot(tropism_, state_.up));
        bend(state_.left, state_.elasticity * dot(tropism_, state_.left));
    }

    // cpfg's movements, before every F, G, f and g: the `tropism:` lines turn H toward
    // their sum V by min(1, |H x V|) radians (the frame turns with it), then the torque
    // rolls the turtle about H, turning its up vector toward the torque's part across H.
    void applyMovements() {
        if (hasMovementTropism_) {
            Vec3 axis = cross(state_.heading, movementTropism_);
            double n = length(axis);
            if (n >= 1e-6) {
                double angle = std::min(n, 1.0);
                axis = axis * (1 / n);
                state_.heading = normalized(rotateAbout(state_.heading, axis, angle));
                state_.left = normalized(rotateAbout(state_.left, axis, angle));
                state_.up = cross(state_.heading, state_.left);
            }
        }
        if (hasTorque_) {
            double strength = length(torque_);
            Vec3 across = cross(state_.heading, torque_ * (1 / strength));
            if (dot(across, across) > 1e-8) {
                Vec3 wanted = cross(across, state_.heading) * strength;
                Vec3 axis = cross(state_.up, wanted);
                double n = length(axis);
                if (n >= 1e-7) {
                    state_.up =
                        normalized(rotateAbout(state_.up, axis * (1 / n), std::min(n, 1.0)));
                    state_.left = cross(state_.up, state_.heading);
                }
            }
        }
    }

    void note(const Vec3& p) {
        if (tracking_) viewVolume_.extend(p);
    }

    void forward(double length, bool draw, bool vertex) {
        note(state_.position);
        if (hasMovementTropism_ || hasTorque_) applyMovements();
        Vec3 from = state_.position;
        state_.position = from + state_.heading * length;
        // A plant is 3D when its geometry leaves the z = 0 plane, not merely because it
        // rolled: a roll by 180 degrees keeps a plant flat (up to rounding, hence the
        // tolerance relative to the step).
        if (!is3D_ && std::fabs(state_.position.z) > 1e-9 * (1 + std::fabs(length))) mark3D();
        if (!polygons_.empty()) {
            if (vertex) polygons_.back().push_back(state_.position);
        } else if (draw) {
            state_.lastSegment = sink_.segment(Segment{
                from, state_.position, state_.width, state_.color, state_.lastSegment, state_.up});
        } else {
            state_.lastSegment = kNoSegment;  // a move starts a new axis
        }
        if (draw && hasTropism_) applyTropism();
        // Inside cpfg's `{(n)` cylinders F and f set a control point where they end.
        if (vertex && cylinders_.movesSetPoints())
            cylinders_.moved(controlPointHere(), drawPiece());
    }

    double lengthArg(std::span<const double> args) const {
        return args.empty() ? view_.turtle.stepLength : args[0];
    }

    void apply(TurtleOp op, std::span<const double> args, std::size_t index) {
        switch (op) {
            case TurtleOp::None:
                break;
            case TurtleOp::Forward:
                forward(lengthArg(args), true, true);
                break;
            case TurtleOp::Move:
                forward(lengthArg(args), false, true);
                break;
            case TurtleOp::ForwardNoVertex:
                if (polygons_.empty())
                    forward(lengthArg(args), true, false);
                else
                    forward(lengthArg(args), false, false);
                break;
            case TurtleOp::MoveNoVertex:
                forward(lengthArg(args), false, false);
                break;
            case TurtleOp::RecordVertex:
                if (!polygons_.empty())
                    polygons_.back().push_back(state_.position);
                else
                    cylinders_.dot(args, controlPointHere(), drawPiece());
                break;
            case TurtleOp::TurnLeft:
                turn(state_.heading, state_.left, args, turnSign_);
                break;
            case TurtleOp::TurnRight:
                turn(state_.heading, state_.left, args, -turnSign_);
                break;
            case TurtleOp::TurnAround:
                state_.heading = state_.heading * -1.0;
                state_.left = state_.left * -1.0;
                break;
            case TurtleOp::PitchDown:
                turn(state_.heading, state_.up, args, -1);
                break;
            case TurtleOp::PitchUp:
                turn(state_.heading, state_.up, args, 1);
                break;
            case TurtleOp::RollLeft:
                turn(state_.left, state_.up, args, -rollSign_);
                break;
            case TurtleOp::RollRight:
                turn(state_.left, state_.up, args, rollSign_);
                break;
            case TurtleOp::RollToVertical:
                rollToVertical();
                break;
            case TurtleOp::AtPrefix:
                note(state_.position);
                atPending_ = true;
                break;
            case TurtleOp::Push: {
                note(state_.position);
                stack_.push_back(state_);
                cylinders_.push();
                state_.lastSegment = kNoSegment;  // a branch is a new axis
                break;
            }
            case TurtleOp::Pop:
                if (stack_.empty())
                    throw Error(SourceLocation{ls_.file, 0, 0},
                                "']' at module " + std::to_string(index) +
                                    " of the derived string pops an empty turtle stack "
                                    "(more ']' than '[')");
                note(state_.position);
                state_ = stack_.back();
                stack_.pop_back();
                cylinders_.pop();
                break;
            case TurtleOp::PolygonBegin:
                note(state_.position);
                // `{(n)`, n not 0: cpfg's generalized cylinder (type n from 1 to 4; others
                // are ignored), not a polygon.
                if (!args.empty() && args[0] != 0) {
                    cylinders_.beginSpline(args);
                    break;
                }
                polygons_.emplace_back();
                polygons_.back().push_back(state_.position);
                polygonOpenedAt_.push_back(index);
                break;
            case TurtleOp::PolygonEnd:
                if (!args.empty() && args[0] != 0) {  // `}(n)` ends a `{(n)` cylinder
                    cylinders_.finishSpline(drawPiece());
                    break;
                }
                note(state_.position);
                if (polygons_.empty())
                    throw Error(SourceLocation{ls_.file, 0, 0},
                                "'}' at module " + std::to_string(index) +
                                    " of the derived string closes no polygon (no '{' is open)");
                if (polygons_.back().size() >= 3) sink_.polygon(polygons_.back(), state_.color);
                polygons_.pop_back();
                polygonOpenedAt_.pop_back();
                break;
            case TurtleOp::WidthDown:
                state_.width = args.empty() ? changedWidth(view_, state_.width, false)
                                            : static_cast<float>(args[0]);
                break;
            case TurtleOp::WidthUp:
                state_.width = args.empty() ? changedWidth(view_, state_.width, true)
                                            : static_cast<float>(args[0]);
                break;
            case TurtleOp::ColorNext:
                state_.color = args.empty() ? colorIndex(state_.color + view_.turtle.colorIncrement)
                                            : colorIndex(args[0]);
                break;
            case TurtleOp::Elasticity:
                state_.elasticity =
                    args.empty() ? state_.elasticity + view_.turtle.elasticityIncrement : args[0];
                break;
            case TurtleOp::ColorPrevious:
                if (!args.empty())
                    state_.color = colorIndex(args[0]);
                else
                    state_.color = colorIndex(state_.color - view_.turtle.colorIncrement);
                break;
            case TurtleOp::SurfacePrefix:
                note(state_.position);
                surfacePending_ = true;
                break;
        }
    }

    // A colour index given as a parameter, clamped to 0..65535 as cpfg clamps to its
    // colour map (not-a-number gives 0): a cast of an out-of-range double is undefined.
    static std::uint16_t colorIndex(double v) {
        if (!(v > 0)) return 0;
        if (v >= 65535) return 65535;
        return static_cast<std::uint16_t>(v);
    }

    // cpfg's @v (ABOP's $): roll about H so that L is horizontal (L = V x H / |V x H|,
    // V = world up).
    void rollToVertical() {
        Vec3 v{0, 1, 0};
        Vec3 l = cross(v, state_.heading);
        double n = length(l);
        if (n < 1e-12) return;  // heading vertical: any roll is as good
        state_.left = l * (1 / n);
        state_.up = cross(state_.heading, state_.left);
    }

    // The module after an @, as cpfg reads it. Its plain meaning never applies (@Gs is not
    // a G step); @-commands graftal does not draw are ignored.
    void atCommand(Symbol s, std::span<const double> args) {
        switch (s) {
            case 'v':
                rollToVertical();
                break;
            case 'M':
                moveTo(args);
                break;
            case 'R':
                setHeading(args);
                break;
            case 'o':
            case 'c':
            case 'O': {
                double d = args.empty() ? state_.width : args[0];
                if (tracking_) {
                    Vec3 p = state_.position, h{d / 2, d / 2, s == 'O' ? d / 2 : 0};
                    if (s == 'o') p.z = 0;
                    note(p - h);
                    note(p + h);
                }
                if (s == 'O') {
                    mark3D();
                    sink_.sphere(Sphere{state_.position, d / 2, state_.color});
                } else {
                    // @o faces the viewer (+z); @c lies in the turtle's plane, facing U.
                    Vec3 normal = s == 'o' ? Vec3{0, 0, 1} : state_.up;
                    if (s == 'c' && std::fabs(normal.z) < 1 - 1e-9) mark3D();
                    sink_.disc(Disc{state_.position, normal, d / 2, state_.color});
                }
                break;
            }
            case 'G':
                cylinderPending_ = true;
                break;
            case '#':
                cylinders_.selectContour(args);
                break;
            case '!':
                cylinders_.setSides(args);
                break;
            default:
                break;
        }
    }

    // @Gs, @Gc(n), @Ge(n), @Gt, @Gr: a control point here (and the piece it ends drawn) or
    // the tangents of the next ones.
    void cylinderCommand(Symbol sub, std::span<const double> args) {
        cylinders_.command(sub, args, controlPointHere(), drawPiece());
    }

    // A control point at the turtle, with what @G, @# and @! have set.
    CylinderControlPoint controlPointHere() const {
        CylinderControlPoint here = cylinders_.attributes();
        here.position = state_.position;
        here.heading = state_.heading;
        here.left = state_.left;
        here.up = state_.up;
        here.width = state_.width;
        here.color = state_.color;
        return here;
    }

    auto drawPiece() {
        return [this](const GeneralizedCylinderTrack::Piece& piece) { drawCylinderPiece(piece); };
    }

    // The centre line as segments (what every output draws), and for sinks that keep
    // surfaces the swept cross-sections.
    void drawCylinderPiece(const GeneralizedCylinderTrack::Piece& piece) {
        const std::vector<CylinderRing> rings = cylinderRings(
            piece.from, piece.to, piece.steps, piece.bspline ? &*piece.bspline : nullptr);
        if (rings.size() < 2) return;
        std::uint32_t first = kNoSegment, previous = kNoSegment;
        for (std::size_t k = 0; k + 1 < rings.size(); ++k) {
            const CylinderRing &a = rings[k], &b = rings[k + 1];
            if (!is3D_ && std::fabs(b.centre.z) > 1e-9 * (1 + length(b.centre - a.centre)))
                mark3D();
            previous =
                sink_.segment(Segment{a.centre, b.centre, static_cast<float>(a.radius + b.radius),
                                      piece.from.color, previous, a.up});
            if (k == 0) first = previous;
        }
        if constexpr (requires { sink_.sweptTube(SweptTube{}); }) {
            SweptTube tube =
                sweepRings(rings, cylinders_.contourPointsOf(piece.from.contour, piece.to.sides),
                           cylinders_.contourPointsOf(piece.to.contour, piece.to.sides),
                           cylinders_.closedContour(piece.from.contour) &&
                               cylinders_.closedContour(piece.to.contour),
                           piece.from.color);
            tube.firstSegment = first;
            tube.segmentCount = static_cast<std::uint32_t>(rings.size() - 1);
            sink_.sweptTube(std::move(tube));
        }
    }

    // @M(x, y[, z]): jump to a point without drawing, keeping the frame; z stays as it is
    // when not given.
    void moveTo(std::span<const double> args) {
        if (args.size() < 2) return;
        state_.position.x = args[0];
        state_.position.y = args[1];
        if (args.size() >= 3) state_.position.z = args[2];
        note(state_.position);
        if (!is3D_ && std::fabs(state_.position.z) > 1e-9) mark3D();
        state_.lastSegment = kNoSegment;  // a jump starts a new axis
    }

    // @R(hx, hy, hz): the heading becomes h (normalised) and L and U turn with it by the
    // rotation that takes the old heading to h (no twist about it). @R(hx, hy, hz, ux, uy,
    // uz) also sets the up vector, given as cpfg's (our -U), made perpendicular to h.
    void setHeading(std::span<const double> args) {
        if (args.size() < 3) return;
        Vec3 h = normalized(Vec3{args[0], args[1], args[2]});
        if (length(h) == 0) return;
        if (args.size() >= 6) {
            Vec3 cpfgUp{args[3], args[4], args[5]};
            Vec3 up = normalized((cpfgUp - h * dot(cpfgUp, h)) * -1.0);
            if (length(up) == 0) return;
            state_.heading = h;
            state_.up = up;
            state_.left = cross(up, h);  // H x L = U
        } else {
            Vec3 axis = cross(state_.heading, h);
            double s = length(axis), c = dot(state_.heading, h);
            if (s < 1e-12) {
                if (c < 0) {  // reversed: a half turn about U, as | does
                    state_.left = state_.left * -1.0;
                }
            } else {
                double angle = std::atan2(s, c);
                axis = axis * (1 / s);
                state_.left = normalized(rotateAbout(state_.left, axis, angle));
            }
            state_.heading = h;
            state_.up = cross(state_.heading, state_.left);
        }
    }

    void placeSurface(Symbol symbol, std::span<const double> args) {
        mark3D();
        SurfaceInstance s;
        s.origin = state_.position;
        s.heading = state_.heading;
        s.left = state_.left;
        s.up = state_.up;
        s.scale = args.empty() ? 1.0 : args[0];
        s.color = state_.color;
        sink_.surface(ls_.symbols.name(symbol), s);
    }

    const LSystem& ls_;
    const ViewSettings& view_;
    Sink& sink_;
    std::array<TurtleOp, kMaxSymbols> ops_;
    double deltaCos_ = 1, deltaSin_ = 0, turnSign_ = 1, rollSign_ = -1;
    Vec3 tropism_{0, -1, 0};
    bool hasTropism_ = false;
    bool tracking_ = false;
    Bounds viewVolume_;
    Vec3 movementTropism_{0, 0, 0};
    bool hasMovementTropism_ = false;
    Vec3 torque_{0, 0, 0};
    bool hasTorque_ = false;
    bool is3D_ = false;
    bool atPending_ = false;        // the last module was an @
    bool cylinderPending_ = false;  // the last modules were @G
    bool surfacePending_ = false;   // the last module was a ~
    GeneralizedCylinderTrack cylinders_;
    std::uint64_t rotations_ = 0;
    std::array<AngleMemo, 4> angles_{};
    std::size_t nextAngle_ = 0;
    TurtleState state_;
    std::vector<TurtleState> stack_;
    std::vector<double> scratch_;  // parameters of a string of floats, as doubles
    std::vector<std::vector<Vec3>> polygons_;
    std::vector<std::size_t> polygonOpenedAt_;
};

// Stores everything: what interpret() returns.
class SceneSink {
  public:
    explicit SceneSink(Scene& scene) : scene_(scene) {}
    std::uint32_t segment(const Segment& s) {
        scene_.segments.push_back(s);
        return static_cast<std::uint32_t>(scene_.segments.size() - 1);
    }
    void polygon(std::span<const Vec3> v, std::uint16_t color) { scene_.addPolygon(v, color); }
    void surface(const std::string& name, SurfaceInstance s) {
        auto it = std::find(scene_.surfaceNames.begin(), scene_.surfaceNames.end(), name);
        s.surface = static_cast<std::uint32_t>(it - scene_.surfaceNames.begin());
        if (it == scene_.surfaceNames.end()) scene_.surfaceNames.push_back(name);
        scene_.surfaces.push_back(s);
    }
    void disc(const Disc& d) { scene_.discs.push_back(d); }
    void sphere(const Sphere& s) { scene_.spheres.push_back(s); }
    void sweptTube(SweptTube t) { scene_.sweptTubes.push_back(std::move(t)); }
    void baseWidth(float w) { scene_.baseWidth = w; }
    void finish(bool is3D) { scene_.is3D = is3D; }

  private:
    Scene& scene_;
};

// Keeps nothing: the turtle only walks.
class NullSink {
  public:
    std::uint32_t segment(const Segment&) { return kNoSegment; }
    void polygon(std::span<const Vec3>, std::uint16_t) {}
    void surface(const std::string&, const SurfaceInstance&) {}
    void disc(const Disc&) {}
    void sphere(const Sphere&) {}
    void baseWidth(float) {}
    void finish(bool) {}
};

}  // namespace graftal::turtle
