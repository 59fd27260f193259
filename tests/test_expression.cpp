#include <gtest/gtest.h>

#include <cmath>

#include "graftal/lang/expression.hpp"

using namespace graftal;

namespace {

double eval(const std::string& text, std::vector<std::string> vars = {},
            std::vector<double> values = {}) {
    DiagnosticList d;
    ExpressionScope scope;
    scope.variables = std::move(vars);
    std::map<std::string, std::string> defines{{"N", "1+2"}, {"R", "N*2"}};
    scope.defines = &defines;
    Expression e = compileExpression(text, {"t.l", 1, 1}, scope, d);
    if (d.hasErrors()) throw Error(d.items());
    return e.evaluate(values);
}

std::string error(const std::string& text) {
    try {
        eval(text, {"x"}, {1});
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "";
}

}  // namespace

TEST(Expression, ArithmeticPrecedenceAndAssociativity) {
    EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7);
    EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9);
    // cpfg's ^ groups to the left and a sign binds tighter (oracle s06_math).
    EXPECT_DOUBLE_EQ(eval("2 ^ 3 ^ 2"), 64);
    EXPECT_DOUBLE_EQ(eval("-2 ^ 2"), 4);
    EXPECT_DOUBLE_EQ(eval("2 * 3 ^ 2"), 18);
    // cpfg's % truncates both operands; its trunc rounds (oracle s06_math).
    EXPECT_DOUBLE_EQ(eval("7.9 % 3"), 1);
    EXPECT_DOUBLE_EQ(eval("-7 % 3"), -1);
    EXPECT_DOUBLE_EQ(eval("7 % 4"), 3);
    EXPECT_DOUBLE_EQ(eval("10 - 4 - 3"), 3);
    EXPECT_DOUBLE_EQ(eval("1.5e2"), 150);
}

TEST(Expression, ComparisonsAndLogic) {
    EXPECT_EQ(eval("1 < 2 && 3 >= 3"), 1);
    EXPECT_EQ(eval("1 > 2 || 0"), 0);
    EXPECT_EQ(eval("!(1 == 1)"), 0);
    EXPECT_EQ(eval("2 != 3"), 1);
    EXPECT_EQ(eval("0 && 1/0"), 0) << "&& short-circuits";
    EXPECT_EQ(eval("5 || 1/0"), 1) << "|| short-circuits";
}

TEST(Expression, FunctionsUseDegrees) {
    EXPECT_NEAR(eval("sin(30)"), 0.5, 1e-12);
    EXPECT_NEAR(eval("cos(60)"), 0.5, 1e-12);
    EXPECT_NEAR(eval("atan2(1, 1)"), 45, 1e-12);
    EXPECT_NEAR(eval("asin(1)"), 90, 1e-12);
    EXPECT_DOUBLE_EQ(eval("min(3, max(1, 2))"), 2);
    EXPECT_DOUBLE_EQ(eval("sign(-4) + fabs(-2) + floor(2.7) + ceil(0.2) + trunc(-1.5)"),
                     -1 + 2 + 2 + 1 - 1);
    EXPECT_NEAR(eval("exp(log(5)) + sqrt(16)"), 9, 1e-12);
}

TEST(Expression, VariablesAndDefines) {
    EXPECT_DOUBLE_EQ(eval("x * y", {"x", "y"}, {3, 4}), 12);
    EXPECT_DOUBLE_EQ(eval("2 * N"), 6) << "a #define is parenthesised";
    EXPECT_DOUBLE_EQ(eval("R"), 6);
}

TEST(Expression, ErrorsCarryTheColumn) {
    EXPECT_EQ(error("x + y"),
              "t.l:1:5: error: unknown name 'y' (not a parameter of this production)");
    EXPECT_EQ(error("sin(1, 2)"), "t.l:1:1: error: sin() takes 1 argument, not 2");
    EXPECT_EQ(error("foo(1)"), "t.l:1:1: error: unknown function 'foo'");
    EXPECT_EQ(error("(1 + 2"), "t.l:1:7: error: expected ')'");
    EXPECT_EQ(error("1 +"),
              "t.l:1:4: error: expected a number, a name or '(' but the expression ended");
    EXPECT_EQ(error("x = 1"), "t.l:1:3: error: expected '==' for a comparison, found '='");
}

// cpfg divides by 1 instead, and warns where printing is possible (oracle s06_math).
TEST(Expression, DivisionByZeroDividesByOne) {
    EXPECT_DOUBLE_EQ(eval("x / (x - 1)", {"x"}, {1}), 1);
    DiagnosticList diags;
    Expression e = compileExpression("3 / 0", {"t.l", 1, 1}, {}, diags);
    std::string printed;
    std::function<void(std::string_view)> sink = [&](std::string_view t) { printed += t; };
    EvalContext ctx;
    ctx.print = &sink;
    EXPECT_DOUBLE_EQ(e.evaluate({}, &ctx), 3);
    EXPECT_EQ(printed,
              "t.l:1:1: warning: division by zero in '3 / 0'; dividing by 1 instead "
              "(as cpfg)\n");
}

TEST(Expression, RandomNeedsAStream) {
    DiagnosticList d;
    ExpressionScope scope;
    Expression e = compileExpression("ran(10)", {"t.l", 1, 1}, scope, d);
    ASSERT_FALSE(d.hasErrors());
    EXPECT_TRUE(e.usesRandom());
    EvalContext ctx;
    ctx.uniform = [] { return 0.25; };
    EXPECT_DOUBLE_EQ(e.evaluate({}, &ctx), 2.5);
    EXPECT_THROW(e.evaluate({}), Error);
}
