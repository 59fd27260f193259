// The measuring walk over a D0L derivation that is never written (d0l_measure.hpp).
#include "graftal/turtle/d0l_measure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <unordered_map>
#include <vector>

#include "graftal/core/bit_cast.hpp"
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
        case TurtleOp::WidthDown:  // a width changes no box
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
// All programs together (a byte per operation): a long derivation of many symbols would
// otherwise hold thousands of programs of every size.
constexpr std::size_t kOperations = std::size_t{32} << 20;
// Programs with fewer moves are never replayed.
constexpr std::uint64_t kReplayedMoves = 64;

// The derivation tree, as the walk reads it: per (symbol, level) the list of operations
// its subtree performs when it is small enough, and the bracket depths it reaches.
class DerivationTree {
  public:
    struct Depth {
        std::int64_t net = 0, highest = 0, lowest = 0;
    };
    struct Program {
        std::uint32_t id = 0;                   // the (symbol, level) pair
        std::uint32_t start = kNone, size = 0;  // in operations_; kNone: no program
        std::uint64_t turns = 0, moves = 0;
        bool replayable = false;  // leaves no bracket open and closes none it did not open
    };

    DerivationTree(const SubtreeSummaries& sums, const std::array<TurtleOp, kMaxSymbols>& ops)
        : sums_(sums), symbols_(sums.symbolCount()), steps_(sums.steps()) {
        const std::size_t pairs = symbols_ * static_cast<std::size_t>(steps_ + 1);
        modules_.assign(pairs, 0);
        programs_.assign(pairs, {});
        depth_.assign(pairs, {});
        for (int level = steps_; level >= 0; --level) {
            for (std::size_t s = 0; s < symbols_; ++s) {
                const std::size_t at = index(static_cast<Symbol>(s), level);
                Program& p = programs_[at];
                p.id = static_cast<std::uint32_t>(at);
                p.start = static_cast<std::uint32_t>(operations_.size());
                if (level == steps_) {
                    const Op op = walkOp(ops[s]);
                    modules_[at] = 1;
                    if (op != kNothing && op != kUnknown) operations_.push_back(op);
                    depth_[at] = op == kPush  ? Depth{1, 1, 0}
                                 : op == kPop ? Depth{-1, 0, -1}
                                              : Depth{};
                } else {
                    const std::span<const Symbol> succ =
                        sums_.successor(static_cast<Symbol>(s), level);
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
                    if (modules > kProgramModules ||
                        operations_.size() + static_cast<std::size_t>(modules) > kOperations) {
                        p.start = kNone;
                        continue;
                    }
                    for (Symbol t : succ) {
                        const Program& c = programs_[index(t, level + 1)];
                        for (std::uint32_t k = 0; k < c.size; ++k)
                            operations_.push_back(operations_[c.start + k]);
                    }
                }
                p.size = static_cast<std::uint32_t>(operations_.size()) - p.start;
                for (std::uint8_t op : operations(p)) {
                    p.turns += op == kLeft || op == kRight;
                    p.moves += op == kDraw || op == kMove;
                }
                // A short program runs faster than its replay is found.
                p.replayable =
                    depth_[at].net == 0 && depth_[at].lowest >= 0 && p.moves >= kReplayedMoves;
            }
        }
    }

    // The bracket depths the walk of the whole derivation reaches.
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

    bool hasProgram(Symbol s, int level) const { return programs_[index(s, level)].start != kNone; }
    const Program& program(Symbol s, int level) const { return programs_[index(s, level)]; }
    std::span<const std::uint8_t> operations(const Program& p) const {
        return {operations_.data() + p.start, p.size};
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
    std::vector<Program> programs_;
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
    double minX, minY, maxX, maxY;
};

// Everything the walk carries from module to module.
struct Turtle {
    double x = 0, y = 0, hx = 0, hy = 1, lx = -1, ly = 0;
    bool inBounds = false;  // (the drawing's box) the position is in it already
    std::uint64_t untilOrthonormal = turtle::kOrthonormaliseEvery;  // turns to the next
    double minX = std::numeric_limits<double>::infinity(), minY = minX;
    double maxX = -std::numeric_limits<double>::infinity(), maxY = maxX;
    Saved* top = nullptr;  // the next free place on the stack
};

// A program run once from a frame, kept to be replayed from the same frame: the
// displacement of every move in order (the very doubles hx * step and hy * step the turtle
// adds), what each operation was, and the frame at the end. Turns need no replaying: a
// program that never leaves its brackets open ends with a frame fixed by its start.
struct Replay {
    std::uint32_t moveStart = 0, moveCount = 0;  // in the replays' moves
    std::uint32_t opStart = 0, opCount = 0;      // in their operations (0: all draws)
    double hx = 0, hy = 0, lx = 0, ly = 0;
};

struct ReplayKey {
    std::uint32_t program;
    std::uint64_t hx, hy, lx, ly;  // the bits of the frame
    bool operator==(const ReplayKey&) const = default;
};
struct ReplayKeyHash {
    std::size_t operator()(const ReplayKey& k) const {
        std::uint64_t h = k.program * 0x9E3779B97F4A7C15u;
        for (std::uint64_t w : {k.hx, k.hy, k.lx, k.ly}) h = (h ^ w) * 0xC2B2AE3D27D4EB4Fu;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

// The walk: depth first through the tree, each small subtree from its program or, when
// the same program already ran from the same frame, from its replay. The box takes the
// points the generic turtle's would: with kViewVolume the start and every position a move
// reaches (cpfg notes the position before every move, at [ and ] and at the end, which are
// these points), otherwise the ends of every drawn segment. A replay adds the same doubles
// in the same order, so it reaches the same positions bit for bit; only the frame's
// Gram-Schmidt pass (every kOrthonormaliseEvery turns) depends on more than the start
// frame, and a program within which it falls runs as such.
template <bool kViewVolume>
class Walk {
  public:
    Walk(const SubtreeSummaries& sums, const DerivationTree& tree, const ViewSettings& view,
         std::size_t stackDepth)
        : sums_(sums), tree_(tree), stack_(stackDepth + 1) {
        turtle::Frame start;
        const double h = radians(view.turtle.initialHeading);
        turtle::rotateFrame(start, std::cos(h), std::sin(h));
        t_.x = start.x, t_.y = start.y, t_.hx = start.hx, t_.hy = start.hy;
        t_.lx = start.lx, t_.ly = start.ly;
        t_.top = stack_.data();
        step_ = view.turtle.stepLength;
        const double delta = radians(view.turtle.angleDegrees);
        const double turnSign = view.turtle.clockwisePlus ? -1.0 : 1.0;
        cos_ = std::cos(delta);
        sinLeft_ = turnSign * std::sin(delta);
        sinRight_ = -turnSign * std::sin(delta);
        if (kViewVolume) extend(t_, t_.x, t_.y);
    }

    Box run(const CancellationToken& cancel) {
        struct Level {
            const Symbol* next;
            const Symbol* end;
        };
        std::vector<Level> path(static_cast<std::size_t>(sums_.steps()) + 1);
        path[0] = {sums_.axiom().data(), sums_.axiom().data() + sums_.axiom().size()};
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
            if (!tree_.hasProgram(s, level)) {
                const std::span<const Symbol> succ = sums_.successor(s, level);
                path[static_cast<std::size_t>(++level)] = {succ.data(), succ.data() + succ.size()};
                continue;
            }
            if ((programs++ & 0xFFF) == 0) cancel.check();
            runProgram(s, level);
        }
        return Box{t_.minX, t_.minY, t_.maxX, t_.maxY};
    }

  private:
    static void extend(Turtle& t, double px, double py) {
        t.minX = std::min(t.minX, px);
        t.minY = std::min(t.minY, py);
        t.maxX = std::max(t.maxX, px);
        t.maxY = std::max(t.maxY, py);
    }

    void runProgram(Symbol s, int level) {
        const DerivationTree::Program& p = tree_.program(s, level);
        const std::span<const std::uint8_t> ops = tree_.operations(p);
        if (!p.replayable || p.turns >= t_.untilOrthonormal) {
            perform<false>(t_, ops);
            return;
        }
        const ReplayKey key{p.id, bitCast<std::uint64_t>(t_.hx), bitCast<std::uint64_t>(t_.hy),
                            bitCast<std::uint64_t>(t_.lx), bitCast<std::uint64_t>(t_.ly)};
        // Past so many frames (a path that never repeats one) only known ones are looked up.
        auto found = replays_.find(key);
        if (found == replays_.end() && replays_.size() >= kReplayKeys) {
            perform<false>(t_, ops);
            return;
        }
        auto [it, fresh] = found != replays_.end() ? std::pair{found, false}
                                                   : replays_.try_emplace(key, kSeenOnce);
        if (it->second < kSeenOnce) {
            replay(t_, replayList_[it->second]);
            t_.untilOrthonormal -= p.turns;
            return;
        }
        // A program replays once it ran twice from a frame: many frames come only once.
        if (fresh || moves_.size() + p.moves > kReplayMoves) {
            perform<false>(t_, ops);
            return;
        }
        Replay r;
        r.moveStart = static_cast<std::uint32_t>(moves_.size());
        r.opStart = static_cast<std::uint32_t>(replayOps_.size());
        perform<true>(t_, ops);
        r.moveCount = static_cast<std::uint32_t>(moves_.size()) - r.moveStart;
        // Draws alone (branches that moved nothing left out) replay without a switch.
        const bool drawsOnly = std::all_of(replayOps_.begin() + r.opStart, replayOps_.end(),
                                           [](std::uint8_t op) { return op == kDraw; });
        r.opCount = drawsOnly ? 0 : static_cast<std::uint32_t>(replayOps_.size()) - r.opStart;
        if (drawsOnly) replayOps_.resize(r.opStart);
        r.hx = t_.hx, r.hy = t_.hy, r.lx = t_.lx, r.ly = t_.ly;
        it->second = static_cast<std::uint32_t>(replayList_.size());
        replayList_.push_back(r);
    }

    // Runs operations; with kRecord also notes what a replay needs.
    template <bool kRecord>
    void perform(Turtle& shared, std::span<const std::uint8_t> ops) {
        Turtle t = shared;  // in registers while the loop runs
        const double step = step_, c = cos_, sinLeft = sinLeft_, sinRight = sinRight_;
        for (const std::uint8_t op : ops) {
            switch (op) {
                case kDraw: {
                    if (!kViewVolume && !t.inBounds) extend(t, t.x, t.y);
                    const double dx = t.hx * step, dy = t.hy * step;
                    t.x = t.x + dx;
                    t.y = t.y + dy;
                    extend(t, t.x, t.y);
                    t.inBounds = true;
                    if (kRecord) {
                        moves_.push_back({dx, dy});
                        replayOps_.push_back(kDraw);
                    }
                    break;
                }
                case kMove: {
                    const double dx = t.hx * step, dy = t.hy * step;
                    t.x = t.x + dx;
                    t.y = t.y + dy;
                    if (kViewVolume) extend(t, t.x, t.y);
                    t.inBounds = false;
                    if (kRecord) {
                        moves_.push_back({dx, dy});
                        replayOps_.push_back(kMove);
                    }
                    break;
                }
                case kLeft:
                case kRight: {
                    const double sn = op == kLeft ? sinLeft : sinRight;
                    const double nhx = t.hx * c + t.lx * sn, nhy = t.hy * c + t.ly * sn;
                    const double nlx = t.lx * c + t.hx * (-sn), nly = t.ly * c + t.hy * (-sn);
                    t.hx = nhx;
                    t.hy = nhy;
                    t.lx = nlx;
                    t.ly = nly;
                    if (--t.untilOrthonormal == 0) {
                        t.untilOrthonormal = turtle::kOrthonormaliseEvery;
                        turtle::Frame f;
                        f.hx = t.hx, f.hy = t.hy, f.lx = t.lx, f.ly = t.ly;
                        turtle::orthonormalise(f);
                        t.hx = f.hx, t.hy = f.hy, t.lx = f.lx, t.ly = f.ly;
                    }
                    break;
                }
                case kAround:
                    t.hx = t.hx * -1.0;
                    t.hy = t.hy * -1.0;
                    t.lx = t.lx * -1.0;
                    t.ly = t.ly * -1.0;
                    break;
                case kPush:
                    *t.top++ = Saved{t.x, t.y, t.hx, t.hy, t.lx, t.ly, t.inBounds};
                    if (kRecord) replayOps_.push_back(kPush);
                    break;
                case kPop: {
                    const Saved& r = *--t.top;
                    t.x = r.x, t.y = r.y, t.hx = r.hx, t.hy = r.hy, t.lx = r.lx, t.ly = r.ly;
                    t.inBounds = r.inBounds;
                    if (kRecord) {
                        // A branch that moves nothing (a turn, a letter) changes nothing a
                        // replay keeps: it leaves it out.
                        if (!replayOps_.empty() && replayOps_.back() == kPush)
                            replayOps_.pop_back();
                        else
                            replayOps_.push_back(kPop);
                    }
                    break;
                }
                default:
                    break;
            }
        }
        shared = t;
    }

    // A program again from the frame it was recorded from: its additions, no turns.
    void replay(Turtle& shared, const Replay& r) {
        Turtle t = shared;
        const Move* move = moves_.data() + r.moveStart;
        if (r.opCount == 0) {  // draws only: the tightest loop
            if (!kViewVolume && !t.inBounds && r.moveCount > 0) extend(t, t.x, t.y);
            double x = t.x, y = t.y;
            double minX = t.minX, minY = t.minY, maxX = t.maxX, maxY = t.maxY;
            for (const Move* end = move + r.moveCount; move < end; ++move) {
                x = x + move->dx;
                y = y + move->dy;
                minX = std::min(minX, x);
                minY = std::min(minY, y);
                maxX = std::max(maxX, x);
                maxY = std::max(maxY, y);
            }
            t.x = x, t.y = y;
            t.minX = minX, t.minY = minY, t.maxX = maxX, t.maxY = maxY;
            if (r.moveCount > 0) t.inBounds = true;
        } else {
            const std::uint8_t* op = replayOps_.data() + r.opStart;
            for (const std::uint8_t* end = op + r.opCount; op < end; ++op) {
                switch (*op) {
                    case kDraw:
                        if (!kViewVolume && !t.inBounds) extend(t, t.x, t.y);
                        t.x = t.x + move->dx;
                        t.y = t.y + move->dy;
                        ++move;
                        extend(t, t.x, t.y);
                        t.inBounds = true;
                        break;
                    case kMove:
                        t.x = t.x + move->dx;
                        t.y = t.y + move->dy;
                        ++move;
                        if (kViewVolume) extend(t, t.x, t.y);
                        t.inBounds = false;
                        break;
                    case kPush:  // the frame in the saved place is never read back
                        *t.top++ = Saved{t.x, t.y, 0, 0, 0, 0, t.inBounds};
                        break;
                    default: {  // kPop
                        const Saved& s = *--t.top;
                        t.x = s.x, t.y = s.y;
                        t.inBounds = s.inBounds;
                        break;
                    }
                }
            }
        }
        t.hx = r.hx, t.hy = r.hy, t.lx = r.lx, t.ly = r.ly;
        shared = t;
    }

    struct Move {
        double dx, dy;
    };
    static constexpr std::uint32_t kSeenOnce = 0xFFFFFFFFu;
    // 16 bytes a move: 16 MiB at most, and a million frames looked up.
    static constexpr std::size_t kReplayMoves = std::size_t{1} << 20;
    static constexpr std::size_t kReplayKeys = std::size_t{1} << 20;

    const SubtreeSummaries& sums_;
    const DerivationTree& tree_;
    std::vector<Saved> stack_;
    Turtle t_;
    double step_ = 1, cos_ = 1, sinLeft_ = 0, sinRight_ = 0;
    std::unordered_map<ReplayKey, std::uint32_t, ReplayKeyHash> replays_;
    std::vector<Replay> replayList_;
    std::vector<Move> moves_;
    std::vector<std::uint8_t> replayOps_;
};

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
    // A ']' with nothing saved is the generic turtle's error to word; a stack of a million
    // branches is left to the turtle that grows its own.
    const DerivationTree::Depth depth = tree.depthOf(sums.axiom());
    if (depth.lowest < 0 || depth.highest > (std::int64_t{1} << 20)) return std::nullopt;

    m.baseWidth = static_cast<float>(view.turtle.initialWidth);
    const auto stackDepth = static_cast<std::size_t>(depth.highest);
    const Box b = which == MeasuredBox::CpfgViewVolume
                      ? Walk<true>(sums, tree, view, stackDepth).run(cancel)
                      : Walk<false>(sums, tree, view, stackDepth).run(cancel);
    // Every point extended has z = +0; the drawing's box is empty without a segment.
    if (which == MeasuredBox::CpfgViewVolume || m.segments > 0) {
        m.bounds.min = Vec3{b.minX, b.minY, 0};
        m.bounds.max = Vec3{b.maxX, b.maxY, 0};
    }
    return m;
}

}  // namespace graftal
