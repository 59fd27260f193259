// The planar measuring walk (see planar_measure.hpp for why it is exact).
#include "planar_measure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "planar_frame.hpp"
#include "planar_length.hpp"
#include "turtle_machine.hpp"

namespace graftal::turtle {

namespace {

bool leavesPlane(TurtleOp op) {
    switch (op) {
        case TurtleOp::PitchDown:
        case TurtleOp::PitchUp:
        case TurtleOp::RollLeft:
        case TurtleOp::RollRight:
        case TurtleOp::RollToVertical:
        case TurtleOp::AtPrefix:  // @R, @M, @c, @O may leave it; the generic turtle knows
        case TurtleOp::SurfacePrefix:
            return true;
        default:
            return false;
    }
}

// Everything the walk carries from module to module.
struct WalkState {
    Frame turtle;
    double minX = std::numeric_limits<double>::infinity(), minY = minX;
    double maxX = -std::numeric_limits<double>::infinity(), maxY = maxX;
    double ink = 0;
    std::uint64_t segments = 0, polygons = 0, rotations = 0;
};

// The walk has two loops. The fast one handles the modules that make up nearly all of a
// long string (steps, turns by delta, branches, widths) with the state in registers and
// no call, and stops at anything else; the slow one takes that module with every case,
// and hands back. A call inside the fast loop would make the compiler keep the state in
// memory, since a call may clobber every vector register.
class PlanarWalk {
  public:
    explicit PlanarWalk(const Model& model) : ops_(opTable(model.lsystem)) {
        const ViewSettings& v = model.view;
        step_ = v.turtle.stepLength;
        double delta = radians(v.turtle.angleDegrees);
        cos_ = std::cos(delta);
        turnSign_ = v.turtle.clockwisePlus ? -1.0 : 1.0;
        sinLeft_ = turnSign_ * std::sin(delta);
        sinRight_ = -turnSign_ * std::sin(delta);
        view_ = &v;
        Frame& t = state_.turtle;
        double h = radians(v.turtle.initialHeading);
        rotateFrame(t, std::cos(h), std::sin(h));
        t.width = static_cast<float>(v.turtle.initialWidth);
        baseWidth_ = t.width;
        t.weight = weightOf(t.width);
        stack_.resize(64);
    }

    bool measure(const ModuleString& modules, StreamedMeasure& out) {
        if (!std::isfinite(step_)) return false;
        return modules.hasParameters() ? walk<true>(modules, out) : walk<false>(modules, out);
    }

  private:
    double weightOf(float width) const { return inkWeight(width, baseWidth_); }

    template <bool kParams>
    bool walk(const ModuleString& modules, StreamedMeasure& out);
    template <bool kParams>
    std::size_t fastRun(const ModuleString& modules, std::size_t i, std::uint64_t* counts);
    bool slowModule(TurtleOp op, ParamView args);

    std::array<TurtleOp, kMaxSymbols> ops_;
    double step_ = 1, cos_ = 1, sinLeft_ = 0, sinRight_ = 0, turnSign_ = 1;
    const ViewSettings* view_ = nullptr;
    float baseWidth_ = 1;
    WalkState state_;
    std::vector<Frame> stack_;  // frames [0, depth_) are saved; the rest is room
    std::size_t depth_ = 0;
    std::vector<std::vector<std::pair<double, double>>> polygons_;
    PlanarLength side_;
    // The points the fast loop leaves for the bounds, taken in when it stops: four more
    // minima and maxima would not fit in its registers.
    std::vector<double> records_ = std::vector<double>(2 * 512);
};

template <bool kParams>
bool PlanarWalk::walk(const ModuleString& modules, StreamedMeasure& out) {
    std::uint64_t* counts = out.symbolCounts.data();
    const std::size_t n = modules.size();
    for (std::size_t i = 0; i < n; ++i) {
        i = fastRun<kParams>(modules, i, counts);
        if (i == n) break;
        const Symbol s = modules.symbol(i);
        ++counts[s];
        if (!slowModule(ops_[s], modules.params(i))) return false;
    }
    if (!polygons_.empty()) return false;

    const WalkState& w = state_;
    out.modules = n;
    out.segments = w.segments;
    out.polygons = w.polygons;
    out.ink = w.ink;
    out.baseWidth = baseWidth_;
    out.is3D = false;
    // Every point extended has z = +0: the box is flat once anything is in it.
    if (w.segments > 0 || w.polygons > 0) {
        out.bounds.min = Vec3{w.minX, w.minY, 0};
        out.bounds.max = Vec3{w.maxX, w.maxY, 0};
    }
    return true;
}

// Walks from module i as long as no module needs the slow loop; returns where it stopped.
template <bool kParams>
std::size_t PlanarWalk::fastRun(const ModuleString& modules, std::size_t i, std::uint64_t* counts) {
    if (!polygons_.empty()) return i;  // the fast loop draws no polygon
    const Symbol* symbols = modules.symbols().data();
    const std::size_t n = modules.size();
    const double step = step_, c = cos_, sinLeft = sinLeft_, sinRight = sinRight_;
    Frame t = state_.turtle;
    std::uint64_t segments = state_.segments, rotations = state_.rotations;
    Frame* stack = stack_.data();
    const std::size_t room = stack_.size();
    std::size_t depth = depth_;
    // (x, y) of every segment end, and of every segment start that may not be in yet.
    double* record = records_.data();
    double* const recordsEnd = record + records_.size() - 4;
    double ink = state_.ink;

    for (; i < n; ++i) {
        const Symbol s = symbols[i];
        const TurtleOp op = ops_[s];
        switch (op) {
            case TurtleOp::Forward:
            case TurtleOp::ForwardNoVertex:
            case TurtleOp::Move:
            case TurtleOp::MoveNoVertex: {
                double length = step;
                if constexpr (kParams) {
                    ParamView args = modules.params(i);
                    if (!args.empty()) {
                        length = args[0];
                        if (!std::isfinite(length)) goto stop;
                    }
                }
                const double x = t.x + t.hx * length, y = t.y + t.hy * length;
                if (op == TurtleOp::Forward || op == TurtleOp::ForwardNoVertex) {
                    const double dx = x - t.x, dy = y - t.y;
                    double l;  // what PlanarLength gives, without calling hypot
                    if ((dx == 0) | (dy == 0)) {
                        l = std::fabs(dx) + std::fabs(dy);
                    } else if (const double* known = side_.find(dx, dy)) {
                        l = *known;
                    } else {
                        goto stop;  // the slow loop calls hypot
                    }
                    if (record > recordsEnd) goto stop;  // full: the slow loop sums up
                    // The segment's start is in the bounds unless a move, a branch or the
                    // beginning put the turtle there.
                    if (!t.inBounds) {
                        record[0] = t.x;
                        record[1] = t.y;
                        record += 2;
                    }
                    record[0] = x;
                    record[1] = y;
                    record += 2;
                    ink += inkTerm(l, t.weight);
                    ++segments;
                    t.inBounds = true;
                } else {
                    t.inBounds = false;
                }
                t.x = x;
                t.y = y;
                break;
            }
            case TurtleOp::TurnLeft:
            case TurtleOp::TurnRight: {
                if constexpr (kParams)
                    if (!modules.params(i).empty()) goto stop;  // cos and sin are calls
                if ((rotations + 1) % kOrthonormaliseEvery == 0) goto stop;
                ++rotations;
                rotateFrame(t, c, op == TurtleOp::TurnLeft ? sinLeft : sinRight);
                break;
            }
            case TurtleOp::TurnAround:
                t.hx = t.hx * -1.0;
                t.hy = t.hy * -1.0;
                t.lx = t.lx * -1.0;
                t.ly = t.ly * -1.0;
                break;
            case TurtleOp::Push:
                if (depth == room) goto stop;  // the slow loop makes room
                stack[depth++] = t;
                break;
            case TurtleOp::Pop:
                if (depth == 0) goto stop;  // the slow loop gives up
                t = stack[--depth];
                break;
            case TurtleOp::WidthDown:
            case TurtleOp::WidthUp:
                if constexpr (kParams)
                    if (!modules.params(i).empty()) goto stop;
                t.width = changedWidth(*view_, t.width, op == TurtleOp::WidthUp);
                t.weight = weightOf(t.width);
                break;
            case TurtleOp::None:
            case TurtleOp::ColorNext:
            case TurtleOp::ColorPrevious:
            case TurtleOp::Elasticity:  // no tropism here (turtleIsBent): bends nothing
                break;                  // a colour changes no measure
            default:
                goto stop;
        }
        ++counts[s];
    }
stop:
    state_.turtle = t;
    state_.segments = segments;
    state_.rotations = rotations;
    depth_ = depth;
    // The points into the bounds. That they come later than in the generic walk changes
    // nothing: a minimum or maximum of the same points in another order can only differ
    // between 0 and -0 (no position is -0) or in a NaN (which never enters the box).
    WalkState& w = state_;
    w.ink = ink;
    for (const double* r = records_.data(); r < record; r += 2) {
        w.minX = std::min(w.minX, r[0]);
        w.minY = std::min(w.minY, r[1]);
        w.maxX = std::max(w.maxX, r[0]);
        w.maxY = std::max(w.maxY, r[1]);
    }
    return i;
}

// One module with every case (the generic turtle's apply() in the plane); false when
// the walk must give way to the generic turtle.
bool PlanarWalk::slowModule(TurtleOp op, ParamView args) {
    WalkState& w = state_;
    Frame& t = w.turtle;
    auto extend = [&](double x, double y) {
        w.minX = std::min(w.minX, x);
        w.minY = std::min(w.minY, y);
        w.maxX = std::max(w.maxX, x);
        w.maxY = std::max(w.maxY, y);
    };
    auto turn = [&](double sinDelta, double sign) {
        if (args.empty()) {
            rotateFrame(t, cos_, sinDelta);
        } else {
            double r = radians(args[0]);
            if (!std::isfinite(r)) return false;  // NaN would reach the zeros of z
            rotateFrame(t, std::cos(r), sign * std::sin(r));
        }
        if (++w.rotations % kOrthonormaliseEvery == 0) orthonormalise(t);
        return true;
    };
    switch (op) {
        case TurtleOp::Forward:
        case TurtleOp::Move:
        case TurtleOp::ForwardNoVertex:
        case TurtleOp::MoveNoVertex: {
            const double length = args.empty() ? step_ : args[0];
            if (!std::isfinite(length)) return false;  // NaN would reach the zero of z
            const double x = t.x + t.hx * length, y = t.y + t.hy * length;
            const bool draws = op == TurtleOp::Forward || op == TurtleOp::ForwardNoVertex;
            if (polygons_.empty() && draws) {
                if (!t.inBounds) extend(t.x, t.y);
                extend(x, y);
                const double l = side_(x - t.x, y - t.y);
                w.ink += inkTerm(l, t.weight);
                ++w.segments;
                t.inBounds = true;
            } else {
                if (!polygons_.empty() && (op == TurtleOp::Forward || op == TurtleOp::Move))
                    polygons_.back().emplace_back(x, y);
                t.inBounds = false;
            }
            t.x = x;
            t.y = y;
            return true;
        }
        case TurtleOp::TurnLeft:
            return turn(sinLeft_, turnSign_);
        case TurtleOp::TurnRight:
            return turn(sinRight_, -turnSign_);
        case TurtleOp::TurnAround:
            t.hx = t.hx * -1.0;
            t.hy = t.hy * -1.0;
            t.lx = t.lx * -1.0;
            t.ly = t.ly * -1.0;
            return true;
        case TurtleOp::Push:
            if (depth_ == stack_.size()) stack_.resize(2 * stack_.size());
            stack_[depth_++] = t;
            return true;
        case TurtleOp::Pop:
            if (depth_ == 0) return false;  // the generic turtle words the error
            t = stack_[--depth_];
            return true;
        case TurtleOp::RecordVertex:
            if (!polygons_.empty()) polygons_.back().emplace_back(t.x, t.y);
            return true;
        case TurtleOp::PolygonBegin:
            // `{(n)` starts a generalized cylinder: the generic turtle draws it.
            if (!args.empty() && args[0] != 0) return false;
            polygons_.emplace_back();
            polygons_.back().emplace_back(t.x, t.y);
            return true;
        case TurtleOp::PolygonEnd:
            if (polygons_.empty() || (!args.empty() && args[0] != 0)) return false;
            if (polygons_.back().size() >= 3) {
                for (const auto& [x, y] : polygons_.back()) extend(x, y);
                ++w.polygons;
            }
            polygons_.pop_back();
            return true;
        case TurtleOp::WidthDown:
            t.width =
                args.empty() ? changedWidth(*view_, t.width, false) : static_cast<float>(args[0]);
            t.weight = weightOf(t.width);
            return true;
        case TurtleOp::WidthUp:
            t.width =
                args.empty() ? changedWidth(*view_, t.width, true) : static_cast<float>(args[0]);
            t.weight = weightOf(t.width);
            return true;
        case TurtleOp::None:
        case TurtleOp::ColorNext:
        case TurtleOp::ColorPrevious:
        case TurtleOp::Elasticity:
            return true;
        case TurtleOp::PitchDown:
        case TurtleOp::PitchUp:
        case TurtleOp::RollLeft:
        case TurtleOp::RollRight:
        case TurtleOp::RollToVertical:
        case TurtleOp::AtPrefix:
        case TurtleOp::SurfacePrefix:
            return false;
    }
    return true;
}

}  // namespace

bool staysPlanar(const Model& model) {
    const LSystem& ls = model.lsystem;
    if (turtleIsBent(model.view)) return false;
    const std::array<TurtleOp, kMaxSymbols> ops = opTable(ls);
    for (Symbol s : ls.axiom.symbols())
        if (leavesPlane(ops[s])) return false;
    for (const auto* list : {&ls.productions, &ls.decomposition, &ls.homomorphism})
        for (const Production& p : *list)
            for (const SuccessorModule& m : p.successor)
                if (leavesPlane(ops[m.symbol])) return false;
    return true;
}

std::optional<StreamedMeasure> measurePlanar(const Model& model, const ModuleString& modules) {
    StreamedMeasure m;
    m.symbolCounts.assign(model.lsystem.symbols.size(), 0);
    PlanarWalk walk(model);
    if (!walk.measure(modules, m)) return std::nullopt;
    return m;
}

}  // namespace graftal::turtle
