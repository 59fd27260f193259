// Arithmetic expressions of the .l language, compiled once to a small stack program.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/curve_xyz.hpp"
#include "graftal/lang/graphical_function.hpp"

namespace graftal {

// Files a model writes with fopen/fprintf/fclose/fflush (cpfg's file output). Handles are
// numbers the model keeps in variables; 0 is never a valid handle.
class OutputFiles {
  public:
    virtual ~OutputFiles() = default;
    // Throws Error (at `where`) when the file may not or cannot be written.
    virtual double open(const std::string& name, bool append, const SourceLocation& where) = 0;
    virtual void write(double handle, std::string_view text, const SourceLocation& where) = 0;
    virtual void flush(double handle, const SourceLocation& where) = 0;
    virtual void close(double handle, const SourceLocation& where) = 0;
};

// What a running expression may need besides its variables: random numbers from the
// L-system's counter-based stream. Deterministic code passes nullptr.
class CpfgRandom;

// A function the program embedding the library supplies in place of a graphical function:
// func(id, x) calls the id-th one, when set, with x (LSystem::userFunctions). The
// derivation's threads may call it at once. It throws Error to stop the derivation; the
// expression then names itself and the call in the error.
using UserFunction = std::function<double(double x)>;

struct EvalContext {
    // Returns a uniform number in [0, 1); called once per ran()/nran() evaluation.
    std::function<double()> uniform;
    // srand(seed): restarts the stream that uniform() draws from at `seed`.
    std::function<void(double)> reseed;
    // When set, ran, nran, bran, biran and srand are cpfg's own, on cpfg's generator
    // (cpfg_random.hpp), in place of uniform() and reseed().
    CpfgRandom* cpfgRandom = nullptr;
    // The L-system's state (LSystem::stateNames): read by names that are not parameters.
    const double* state = nullptr;
    // Where printf writes (the library never prints itself). nullptr: output is dropped.
    const std::function<void(std::string_view)>* print = nullptr;
    // Where fopen/fprintf go. nullptr: using them is an error.
    OutputFiles* files = nullptr;
    // The graphical functions func(id, x) reads (LSystem::functions), id counted from 1.
    const std::vector<GraphicalFunction>* functions = nullptr;
    // The program's functions func(id, x) calls before the graphical ones, id counted from
    // 1; an empty one leaves that id to the view file's function.
    const std::vector<UserFunction>* userFunctions = nullptr;
    // The curves curveX/Y/Z(id, t) and curveGAL(id) read (LSystem::curves), id from 1.
    const std::vector<CurveXYZ>* curves = nullptr;
};

class Expression {
  public:
    enum class Op : std::uint8_t {
        Const,
        Var,
        Neg,
        Not,
        Add,
        Sub,
        Mul,
        Div,
        Mod,
        Pow,
        Lt,
        Le,
        Gt,
        Ge,
        Eq,
        Ne,
        And,
        Or,
        Call1,
        Call2,
        Ran,
        Nran,
        Load,     // state[arg]
        Printf,   // strings_[arg] formatted with the fn values on the stack; gives 0
        Select,   // c ? a : b with all three on the stack
        Bran,     // bran(a, b): beta distributed in [0, 1]
        Biran,    // biran(n, p): binomial, a whole number in 0..n
        Srand,    // srand(seed): restarts the random stream, gives 0
        Element,  // arrays_[arg] indexed by the values on the stack; fn 1: its slot number
        Fopen,    // fopen(strings_[arg], mode): a handle
        Fprintf,  // fprintf(handle, strings_[arg], fn values): 0
        Fclose,   // fclose(handle): 0
        Fflush,   // fflush(handle): 0
        JumpIfFalse,
        JumpIfTrue,
        Jump,
        Pop,
        Func,         // func(id, x): the id-th user or graphical function of the EvalContext
        Curve,        // curveX/Y/Z(id, t): coordinate fn (0, 1, 2) of the id-th curve at t
        CurveLength,  // curveGAL(id): the length of the id-th curve
    };
    struct Instr {
        Op op;
        std::uint8_t fn = 0;    // function id for Call1/Call2
        std::uint32_t arg = 0;  // constant index, variable slot, or jump target
    };

    Expression() = default;

    // Evaluates with `slots` holding the bound variables. Throws Error (with this
    // expression's location) on a division by zero or a domain error (a function or ^
    // giving nan or infinity).
    double evaluate(std::span<const double> slots, const EvalContext* ctx = nullptr) const {
        // The shapes most successor arguments have, inline: a derivation step evaluates
        // them for millions of modules. Each does the program's one operation on the same
        // operands, so the result is the same double.
        switch (shape_) {
            case Shape::Constant:
                return a_;
            case Shape::Variable:
                return slots[slot_];
            case Shape::VariableConstant:
                return apply(slots[slot_], a_);
            case Shape::ConstantVariable:
                return apply(a_, slots[slot_]);
            case Shape::Program:
                break;
        }
        return run(slots, ctx);
    }

    bool isConstant() const { return code_.size() == 1 && code_[0].op == Op::Const; }
    bool empty() const { return code_.empty(); }
    bool usesRandom() const { return usesRandom_; }
    // Reads the state or prints: needs an EvalContext with `state` (and `print`).
    bool usesState() const { return usesState_; }
    bool prints() const { return prints_; }
    bool needsContext() const { return usesRandom_ || usesState_ || prints_ || usesFunctions_; }
    const std::string& text() const { return text_; }
    const SourceLocation& location() const { return location_; }
    void print(std::ostream& os) const { os << text_; }

  private:
    friend class ExpressionCompiler;
    // Program: anything else, run by the interpreter. Only +, -, * and / by a nonzero
    // constant make the two-operand shapes: they cannot fail.
    enum class Shape : std::uint8_t {
        Program,
        Constant,
        Variable,
        VariableConstant,
        ConstantVariable
    };
    double apply(double x, double y) const {
        switch (op_) {
            case Op::Add:
                return x + y;
            case Op::Sub:
                return x - y;
            case Op::Mul:
                return x * y;
            default:
                return x / y;
        }
    }
    double run(std::span<const double> slots, const EvalContext* ctx) const;
    double callUserFunction(const UserFunction& f, double id, double x) const;
    void findShape();

    Shape shape_ = Shape::Program;
    Op op_ = Op::Add;
    std::uint32_t slot_ = 0;
    double a_ = 0;  // the constant of the shape
    std::vector<Instr> code_;
    std::vector<double> constants_;
    std::vector<std::string> strings_;  // printf formats, escapes resolved
    struct ArrayRef {
        std::string name;
        std::uint32_t base = 0;
        std::vector<std::uint32_t> dims;
    };
    std::vector<ArrayRef> arrays_;  // arrays the program indexes
    std::string text_;
    SourceLocation location_;
    bool usesRandom_ = false;
    bool usesState_ = false;
    bool prints_ = false;
    bool usesFunctions_ = false;
    std::uint32_t maxStack_ = 0;
};

std::ostream& operator<<(std::ostream& os, const Expression& e);

// A global array: its elements are state slots base .. base + product(dims) - 1, row-major.
struct ArrayShape {
    std::uint32_t base = 0;
    std::vector<std::uint32_t> dims;
};

// Names an expression may use: formal parameters (slots) and #define constants.
struct ExpressionScope {
    std::vector<std::string> variables;                           // slot i is variables[i]
    const std::map<std::string, std::string>* defines = nullptr;  // NAME -> expression text
    // Names that are state slots (LSystem::stateNames) -> slot: the globals and, in a
    // production, its own variables.
    const std::map<std::string, std::uint32_t>* state = nullptr;
    const std::map<std::string, ArrayShape>* arrays = nullptr;  // `define: { array ... }`
};

// Compiles `name[i][j]...` (text at `loc`) to a program giving the element's state slot,
// for assignments to array elements.
Expression compileElementAddress(std::string_view text, const SourceLocation& loc,
                                 const ExpressionScope& scope, DiagnosticList& diags);

// Compiles `text` (which starts at `loc`). Problems go to `diags` with exact columns; the
// returned expression is then empty.
Expression compileExpression(std::string_view text, const SourceLocation& loc,
                             const ExpressionScope& scope, DiagnosticList& diags);

// printf's formatting of `values` (every value a double, as in cpfg).
std::string formatPrintf(std::string_view format, std::span<const double> values);

// Convenience for constant expressions (view settings, derivation length): throws Error.
double evaluateConstant(std::string_view text, const SourceLocation& loc,
                        const std::map<std::string, std::string>& defines);

}  // namespace graftal
