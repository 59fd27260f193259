// The measuring walk over a D0L derivation that is never written (d0l_measure.hpp).
#include "graftal/turtle/d0l_measure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "graftal/turtle/subtree_summaries.hpp"
#include "planar_frame.hpp"
#include "planar_measure.hpp"
#include "turtle_machine.hpp"

namespace graftal {

namespace {

using turtle::TurtleOp;

// What the walk does for a module; modules that change nothing a box or a count can see
// (colours, widths, plain letters) have no operation at all.
enum Op : std::uint8_t { kDraw, kMove, kLeft, kRight, kAround, kPush, kPop, kNothing, kUnknown };

Op walkOp(TurtleOp op) {
    switch (op) {
        case TurtleOp::Forward:
        case TurtleOp::ForwardNoVertex:  // no polygon is ever open: it draws
            return kDraw;
        case TurtleOp::Move:
        case TurtleOp::MoveNoVertex:
            return kMove;
        case TurtleOp::TurnLeft:
            return kLeft;
        case TurtleOp::TurnRight:
            return kRight;
        case TurtleOp::TurnAround:
            return kAround;
        case TurtleOp::Push:
            return kPush;
        case TurtleOp::Pop:
            return kPop;
        case TurtleOp::None:
        case TurtleOp::WidthDown:   // a width changes no box
        case TurtleOp::WidthUp:
        case TurtleOp::ColorNext:
        case TurtleOp::ColorPrevious:
        case TurtleOp::Elasticity:  // no tropism (staysPlanar): bends nothing
            return kNothing;
        default:
            return kUnknown;
    }
}

// Subtrees that expand to at most this many modules are walked from a list of operations;
// larger ones are expanded one step.
constexpr double kProgramModules = 4096;

// The derivation tree, as the walk reads it: per (symbol, level) the list of operations
// its subtree performs when it is small enough, and the bracket depths it reaches.
class DerivationTree {
  public:
    DerivationTree(const SubtreeSummaries& sums, const std::array<TurtleOp, kMaxSymbols>& ops)
        : sums_(sums), symbols_(sums.symbolCount()), steps_(sums.steps()) {
        const std::size_t pairs = symbols_ * static_cast<std::size_t>(steps_ + 1);
        modules_.assign(pairs, 0);
        programStart_.assign(pairs, kNone);
        programSize_.assign(pairs, 0);
        depth_.assign(pairs, {});
        for (int level = steps_; level >= 0; --level) {
            for (std::size_t s = 0; s < symbols_; ++s) {
                const std::size_t at = index(static_cast<Symbol>(s), level);
                if (level == steps_) {
                    const Op op = walkOp(ops[s]);
                    modules_[at] = 1;
                    programStart_[at] = static_cast<std::uint32_t>(operations_.size());
                    if (op != kNothing && op != kUnknown) operations_.push_back(op);
                    programSize_[at] = static_cast<std::uint32_t>(operations_.size()) -
                                       programStart_[at];
                    depth_[at] = op == kPush ? Depth{1, 1, 0} : op == kPop ? Depth{-1, 0, -1}
                                                                          : Depth{};
                    continue;
                }
                const std::span<const Symbol> succ = sums_.successor(static_cast<Symbol>(s), level);
                double modules = 0;
                Depth d;
                for (Symbol t : succ) {
                    const std::size_t child = index(t, level + 1);
                    modules += modules_[child];
                    d.highest = std::max(d.highest, d.net + depth_[child].highest);
                    d.lowest = std::min(d.lowest, d.net + depth_[child].lowest);
                    d.net += depth_[child].net;
                }
                modules_[at] = modules;
                depth_[at] = d;
                if (modules > kProgramModules) continue;
                programStart_[at] = static_cast<std::uint32_t>(operations_.size());
                for (Symbol t : succ) {
                    const std::size_t child = index(t, level + 1);
                    const std::uint32_t from = programStart_[child];
                    for (std::uint32_t k = 0; k < programSize_[child]; ++k)
                        operations_.push_back(operations_[from + k]);
                }
                programSize_[at] = static_cast<std::uint32_t>(operations_.size()) -
                                   programStart_[at];
            }
        }
    }

    // The bracket depths the walk of the whole derivation reaches.
    struct Depth {
        std::int64_t net = 0, highest = 0, lowest = 0;
    };
    Depth depthOf(std::span<const Symbol> axiom) const {
        Depth d;
        for (Symbol t : axiom) {
            const Depth& c = depth_[index(t, 0)];
            d.highest = std::max(d.highest, d.net + c.highest);
            d.lowest = std::min(d.lowest, d.net + c.lowest);
            d.net += c.net;
        }
        return d;
    }

    bool hasProgram(Symbol s, int level) const { return programStart_[index(s, level)] != kNone; }
    std::span<const std::uint8_t> program(Symbol s, int level) const {
        const std::size_t at = index(s, level);
        return {operations_.data() + programStart_[at], programSize_[at]};
    }

  private:
    std::size_t index(Symbol s, int level) const {
        return static_cast<std::size_t>(level) * symbols_ + s;
    }
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    const SubtreeSummaries& sums_;
    std::size_t symbols_;
    int steps_;
    std::vector<double> modules_;  // modules of the subtree in the last string
    std::vector<std::uint32_t> programStart_, programSize_;
    std::vector<Depth> depth_;
    std::vector<std::uint8_t> operations_;
};

// The symbol counts of the last string, step by step from the axiom's.
std::vector<std::uint64_t> lastCounts(const SubtreeSummaries& sums) {
    const std::size_t n = sums.symbolCount();
    std::vector<std::uint64_t> counts(n, 0), next(n);
    for (Symbol s : sums.axiom()) ++counts[s];
    for (int level = 0; level < sums.steps(); ++level) {
        std::fill(next.begin(), next.end(), 0);
        for (std::size_t s = 0; s < n; ++s)
            if (counts[s])
                for (Symbol t : sums.successor(static_cast<Symbol>(s), level)) next[t] += counts[s];
        counts.swap(next);
    }
    return counts;
}

// What [ saves: the frame and, for the drawing's box, whether the position is in it.
struct Saved {
    double x, y, hx, hy, lx, ly;
    bool inBounds;
};

struct Box {
    double minX = std::numeric_limits<double>::infinity(), minY = minX;
    double maxX = -std::numeric_limits<double>::infinity(), maxY = maxX;
};

// The walk itself: depth first through the tree, each small subtree from its program. The
// turtle's doubles stay in local variables (a call in the loop would send them to memory).
// The box takes the points the generic turtle's would: with kViewVolume the start and every
// position a move reaches (cpfg notes the position before every move, at [ and ] and at
// the end, which are these points), otherwise the ends of every drawn segment.
template <bool kViewVolume>
Box walk(const SubtreeSummaries& sums, const DerivationTree& tree, const ViewSettings& view,
         std::size_t stackDepth, const CancellationToken& cancel) {
    turtle::Frame start;
    const double h = radians(view.turtle.initialHeading);
    turtle::rotateFrame(start, std::cos(h), std::sin(h));
    double x = start.x, y = start.y, hx = start.hx, hy = start.hy, lx = start.lx, ly = start.ly;
    bool inBounds = false;
    const double step = view.turtle.stepLength;
    const double delta = radians(view.turtle.angleDegrees);
    const double turnSign = view.turtle.clockwisePlus ? -1.0 : 1.0;
    const double c = std::cos(delta), sinLeft = turnSign * std::sin(delta),
                 sinRight = -turnSign * std::sin(delta);
    std::uint64_t untilOrthonormal = turtle::kOrthonormaliseEvery;
    Box box;
    double minX = box.minX, minY = box.minY, maxX = box.maxX, maxY = box.maxY;
    auto extend = [&](double px, double py) {
        minX = std::min(minX, px);
        minY = std::min(minY, py);
        maxX = std::max(maxX, px);
        maxY = std::max(maxY, py);
    };
    if (kViewVolume) extend(x, y);
    std::vector<Saved> stack(stackDepth + 1);
    Saved* top = stack.data();

    struct Level {
        const Symbol* next;
        const Symbol* end;
    };
    std::vector<Level> path(static_cast<std::size_t>(sums.steps()) + 1);
    path[0] = {sums.axiom().data(), sums.axiom().data() + sums.axiom().size()};
    int level = 0;
    std::uint32_t programs = 0;
    for (;;) {
        Level& here = path[static_cast<std::size_t>(level)];
        if (here.next == here.end) {
            if (level == 0) break;
            --level;
            continue;
        }
        const Symbol s = *here.next++;
        if (!tree.hasProgram(s, level)) {
            const std::span<const Symbol> succ = sums.successor(s, level);
            path[static_cast<std::size_t>(++level)] = {succ.data(), succ.data() + succ.size()};
            continue;
        }
        if ((++programs & 0xFFFF) == 0) cancel.check();
        const std::span<const std::uint8_t> program = tree.program(s, level);
        for (const std::uint8_t op : program) {
            switch (op) {
                case kDraw: {
                    if (!kViewVolume && !inBounds) extend(x, y);
                    x = x + hx * step;
                    y = y + hy * step;
                    extend(x, y);
                    inBounds = true;
                    break;
                }
                case kMove:
                    x = x + hx * step;
                    y = y + hy * step;
                    if (kViewVolume) extend(x, y);
                    inBounds = false;
                    break;
                case kLeft:
                case kRight: {
                    const double sn = op == kLeft ? sinLeft : sinRight;
                    const double nhx = hx * c + lx * sn, nhy = hy * c + ly * sn;
                    const double nlx = lx * c + hx * (-sn), nly = ly * c + hy * (-sn);
                    hx = nhx;
                    hy = nhy;
                    lx = nlx;
                    ly = nly;
                    if (--untilOrthonormal == 0) {
                        untilOrthonormal = turtle::kOrthonormaliseEvery;
                        turtle::Frame f;
                        f.hx = hx, f.hy = hy, f.lx = lx, f.ly = ly;
                        turtle::orthonormalise(f);
                        hx = f.hx, hy = f.hy, lx = f.lx, ly = f.ly;
                    }
                    break;
                }
                case kAround:
                    hx = hx * -1.0;
                    hy = hy * -1.0;
                    lx = lx * -1.0;
                    ly = ly * -1.0;
                    break;
                case kPush:
                    *top++ = Saved{x, y, hx, hy, lx, ly, inBounds};
                    break;
                case kPop: {
                    const Saved& r = *--top;
                    x = r.x, y = r.y, hx = r.hx, hy = r.hy, lx = r.lx, ly = r.ly;
                    inBounds = r.inBounds;
                    break;
                }
                default:
                    break;
            }
        }
    }
    box.minX = minX, box.minY = minY, box.maxX = maxX, box.maxY = maxY;
    return box;
}

}  // namespace

std::optional<StreamedMeasure> measureD0L(const Model& model, int steps, MeasuredBox which,
                                          const CancellationToken& cancel) {
    const LSystem& ls = model.lsystem;
    const ViewSettings& view = model.view;
    if (!turtle::staysPlanar(model)) return std::nullopt;
    const double delta = radians(view.turtle.angleDegrees);
    if (!std::isfinite(view.turtle.stepLength) || !std::isfinite(std::cos(delta)) ||
        !std::isfinite(std::sin(delta)) || !std::isfinite(view.turtle.initialHeading))
        return std::nullopt;
    const SubtreeSummaries sums(model, steps);
    if (!sums.available()) return std::nullopt;
    StreamedMeasure m;
    m.symbolCounts = lastCounts(sums);
    const std::array<TurtleOp, kMaxSymbols> ops = turtle::opTable(ls);
    for (std::size_t s = 0; s < m.symbolCounts.size(); ++s) {
        if (!m.symbolCounts[s]) continue;
        if (walkOp(ops[s]) == kUnknown) return std::nullopt;
        m.modules += m.symbolCounts[s];
        if (walkOp(ops[s]) == kDraw) m.segments += m.symbolCounts[s];
    }
    const DerivationTree tree(sums, ops);
    // A ']' with nothing saved is the generic turtle's error to word.
    const DerivationTree::Depth depth = tree.depthOf(sums.axiom());
    if (depth.lowest < 0 || depth.highest > (std::int64_t{1} << 24)) return std::nullopt;

    m.baseWidth = static_cast<float>(view.turtle.initialWidth);
    const auto stackDepth = static_cast<std::size_t>(depth.highest);
    const Box b = which == MeasuredBox::CpfgViewVolume
                      ? walk<true>(sums, tree, view, stackDepth, cancel)
                      : walk<false>(sums, tree, view, stackDepth, cancel);
    // Every point extended has z = +0; the drawing's box is empty without a segment.
    if (which == MeasuredBox::CpfgViewVolume || m.segments > 0) {
        m.bounds.min = Vec3{b.minX, b.minY, 0};
        m.bounds.max = Vec3{b.maxX, b.maxY, 0};
    }
    return m;
}

}  // namespace graftal
