// The turtle walks the module string once, with a per-symbol operation table, and
// appends plain geometry to a Scene.
#include "graftal/turtle.hpp"

#include <array>
#include <cmath>

namespace graftal {

namespace {

enum class TurtleOp : std::uint8_t {
    None, Forward, Move, TurnLeft, TurnRight, PitchDown, PitchUp, RollLeft, RollRight,
    TurnAround, Push, Pop, PolygonBegin, PolygonEnd, WidthDown, WidthUp, ColorNext,
    ColorPrevious,
};

constexpr double kPi = 3.14159265358979323846;

TurtleOp opFor(Symbol s) {
    switch (s) {
        case 'F': return TurtleOp::Forward;
        case 'f': return TurtleOp::Move;
        case '+': return TurtleOp::TurnLeft;
        case '-': return TurtleOp::TurnRight;
        case '&': return TurtleOp::PitchDown;
        case '^': return TurtleOp::PitchUp;
        case '\\': return TurtleOp::RollLeft;
        case '/': return TurtleOp::RollRight;
        case '|': return TurtleOp::TurnAround;
        case '[': return TurtleOp::Push;
        case ']': return TurtleOp::Pop;
        case '{': return TurtleOp::PolygonBegin;
        case '}': return TurtleOp::PolygonEnd;
        case '!': return TurtleOp::WidthDown;
        case '#': return TurtleOp::WidthUp;
        case '\'':
        case ';': return TurtleOp::ColorNext;
        case ',': return TurtleOp::ColorPrevious;
        default: return TurtleOp::None;
    }
}

Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator*(Vec3 a, double k) { return {a.x * k, a.y * k, a.z * k}; }

struct TurtleState {
    Vec3 position;
    Vec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, 1};  // H x L = U
    float width = 1;
    std::uint16_t color = 0;
};

using Visitor = std::function<void(std::size_t, const TurtleFrame&)>;

// Rotates the pair (a, b) by angle: a' = a cos + b sin, b' = b cos - a sin.
void rotatePair(Vec3& a, Vec3& b, double radians) {
    double c = std::cos(radians), s = std::sin(radians);
    Vec3 na = a * c + b * s;
    Vec3 nb = b * c + a * (-s);
    a = na;
    b = nb;
}

class Turtle {
public:
    // With `scene` null the turtle only walks (for query modules and environments).
    Turtle(const LSystem& ls, Scene* scene) : ls_(ls), scene_(scene) {
        for (std::size_t s = 0; s < ops_.size(); ++s)
            ops_[s] = s < ls.symbols.size() ? opFor(static_cast<Symbol>(s)) : TurtleOp::None;
        delta_ = ls.view.angleDegrees * kPi / 180.0;
        turnSign_ = ls.view.clockwisePlus ? -1.0 : 1.0;
        rotatePair(state_.heading, state_.left, ls.view.initialHeading * kPi / 180.0);
    }

    void run(const ModuleString& m, const std::vector<bool>* wanted = nullptr,
             const Visitor* visit = nullptr) {
        std::span<const Symbol> syms = m.symbols();
        bool params = m.hasParameters();
        for (std::size_t i = 0; i < syms.size(); ++i) {
            if (wanted && syms[i] < wanted->size() && (*wanted)[syms[i]])
                (*visit)(i, TurtleFrame{state_.position, state_.heading, state_.left, state_.up});
            TurtleOp op = ops_[syms[i]];
            if (op == TurtleOp::None) continue;
            std::span<const double> args = params ? m.params(i) : std::span<const double>{};
            apply(op, args, i);
        }
        if (!polygons_.empty())
            throw Error(SourceLocation{ls_.file, 0, 0},
                        "the derived string leaves a '{' open (module " +
                            std::to_string(polygonOpenedAt_.back()) +
                            "): expected a matching '}'");
    }

private:
    double angleArg(std::span<const double> args) const {
        return args.empty() ? delta_ : args[0] * kPi / 180.0;
    }

    void forward(double length, bool draw) {
        Vec3 from = state_.position;
        state_.position = from + state_.heading * length;
        if (!scene_) return;
        if (!polygons_.empty()) {
            polygons_.back().push_back(state_.position);
        } else if (draw) {
            scene_->segments.push_back({from, state_.position, state_.width, state_.color});
        }
    }

    void apply(TurtleOp op, std::span<const double> args, std::size_t index) {
        switch (op) {
            case TurtleOp::None: break;
            case TurtleOp::Forward:
                forward(args.empty() ? ls_.view.stepLength : args[0], true);
                break;
            case TurtleOp::Move:
                forward(args.empty() ? ls_.view.stepLength : args[0], false);
                break;
            case TurtleOp::TurnLeft:
                rotatePair(state_.heading, state_.left, turnSign_ * angleArg(args));
                break;
            case TurtleOp::TurnRight:
                rotatePair(state_.heading, state_.left, -turnSign_ * angleArg(args));
                break;
            case TurtleOp::TurnAround: rotatePair(state_.heading, state_.left, kPi); break;
            case TurtleOp::PitchDown:
                rotatePair(state_.heading, state_.up, -angleArg(args));
                break;
            case TurtleOp::PitchUp: rotatePair(state_.heading, state_.up, angleArg(args)); break;
            case TurtleOp::RollLeft: rotatePair(state_.left, state_.up, angleArg(args)); break;
            case TurtleOp::RollRight: rotatePair(state_.left, state_.up, -angleArg(args)); break;
            case TurtleOp::Push: stack_.push_back(state_); break;
            case TurtleOp::Pop:
                if (stack_.empty())
                    throw Error(SourceLocation{ls_.file, 0, 0},
                                "']' at module " + std::to_string(index) +
                                    " of the derived string pops an empty turtle stack "
                                    "(more ']' than '[')");
                state_ = stack_.back();
                stack_.pop_back();
                break;
            case TurtleOp::PolygonBegin:
                polygons_.emplace_back();
                polygons_.back().push_back(state_.position);
                polygonOpenedAt_.push_back(index);
                break;
            case TurtleOp::PolygonEnd:
                if (polygons_.empty())
                    throw Error(SourceLocation{ls_.file, 0, 0},
                                "'}' at module " + std::to_string(index) +
                                    " of the derived string closes no polygon (no '{' is open)");
                if (scene_ && polygons_.back().size() >= 3)
                    scene_->addPolygon(polygons_.back(), state_.color);
                polygons_.pop_back();
                polygonOpenedAt_.pop_back();
                break;
            case TurtleOp::WidthDown:
                state_.width = args.empty() ? state_.width * 0.7f : static_cast<float>(args[0]);
                break;
            case TurtleOp::WidthUp:
                state_.width = args.empty() ? state_.width / 0.7f : static_cast<float>(args[0]);
                break;
            case TurtleOp::ColorNext:
                state_.color = args.empty() ? static_cast<std::uint16_t>(state_.color + 1)
                                            : static_cast<std::uint16_t>(args[0]);
                break;
            case TurtleOp::ColorPrevious:
                if (!args.empty()) state_.color = static_cast<std::uint16_t>(args[0]);
                else if (state_.color > 0) --state_.color;
                break;
        }
    }

    const LSystem& ls_;
    Scene* scene_;
    std::array<TurtleOp, kMaxSymbols> ops_{};
    double delta_ = 0, turnSign_ = 1;
    TurtleState state_;
    std::vector<TurtleState> stack_;
    std::vector<std::vector<Vec3>> polygons_;
    std::vector<std::size_t> polygonOpenedAt_;
};

}  // namespace

Scene interpret(const LSystem& lsystem, const ModuleString& modules) {
    Scene scene;
    Turtle turtle(lsystem, &scene);
    turtle.run(modules);
    return scene;
}

void traceTurtle(const LSystem& lsystem, const ModuleString& modules,
                 const std::vector<bool>& wanted, const Visitor& visit) {
    Turtle turtle(lsystem, nullptr);
    turtle.run(modules, &wanted, &visit);
}

}  // namespace graftal
