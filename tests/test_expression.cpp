#include <gtest/gtest.h>

#include <cmath>

#include "graftal/graftal.hpp"
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

TEST(Expression, UserFunctionsAnswerFuncBeforeTheViewFile) {
    DiagnosticList d;
    ExpressionScope scope;
    scope.variables = {"x"};
    Expression e = compileExpression("func(2, x) + 1", {"t.l", 1, 1}, scope, d);
    ASSERT_FALSE(d.hasErrors());
    const std::vector<UserFunction> table = {{}, [](double x) { return 10 * x; }};
    EvalContext ctx;
    ctx.userFunctions = &table;
    const std::vector<double> slots = {0.5};
    EXPECT_DOUBLE_EQ(e.evaluate(slots, &ctx), 6);
    // An id the program leaves empty (1) is the view file's: here there is none.
    Expression first = compileExpression("func(1, x)", {"t.l", 1, 1}, scope, d);
    try {
        first.evaluate(slots, &ctx);
        FAIL() << "func(1, x) has no function";
    } catch (const Error& err) {
        EXPECT_NE(err.diagnostics().front().message.find("names no function"), std::string::npos);
    }
}

TEST(Expression, AUserFunctionsErrorNamesTheProductionModuleAndStep) {
    ParseOptions options;
    options.fileName = "user.l";
    Model m = parse(
                  "Lsystem: 1\nderivation length: 3\naxiom: A(0)\n"
                  "A(t) : * --> F(func(1, t)) A(t + 1)\nendlsystem\n",
                  options)
                  .orThrow();
    auto table = std::make_shared<std::vector<UserFunction>>();
    table->push_back([](double t) {
        if (t >= 2) throw Error(SourceLocation{}, "too late");
        return t * t + 1;
    });
    m.lsystem.userFunctions = table;
    EXPECT_EQ(derive(m, 2).toString(m.lsystem.symbols), "F(1)F(2)A(2)");
    try {
        derive(m, 3);
        FAIL() << "the function refuses t = 2";
    } catch (const Error& err) {
        EXPECT_EQ(err.diagnostics().front().toString(),
                  "user.l:4:1: error: 'func(1, t)': func(1, 2) failed: too late (while "
                  "rewriting module 2 'A(2)' in derivation step 3)");
    }
}
