#include "graftal/turtle/subtree_summaries.hpp"

#include <algorithm>
#include <cmath>

#include "streamed_sinks.hpp"
#include "turtle_machine.hpp"

namespace graftal {

namespace {

using turtle::TurtleOp;

bool hasRandomOrParameters(const LSystem& ls) {
    if (ls.isParametric() || ls.axiom.hasParameters()) return true;
    for (const auto& p : ls.productions) {
        if (p.probability || p.condition || p.isParametric()) return true;
        for (const auto& m : p.successor)
            if (!m.args.empty()) return true;
    }
    return false;
}

bool drawsPolygons(const LSystem& ls) {
    auto polygon = [](Symbol s) { return s == '{' || s == '}' || s == '.'; };
    for (Symbol s : ls.axiom.symbols())
        if (polygon(s)) return true;
    for (const auto& p : ls.productions)
        for (const auto& m : p.successor)
            if (polygon(m.symbol)) return true;
    return false;
}

// Complex multiplication: the turn of a subtree after the turn before it, renormalised so
// that thousands of compositions keep it a rotation.
void turnBy(double& c, double& s, double c2, double s2) {
    double nc = c * c2 - s * s2, ns = s * c2 + c * s2;
    double n = std::hypot(nc, ns);
    c = nc / n;
    s = ns / n;
}

}  // namespace

SubtreeSummaries::SubtreeSummaries(const Model& model, int steps, std::size_t memoryLimit)
    : ls_(model.lsystem), view_(model.view) {
    const LSystem& ls = ls_;
    steps_ = steps < 0 ? ls.derivationLength : steps;
    symbolCount_ = ls.symbols.size();
    if (!streamingObstacle(ls).empty() || hasRandomOrParameters(ls) || drawsPolygons(ls) ||
        (turtleIsBent(view_)))
        return;
    // One summary per symbol and string: keep the table small.
    const double entries = static_cast<double>(symbolCount_) * (steps_ + 1);
    if (entries > 2e7 || entries * sizeof(SubtreeMotion) > static_cast<double>(memoryLimit) / 2)
        return;
    axiom_.assign(ls.axiom.symbols().begin(), ls.axiom.symbols().end());

    std::size_t tables = std::max<std::size_t>(1, ls.tableNames.size());
    successorStart_.assign(tables, std::vector<std::uint32_t>(symbolCount_ + 1, 0));
    successorSymbols_.assign(tables, {});
    std::vector<std::vector<bool>> rewrites(tables, std::vector<bool>(symbolCount_, false));
    for (std::size_t t = 0; t < tables; ++t) {
        // As the derivation chooses: the first production in file order for the symbol.
        std::vector<const Production*> first(symbolCount_, nullptr);
        for (const auto& p : ls.productions) {
            if (p.table >= 0 && static_cast<std::size_t>(p.table) != t) continue;
            Symbol s = p.predecessor[0].symbol;
            if (!first[s]) first[s] = &p;
        }
        for (std::size_t s = 0; s < symbolCount_; ++s) {
            successorStart_[t][s] = static_cast<std::uint32_t>(successorSymbols_[t].size());
            if (!first[s]) {
                successorSymbols_[t].push_back(static_cast<Symbol>(s));
                continue;
            }
            rewrites[t][s] = true;
            for (const auto& m : first[s]->successor) successorSymbols_[t].push_back(m.symbol);
        }
        successorStart_[t][symbolCount_] = static_cast<std::uint32_t>(successorSymbols_[t].size());
    }
    // Brackets that are rewritten would not balance the way the folds below assume.
    for (std::size_t t = 0; t < tables; ++t)
        if (rewrites[t]['['] || rewrites[t][']']) return;

    tableOfLevel_.resize(static_cast<std::size_t>(steps_));
    lastRewrite_.assign(symbolCount_, -1);
    for (int level = 0; level < steps_; ++level) {
        int t = std::clamp(ls.tableForStep(level + 1), 0, static_cast<int>(tables) - 1);
        tableOfLevel_[static_cast<std::size_t>(level)] = t;
        for (std::size_t s = 0; s < symbolCount_; ++s)
            if (rewrites[static_cast<std::size_t>(t)][s]) lastRewrite_[s] = level + 1;
    }

    motions_.resize(symbolCount_ * static_cast<std::size_t>(steps_ + 1));
    for (std::size_t s = 0; s < symbolCount_; ++s)
        motions_[static_cast<std::size_t>(steps_) * symbolCount_ + s] =
            leaf(static_cast<Symbol>(s));
    for (int level = steps_ - 1; level >= 0; --level)
        for (std::size_t s = 0; s < symbolCount_; ++s)
            motions_[static_cast<std::size_t>(level) * symbolCount_ + s] =
                rewrittenAfter(static_cast<Symbol>(s), level)
                    ? fold(successor(static_cast<Symbol>(s), level), level + 1)
                    : leaf(static_cast<Symbol>(s));
    available_ = true;
}

std::span<const Symbol> SubtreeSummaries::successor(Symbol symbol, int level) const {
    auto t = static_cast<std::size_t>(tableOfLevel_[static_cast<std::size_t>(level)]);
    const auto& start = successorStart_[t];
    return {successorSymbols_[t].data() + start[symbol], start[symbol + 1u] - start[symbol]};
}

double SubtreeSummaries::segments() const {
    return available_ ? fold(axiom_, 0).segments : 0;
}

// The motion of the module itself, as the turtle performs it.
SubtreeMotion SubtreeSummaries::leaf(Symbol symbol) const {
    SubtreeMotion m;
    m.summarised = true;
    const ViewSettings& v = view_;
    double delta = radians(v.turtle.angleDegrees);
    double turn = v.turtle.clockwisePlus ? -1.0 : 1.0;
    const TurtleOp op = turtle::opOf(ls_, symbol);
    switch (op) {
        case TurtleOp::None:
            break;
        case TurtleOp::Forward:
        case TurtleOp::ForwardNoVertex:
            m.segments = 1;
            m.length = std::fabs(v.turtle.stepLength);
            [[fallthrough]];
        case TurtleOp::Move:
        case TurtleOp::MoveNoVertex:
            m.along = v.turtle.stepLength;
            m.radius = std::fabs(v.turtle.stepLength);
            break;
        case TurtleOp::TurnLeft:
        case TurtleOp::TurnRight:
            m.cos = std::cos(delta);
            m.sin = (op == TurtleOp::TurnLeft ? turn : -turn) * std::sin(delta);
            break;
        case TurtleOp::TurnAround:
            m.cos = -1;
            break;
        default:  // pitch, roll, $, brackets alone, width, colour, surfaces
            m.summarised = false;
            break;
    }
    return m;
}

// The motion of a string of `level` from the motions of its modules; brackets restore
// position and frame as the turtle's stack does.
SubtreeMotion SubtreeSummaries::fold(std::span<const Symbol> modules, int level) const {
    struct Saved {
        double x, y, c, s;
    };
    std::vector<Saved> stack;
    SubtreeMotion r;
    double x = 0, y = 0, c = 1, s = 0;
    for (Symbol m : modules) {
        if (m == '[') {
            stack.push_back({x, y, c, s});
            continue;
        }
        if (m == ']') {
            if (stack.empty()) return {};
            x = stack.back().x, y = stack.back().y, c = stack.back().c, s = stack.back().s;
            stack.pop_back();
            continue;
        }
        const SubtreeMotion& child = motion(m, level);
        if (!child.summarised) return {};
        r.radius = std::max(r.radius, std::hypot(x, y) + child.radius);
        // The child's displacement, given in the frame turned by (c, s).
        x += child.along * c - child.aside * s;
        y += child.along * s + child.aside * c;
        turnBy(c, s, child.cos, child.sin);
        r.segments += child.segments;
        r.length += child.length;
    }
    if (!stack.empty()) return {};
    r.along = x;
    r.aside = y;
    r.cos = c;
    r.sin = s;
    r.summarised = true;
    return r;
}

namespace {

// Depth-first over the derivation like streamDerivation, but a subtree that `jumpOver`
// accepts is not expanded: `jumpOver` has moved the turtle over it.
template <class Machine, class JumpOver>
void walk(const SubtreeSummaries& sums, Machine& machine, JumpOver&& jumpOver) {
    struct Level {
        const Symbol* at;
        const Symbol* end;
    };
    std::vector<Level> levels;
    levels.push_back({sums.axiom().data(), sums.axiom().data() + sums.axiom().size()});
    std::size_t index = 0;
    while (!levels.empty()) {
        Level& here = levels.back();
        if (here.at == here.end) {
            levels.pop_back();
            continue;
        }
        Symbol s = *here.at++;
        int level = static_cast<int>(levels.size()) - 1;
        if (level == sums.steps() || !sums.rewrittenAfter(s, level)) {
            machine.module(s, {}, index++);
            continue;
        }
        const SubtreeMotion& m = sums.motion(s, level);
        // After @ or ~ the module that follows is the prefix's: never jumped over.
        if (m.summarised && !machine.prefixPending() && jumpOver(m)) continue;
        std::span<const Symbol> next = sums.successor(s, level);
        levels.push_back({next.data(), next.data() + next.size()});
    }
    machine.finish();
}

// Moves the turtle over a summarised subtree and returns the segment from its start to its
// end.
Segment jump(turtle::TurtleState& t, const SubtreeMotion& m) {
    Vec3 from = t.position;
    t.position = from + t.heading * m.along + t.left * m.aside;
    turtle::rotatePair(t.heading, t.left, m.cos, m.sin);
    return Segment{from, t.position, t.width, t.color, kNoSegment, t.up};
}

// Pictures are drawn in x and y only, so the disc need only be inside in those.
bool inside(const Bounds& b, const Vec3& p, double r) {
    return !b.empty() && p.x - r >= b.min.x && p.x + r <= b.max.x && p.y - r >= b.min.y &&
           p.y + r <= b.max.y;
}

}  // namespace

StreamedMeasure measureSummarised(const Model& model, const SubtreeSummaries& sums, int imageSide,
                                  double pixelTolerance) {
    StreamedMeasure result;
    result.symbolCounts.assign(model.lsystem.symbols.size(), 0);
    MeasureSink sink(result);
    turtle::TurtleMachine<MeasureSink> machine(model, sink);
    const double pixels = std::max(1, imageSide);
    walk(sums, machine, [&](const SubtreeMotion& m) {
        turtle::TurtleState& t = machine.state();
        const Bounds& b = result.bounds;
        // The bounds so far are at most the final ones, so this pixel is at most the final
        // pixel: a subtree within the tolerance of it cannot move the picture visibly.
        double pixel = b.empty() ? 0 : std::max(b.max.x - b.min.x, b.max.y - b.min.y) / pixels;
        bool tiny = m.radius <= pixelTolerance * pixel;
        if (m.segments > 0 && !tiny && !inside(b, t.position, m.radius)) return false;
        Vec3 start = t.position;
        Segment chord = jump(t, m);
        if (m.segments > 0) {
            if (tiny) {
                Vec3 r{m.radius, m.radius, 0};
                result.bounds.extend(start - r);
                result.bounds.extend(start + r);
            }
            result.segments += static_cast<std::uint64_t>(m.segments);
            result.ink +=
                m.length *
                (chord.width > 0 && result.baseWidth > 0 ? chord.width / result.baseWidth : 0);
        }
        return true;
    });
    return result;
}

void drawSummarised(const Model& model, const SubtreeSummaries& sums, double scale,
                    double dotRadius, StreamedDrawing& drawing) {
    DrawingSink sink(drawing);
    turtle::TurtleMachine<DrawingSink> machine(model, sink);
    walk(sums, machine, [&](const SubtreeMotion& m) {
        if (m.segments > 0 && m.radius * scale > dotRadius) return false;
        Segment chord = jump(machine.state(), m);
        if (m.segments > 0) drawing.segment(chord);
        return true;
    });
}

double summarisedStrokeCount(const SubtreeSummaries& sums, double scale, double dotRadius) {
    if (!sums.available()) return 0;
    // Strokes per (symbol, string), filled from the last string up as the summaries are.
    const std::size_t width = sums.symbolCount();
    std::vector<double> strokes(width * static_cast<std::size_t>(sums.steps() + 1), 0);
    auto at = [&](Symbol s, int level) -> double& {
        return strokes[static_cast<std::size_t>(level) * width + s];
    };
    for (int level = sums.steps(); level >= 0; --level)
        for (std::size_t i = 0; i < width; ++i) {
            auto s = static_cast<Symbol>(i);
            const SubtreeMotion& m = sums.motion(s, level);
            if (level == sums.steps() || !sums.rewrittenAfter(s, level)) {
                at(s, level) = sums.motion(s, sums.steps()).segments;
                continue;
            }
            if (m.summarised && !(m.segments > 0 && m.radius * scale > dotRadius)) {
                at(s, level) = m.segments > 0 ? 1 : 0;
                continue;
            }
            double sum = 0;
            for (Symbol c : sums.successor(s, level)) sum += at(c, level + 1);
            at(s, level) = sum;
        }
    double total = 0;
    for (Symbol s : sums.axiom()) total += at(s, 0);
    return total;
}

double dotRadiusWithin(const SubtreeSummaries& sums, double scale, double dotRadius,
                       double strokeBudget, double largestDotRadius) {
    while (dotRadius < largestDotRadius &&
           summarisedStrokeCount(sums, scale, dotRadius) > strokeBudget)
        dotRadius = std::min(dotRadius * 1.25, largestDotRadius);
    return dotRadius;
}

}  // namespace graftal
