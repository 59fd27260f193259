// The built-in functions of expressions (sin, cos, ..., ran, nran, bran, biran, func,
// curveX): the compiler looks up their names and arities, the interpreter computes them.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

namespace graftal {

struct FunctionInfo {
    const char* name;
    int arity;
    // For Call1/Call2 the function applyFunction1/2 computes; for curveX/Y/Z the
    // coordinate (0, 1, 2); otherwise 0.
    std::uint8_t id;
};

// The built-in function called `name`, or nullptr. printf and the file functions (fopen,
// fprintf, fclose, fflush) take strings and are parsed apart; they are not in the table.
const FunctionInfo* findFunction(std::string_view name);

// The one-argument function `fn` (Expression::Op::Call1) at x; trigonometry in degrees.
double applyFunction1(std::uint8_t fn, double x);
// The two-argument function `fn` (Expression::Op::Call2) at (a, b).
double applyFunction2(std::uint8_t fn, double a, double b);

// bran(a, b): a beta(a, b) deviate in [0, 1] from uniform numbers in [0, 1); a and b > 0.
double betaDeviate(double a, double b, const std::function<double()>& uniform);

}  // namespace graftal
