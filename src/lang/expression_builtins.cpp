// The built-in functions of expressions: their names and arities, and what they compute.
#include "expression_builtins.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "graftal/core/random_stream.hpp"

namespace graftal {

namespace {

// x * kDegree, not radians(x): sin(), cos(), ... have always rounded π/180 once and
// multiplied by it, and the values models draw with must not move in their last bit.
constexpr double kDegree = std::numbers::pi / 180.0;

enum Fn1 : std::uint8_t {
    FnSin,
    FnCos,
    FnTan,
    FnAsin,
    FnAcos,
    FnAtan,
    FnExp,
    FnLog,
    FnSqrt,
    FnFabs,
    FnFloor,
    FnCeil,
    FnTrunc,
    FnSign,
    FnStop,
};
enum Fn2 : std::uint8_t { FnAtan2, FnMin, FnMax };

// cpfg's trigonometry works in degrees, and so do we.
constexpr std::array kFunctions{
    FunctionInfo{"sin", 1, FnSin},   FunctionInfo{"cos", 1, FnCos},
    FunctionInfo{"tan", 1, FnTan},   FunctionInfo{"asin", 1, FnAsin},
    FunctionInfo{"acos", 1, FnAcos}, FunctionInfo{"atan", 1, FnAtan},
    FunctionInfo{"exp", 1, FnExp},   FunctionInfo{"log", 1, FnLog},
    FunctionInfo{"sqrt", 1, FnSqrt}, FunctionInfo{"fabs", 1, FnFabs},
    FunctionInfo{"abs", 1, FnFabs},  FunctionInfo{"floor", 1, FnFloor},
    FunctionInfo{"ceil", 1, FnCeil}, FunctionInfo{"trunc", 1, FnTrunc},
    FunctionInfo{"sign", 1, FnSign}, FunctionInfo{"atan2", 2, FnAtan2},
    FunctionInfo{"min", 2, FnMin},   FunctionInfo{"max", 2, FnMax},
    FunctionInfo{"ran", 1, 0},       FunctionInfo{"nran", 2, 0},
    FunctionInfo{"bran", 2, 0},      FunctionInfo{"biran", 2, 0},
    FunctionInfo{"srand", 1, 0},     FunctionInfo{"func", 2, 0},
    FunctionInfo{"curveX", 2, 0},    FunctionInfo{"curveY", 2, 1},
    FunctionInfo{"curveZ", 2, 2},    FunctionInfo{"curveGAL", 1, 0},
    FunctionInfo{"stop", 1, FnStop},
};

// A gamma(shape, 1) deviate (Marsaglia and Tsang), from uniform numbers.
double gammaDeviate(double shape, const std::function<double()>& uniform) {
    if (shape < 1) {
        double u = uniform();
        return gammaDeviate(shape + 1, uniform) * std::pow(u > 0 ? u : 1e-300, 1 / shape);
    }
    const double d = shape - 1.0 / 3, c = 1 / std::sqrt(9 * d);
    for (int tries = 0; tries < 1000; ++tries) {
        double x = normalDeviate(uniform);
        double v = 1 + c * x;
        if (v <= 0) continue;
        v = v * v * v;
        double u = uniform();
        if (u > 0 && std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v;
    }
    return d;
}

}  // namespace

const FunctionInfo* findFunction(std::string_view name) {
    for (const auto& f : kFunctions)
        if (name == f.name) return &f;
    return nullptr;
}

double applyFunction1(std::uint8_t fn, double x) {
    switch (fn) {
        case FnSin:
            return std::sin(x * kDegree);
        case FnCos:
            return std::cos(x * kDegree);
        case FnTan:
            return std::tan(x * kDegree);
        case FnAsin:
            return std::asin(x) / kDegree;
        case FnAcos:
            return std::acos(x) / kDegree;
        case FnAtan:
            return std::atan(x) / kDegree;
        case FnExp:
            return std::exp(x);
        case FnLog:
            return std::log(x);
        case FnSqrt:
            return std::sqrt(x);
        case FnFabs:
            return std::fabs(x);
        case FnFloor:
            return std::floor(x);
        case FnCeil:
            return std::ceil(x);
        case FnTrunc:
            return std::floor(x + 0.5);  // cpfg's trunc rounds to the nearest whole number
        case FnSign:
            return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
        case FnStop:
            // cpfg's stop(x) stops (or, with 1, pauses) its animation and leaves x as its
            // value; it changes nothing in the derivation.
            return x;
    }
    return 0;
}

double applyFunction2(std::uint8_t fn, double a, double b) {
    switch (fn) {
        case FnAtan2:
            return std::atan2(a, b) / kDegree;
        case FnMin:
            return std::min(a, b);
        case FnMax:
            return std::max(a, b);
    }
    return 0;
}

double betaDeviate(double a, double b, const std::function<double()>& uniform) {
    // Two gamma deviates, a's drawn first: x / (x + y) is beta(a, b).
    double x = gammaDeviate(a, uniform);
    double y = gammaDeviate(b, uniform);
    return x + y > 0 ? x / (x + y) : 0.5;
}

}  // namespace graftal
