// Recursive-descent compiler from expression text to a postfix program, and its evaluator.
#include "graftal/expression.hpp"
#include "graftal/module_string.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <set>

namespace graftal {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

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
};
enum Fn2 : std::uint8_t { FnAtan2, FnMin, FnMax };

struct FunctionInfo {
    const char* name;
    int arity;
    std::uint8_t id;
};

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
};

}  // namespace

class ExpressionCompiler {
  public:
    ExpressionCompiler(std::string_view text, const SourceLocation& loc,
                       const ExpressionScope& scope, DiagnosticList& diags)
        : text_(text), loc_(loc), scope_(scope), diags_(diags) {}

    // `name[...]...` only, compiled to the element's slot number.
    Expression compileAddress() {
        expr_.text_ = std::string(trim(text_));
        expr_.location_ = loc_;
        skipSpace();
        std::size_t start = pos_;
        while (pos_ < text_.size() &&
               (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
            ++pos_;
        std::string name(text_.substr(start, pos_ - start));
        if (!parseElement(name, start, true)) fail(start, "'" + name + "' is not an array");
        skipSpace();
        if (!failed_ && pos_ < text_.size())
            fail(pos_, "unexpected '" + std::string(1, text_[pos_]) + "' after the element");
        if (failed_) return Expression{};
        computeStackDepth();
        return std::move(expr_);
    }

    Expression compile() {
        expr_.text_ = std::string(trim(text_));
        expr_.location_ = loc_;
        skipSpace();
        if (pos_ >= text_.size()) {
            fail(pos_, "expected an expression");
        } else {
            parseTernary();
            skipSpace();
            if (!failed_ && pos_ < text_.size())
                fail(pos_, "unexpected '" + std::string(1, text_[pos_]) +
                               "' after the end of the expression");
        }
        if (failed_) return Expression{};
        computeStackDepth();
        expr_.findShape();
        return std::move(expr_);
    }

  private:
    static std::string_view trim(std::string_view s) {
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
            s.remove_prefix(1);
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
        return s;
    }

    SourceLocation at(std::size_t offset) const {
        SourceLocation l = loc_;
        if (l.line > 0) l.column += static_cast<int>(offset);
        return l;
    }

    void fail(std::size_t offset, const std::string& msg) {
        if (!failed_) diags_.error(at(offset), msg);
        failed_ = true;
    }

    // A limit on nesting or size: reported as is, even from inside a #define.
    void limit(std::size_t offset, const std::string& msg) {
        if (!failed_) limitMessage_ = msg;
        fail(offset, msg);
    }

    void skipSpace() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }

    bool accept(std::string_view tok) {
        skipSpace();
        if (text_.substr(pos_, tok.size()) == tok) {
            pos_ += tok.size();
            return true;
        }
        return false;
    }

    void emit(Expression::Op op, std::uint32_t arg = 0, std::uint8_t fn = 0) {
        expr_.code_.push_back({op, fn, arg});
    }

    void emitConst(double v) {
        expr_.constants_.push_back(v);
        emit(Expression::Op::Const, static_cast<std::uint32_t>(expr_.constants_.size() - 1));
    }

    // cpfg's `c ? a : b` (both branches are evaluated, as they have no side effects
    // other than printf).
    void parseTernary() {
        parseOr();
        if (!failed_ && accept("?")) {
            parseTernary();
            if (failed_) return;
            if (!accept(":")) {
                fail(pos_, "expected ':' in 'condition ? value : value'");
                return;
            }
            parseTernary();
            emit(Expression::Op::Select);
        }
    }

    void parseOr() {
        parseAnd();
        while (!failed_ && accept("||")) {
            std::size_t jump = expr_.code_.size();
            emit(Expression::Op::JumpIfTrue);
            parseAnd();
            emit(Expression::Op::Ne, 0);  // normalise the right operand to 0/1
            expr_.code_[jump].arg = static_cast<std::uint32_t>(expr_.code_.size());
        }
    }

    void parseAnd() {
        parseComparison();
        while (!failed_ && accept("&&")) {
            std::size_t jump = expr_.code_.size();
            emit(Expression::Op::JumpIfFalse);
            parseComparison();
            emit(Expression::Op::Ne, 0);
            expr_.code_[jump].arg = static_cast<std::uint32_t>(expr_.code_.size());
        }
    }

    void parseComparison() {
        parseAdditive();
        while (!failed_) {
            Expression::Op op;
            if (accept("<>"))
                op = Expression::Op::Ne;
            else if (accept("<="))
                op = Expression::Op::Le;
            else if (accept(">="))
                op = Expression::Op::Ge;
            else if (accept("=="))
                op = Expression::Op::Eq;
            else if (accept("!="))
                op = Expression::Op::Ne;
            else if (accept("<"))
                op = Expression::Op::Lt;
            else if (accept(">"))
                op = Expression::Op::Gt;
            else if (peekSingle('=')) {
                fail(pos_, "expected '==' for a comparison, found '='");
                return;
            } else
                return;
            parseAdditive();
            emit(op, 1);
        }
    }

    bool peekSingle(char c) {
        skipSpace();
        return pos_ < text_.size() && text_[pos_] == c;
    }

    void parseAdditive() {
        parseMultiplicative();
        while (!failed_) {
            if (accept("+")) {
                parseMultiplicative();
                emit(Expression::Op::Add);
            } else if (accept("-")) {
                parseMultiplicative();
                emit(Expression::Op::Sub);
            } else
                return;
        }
    }

    void parseMultiplicative() {
        parsePower();
        while (!failed_) {
            if (accept("*")) {
                parsePower();
                emit(Expression::Op::Mul);
            } else if (accept("/")) {
                parsePower();
                emit(Expression::Op::Div);
            } else if (accept("%")) {
                parsePower();
                emit(Expression::Op::Mod);
            } else
                return;
        }
    }

    void parseUnary() {
        // Every nesting (parentheses, arguments, unary signs, powers, #define) passes here;
        // bounding it keeps a hostile file from overflowing the stack.
        if (depth_ >= kMaxNesting) {
            limit(pos_,
                  "expression nested more than " + std::to_string(kMaxNesting) + " levels deep");
            return;
        }
        ++depth_;
        parseUnaryBelowLimit();
        --depth_;
    }

    void parseUnaryBelowLimit() {
        if (accept("-")) {
            parseUnary();
            emit(Expression::Op::Neg);
            return;
        }
        if (accept("+")) {
            parseUnary();
            return;
        }
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == '!' && text_.substr(pos_, 2) != "!=") {
            ++pos_;
            parseUnary();
            emit(Expression::Op::Not);
            return;
        }
        parsePrimary();
    }

    // cpfg's ^: a sign binds tighter (-2^2 = 4) and it groups to the left (2^3^2 = 64).
    void parsePower() {
        parseUnary();
        while (!failed_ && accept("^")) {
            parseUnary();
            emit(Expression::Op::Pow);
        }
    }

    void parsePrimary() {
        skipSpace();
        if (pos_ >= text_.size()) {
            fail(pos_, "expected a number, a name or '(' but the expression ended");
            return;
        }
        char c = text_[pos_];
        if (c == '(') {
            ++pos_;
            parseTernary();
            if (!failed_ && !accept(")")) fail(pos_, "expected ')'");
            return;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
            parseNumber();
            return;
        }
        if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            std::size_t start = pos_;
            while (pos_ < text_.size() &&
                   (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
                ++pos_;
            std::string name(text_.substr(start, pos_ - start));
            skipSpace();
            if (pos_ < text_.size() && text_[pos_] == '[' && parseElement(name, start, false))
                return;
            if (pos_ < text_.size() && text_[pos_] == '(') {
                parseCall(name, start);
            } else {
                parseName(name, start);
            }
            return;
        }
        fail(pos_, "expected a number, a name or '(' but found '" + std::string(1, c) + "'");
    }

    void parseNumber() {
        std::size_t start = pos_;
        while (pos_ < text_.size() &&
               (std::isdigit(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.'))
            ++pos_;
        if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
            std::size_t save = pos_++;
            if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
            if (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) {
                while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_])))
                    ++pos_;
            } else {
                pos_ = save;
            }
        }
        double v = 0;
        auto r = std::from_chars(text_.data() + start, text_.data() + pos_, v);
        if (r.ec != std::errc() || r.ptr != text_.data() + pos_) {
            fail(start,
                 "malformed number '" + std::string(text_.substr(start, pos_ - start)) + "'");
            return;
        }
        emitConst(v);
    }

    void parseName(const std::string& name, std::size_t start) {
        for (std::size_t i = 0; i < scope_.variables.size(); ++i) {
            if (scope_.variables[i] == name) {
                emit(Expression::Op::Var, static_cast<std::uint32_t>(i));
                return;
            }
        }
        if (scope_.defines) {
            auto it = scope_.defines->find(name);
            if (it != scope_.defines->end()) {
                if (expanding_.count(name)) {
                    fail(start, "#define '" + name + "' refers to itself");
                    return;
                }
                const CompiledDefine* d = compileDefine(name, it->second, start);
                if (!d) return;
                if (d->folded) {
                    emitConst(d->value);
                    return;
                }
                if (expr_.code_.size() + d->program.code_.size() > kMaxProgram) {
                    limit(start, "expression too long: expanding #define '" + name +
                                     "' gives more than " + std::to_string(kMaxProgram) + " steps");
                    return;
                }
                inlineProgram(d->program);
                return;
            }
        }
        // After the #defines: like cpfg's preprocessor, a #define Q or Z wins.
        if (scope_.state) {
            auto it = scope_.state->find(name);
            if (it != scope_.state->end()) {
                emit(Expression::Op::Load, it->second);
                expr_.usesState_ = true;
                return;
            }
        }
        fail(start, "unknown name '" + name + "'" +
                        (scope_.variables.empty() ? std::string()
                                                  : " (not a parameter of this production)"));
    }

    // A #define is compiled once per expression, however often it is used: a chain of
    // defines each using the previous twice would otherwise take 2^n compilations.
    struct CompiledDefine {
        Expression program;
        bool folded = false;  // no parameter, no ran(): `value` stands for the program
        double value = 0;
    };

    const CompiledDefine* compileDefine(const std::string& name, const std::string& body,
                                        std::size_t start) {
        auto cached = defines_->find(name);
        if (cached != defines_->end()) return &cached->second;
        // Compiled as the C preprocessor would expand it, but parenthesised so that
        // `#define N 1+2` gives 2*N == 6.
        DiagnosticList inner;
        ExpressionCompiler sub(body, at(start), scope_, inner);
        sub.expanding_ = expanding_;
        sub.expanding_.insert(name);
        sub.depth_ = depth_;
        sub.defines_ = defines_;
        CompiledDefine d;
        d.program = sub.compile();
        if (!sub.limitMessage_.empty()) {
            // A limit met inside the define is the error to show, at its use here.
            limit(start, sub.limitMessage_);
            return nullptr;
        }
        if (d.program.empty()) {
            fail(start, "#define '" + name + "' is not a valid expression: '" + body + "'");
            return nullptr;
        }
        bool usesVariables = false;
        for (const auto& in : d.program.code_) usesVariables |= in.op == Expression::Op::Var;
        // State, arrays and printf are read or done where the expression runs.
        if (!usesVariables && !d.program.usesRandom_ && !d.program.usesState_ &&
            !d.program.prints_) {
            try {
                d.value = d.program.evaluate({});
                d.folded = true;
            } catch (const Error&) {
                // 1/0 and the like stay as code: they fail only where they are evaluated.
            }
        }
        return &defines_->emplace(name, std::move(d)).first->second;
    }

    void inlineProgram(const Expression& e) {
        auto base = static_cast<std::uint32_t>(expr_.code_.size());
        auto cbase = static_cast<std::uint32_t>(expr_.constants_.size());
        expr_.constants_.insert(expr_.constants_.end(), e.constants_.begin(), e.constants_.end());
        for (auto in : e.code_) {
            if (in.op == Expression::Op::Const) in.arg += cbase;
            if (in.op == Expression::Op::JumpIfFalse || in.op == Expression::Op::JumpIfTrue ||
                in.op == Expression::Op::Jump)
                in.arg += base;
            expr_.code_.push_back(in);
        }
        expr_.usesRandom_ |= e.usesRandom_;
        expr_.usesState_ |= e.usesState_;
        expr_.prints_ |= e.prints_;
        expr_.usesFunctions_ |= e.usesFunctions_;
        auto abase = static_cast<std::uint32_t>(expr_.arrays_.size());
        expr_.arrays_.insert(expr_.arrays_.end(), e.arrays_.begin(), e.arrays_.end());
        for (std::size_t k = expr_.code_.size() - e.code_.size(); k < expr_.code_.size(); ++k)
            if (expr_.code_[k].op == Expression::Op::Element) expr_.code_[k].arg += abase;
        auto sbase = static_cast<std::uint32_t>(expr_.strings_.size());
        expr_.strings_.insert(expr_.strings_.end(), e.strings_.begin(), e.strings_.end());
        for (std::size_t k = expr_.code_.size() - e.code_.size(); k < expr_.code_.size(); ++k)
            if (expr_.code_[k].op == Expression::Op::Printf ||
                (expr_.code_[k].op >= Expression::Op::Fopen &&
                 expr_.code_[k].op <= Expression::Op::Fflush))
                expr_.code_[k].arg += sbase;
    }

    // name[i][j]...: true when `name` is an array (errors then reported here).
    bool parseElement(const std::string& name, std::size_t start, bool address) {
        if (!scope_.arrays) return false;
        auto it = scope_.arrays->find(name);
        if (it == scope_.arrays->end()) return false;
        const ArrayShape& shape = it->second;
        for (std::size_t d = 0; d < shape.dims.size(); ++d) {
            if (!accept("[")) {
                fail(pos_, "'" + name + "' has " + std::to_string(shape.dims.size()) +
                               " dimensions: expected '['");
                return true;
            }
            parseTernary();
            if (failed_) return true;
            if (!accept("]")) {
                fail(pos_, "expected ']' after the subscript");
                return true;
            }
        }
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == '[') {
            fail(pos_,
                 "'" + name + "' has only " + std::to_string(shape.dims.size()) + " dimensions");
            return true;
        }
        expr_.arrays_.push_back({name, shape.base, shape.dims});
        emit(Expression::Op::Element, static_cast<std::uint32_t>(expr_.arrays_.size() - 1),
             address ? 1 : 0);
        expr_.usesState_ = true;
        (void)start;
        return true;
    }

    // A "..." literal, with C's \n \t \\ \" escapes resolved.
    bool parseString(std::string& out) {
        skipSpace();
        if (pos_ >= text_.size() || text_[pos_] != '"') {
            fail(pos_, "expected a format string in double quotes");
            return false;
        }
        std::size_t start = pos_++;
        while (pos_ < text_.size() && text_[pos_] != '"') {
            char c = text_[pos_++];
            if (c == '\\' && pos_ < text_.size()) {
                char e = text_[pos_++];
                c = e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e == '0' ? '\0' : e;
            }
            out += c;
        }
        if (pos_ >= text_.size()) {
            fail(start, "unterminated string: expected a closing '\"'");
            return false;
        }
        ++pos_;
        return true;
    }

    // printf("format", values...): prints through the EvalContext and gives 0.
    void parsePrintf(std::size_t start) {
        ++pos_;  // '('
        std::string format;
        if (!parseString(format)) return;
        int count = 0;
        while (accept(",")) {
            parseTernary();
            if (failed_) return;
            ++count;
        }
        if (!accept(")")) {
            fail(pos_, "expected ')' or ',' in the arguments of printf()");
            return;
        }
        if (count > 255) {
            fail(start, "printf() takes at most 255 values");
            return;
        }
        expr_.strings_.push_back(std::move(format));
        emit(Expression::Op::Printf, static_cast<std::uint32_t>(expr_.strings_.size() - 1),
             static_cast<std::uint8_t>(count));
        expr_.prints_ = true;
    }

    // fopen("name", "w"), fprintf(file, "format", values...), fclose(file), fflush(file).
    void parseFileCall(const std::string& name) {
        ++pos_;  // '('
        std::string text;
        int count = 0;
        if (name == "fopen") {
            std::string mode;
            if (!parseString(text)) return;
            if (!accept(",")) {
                fail(pos_, "expected ',' and the mode in fopen(\"name\", \"w\")");
                return;
            }
            skipSpace();
            std::size_t modeAt = pos_;
            if (!parseString(mode)) return;
            if (mode != "w" && mode != "a") {
                fail(modeAt, "fopen() opens files for writing: mode \"w\" or \"a\"");
                return;
            }
            if (mode == "a")
                text.insert(0, 1, '+');  // appended: marked for OutputFiles
            else
                text.insert(0, 1, '=');
        } else {
            parseTernary();  // the handle
            if (failed_) return;
            if (name == "fprintf") {
                if (!accept(",")) {
                    fail(pos_, "expected ',' and a format string after the file in fprintf()");
                    return;
                }
                if (!parseString(text)) return;
                while (accept(",")) {
                    parseTernary();
                    if (failed_) return;
                    ++count;
                }
            }
        }
        if (!accept(")")) {
            fail(pos_, "expected ')' to end the arguments of " + name + "()");
            return;
        }
        if (count > 254) {
            fail(pos_, "fprintf() takes at most 254 values");
            return;
        }
        expr_.strings_.push_back(std::move(text));
        auto op = name == "fopen"     ? Expression::Op::Fopen
                  : name == "fprintf" ? Expression::Op::Fprintf
                  : name == "fclose"  ? Expression::Op::Fclose
                                      : Expression::Op::Fflush;
        emit(op, static_cast<std::uint32_t>(expr_.strings_.size() - 1),
             static_cast<std::uint8_t>(count));
        expr_.prints_ = true;
    }

    void parseCall(const std::string& name, std::size_t start) {
        if (name == "printf") {
            parsePrintf(start);
            return;
        }
        if (name == "fprintf" || name == "fopen" || name == "fclose" || name == "fflush") {
            parseFileCall(name);
            return;
        }
        if (name == "tfunc") {
            // cpfg has no tfunc: its lexer does not know the name, so `tfunc(` is a syntax
            // error there. Timeline functions (.tset files) belong to lpfg.
            fail(start,
                 "tfunc() is not a cpfg function (timeline functions from .tset files are "
                 "lpfg's); use func(id, x) with a function of the view file");
            return;
        }
        const FunctionInfo* fn = nullptr;
        for (const auto& f : kFunctions)
            if (name == f.name) fn = &f;
        if (!fn) {
            fail(start, "unknown function '" + name + "'");
            return;
        }
        ++pos_;  // '('
        int count = 0;
        skipSpace();
        if (!(pos_ < text_.size() && text_[pos_] == ')')) {
            do {
                parseTernary();
                if (failed_) return;
                ++count;
            } while (accept(","));
        }
        if (!accept(")")) {
            fail(pos_, "expected ')' or ',' in the arguments of " + name + "()");
            return;
        }
        if (count != fn->arity) {
            fail(start, name + "() takes " + std::to_string(fn->arity) + " argument" +
                            (fn->arity == 1 ? "" : "s") + ", not " + std::to_string(count));
            return;
        }
        if (name == "func") {
            emit(Expression::Op::Func);
            expr_.usesFunctions_ = true;
        } else if (name.starts_with("curve")) {
            emit(name == "curveGAL" ? Expression::Op::CurveLength : Expression::Op::Curve, 0,
                 fn->id);
            expr_.usesFunctions_ = true;
        } else if (name == "ran") {
            emit(Expression::Op::Ran);
            expr_.usesRandom_ = true;
        } else if (name == "nran") {
            emit(Expression::Op::Nran);
            expr_.usesRandom_ = true;
        } else if (name == "bran" || name == "biran" || name == "srand") {
            emit(name == "bran"    ? Expression::Op::Bran
                 : name == "biran" ? Expression::Op::Biran
                                   : Expression::Op::Srand);
            expr_.usesRandom_ = true;
        } else {
            emit(fn->arity == 1 ? Expression::Op::Call1 : Expression::Op::Call2, 0, fn->id);
        }
    }

    void computeStackDepth() {
        // Straight-line upper bound: every push counted, pops subtracted.
        int depth = 0, maxDepth = 0;
        for (const auto& in : expr_.code_) {
            switch (in.op) {
                case Expression::Op::Const:
                case Expression::Op::Var:
                case Expression::Op::Load:
                    ++depth;
                    break;
                case Expression::Op::Fopen:
                    ++depth;
                    break;
                case Expression::Op::Fprintf:
                    depth -= in.fn;
                    break;
                case Expression::Op::Fclose:
                case Expression::Op::Fflush:
                    break;
                case Expression::Op::Printf:
                    depth += 1 - in.fn;
                    break;
                case Expression::Op::Select:
                    depth -= 2;
                    break;
                case Expression::Op::Element:
                    depth -= static_cast<int>(expr_.arrays_[in.arg].dims.size()) - 1;
                    break;
                case Expression::Op::Neg:
                case Expression::Op::Not:
                case Expression::Op::Call1:
                case Expression::Op::Ran:
                case Expression::Op::Srand:
                case Expression::Op::CurveLength:
                case Expression::Op::Jump:
                    break;
                case Expression::Op::JumpIfFalse:
                case Expression::Op::JumpIfTrue:
                case Expression::Op::Pop:
                    --depth;
                    break;
                default:
                    if (in.op == Expression::Op::Ne && in.arg == 0) break;  // normalise
                    --depth;
                    break;
            }
            maxDepth = std::max(maxDepth, depth);
        }
        expr_.maxStack_ = static_cast<std::uint32_t>(maxDepth + 2);
    }

    std::string_view text_;
    SourceLocation loc_;
    const ExpressionScope& scope_;
    DiagnosticList& diags_;
    static constexpr int kMaxNesting = 256;
    static constexpr std::size_t kMaxProgram = 100000;

    std::size_t pos_ = 0;
    int depth_ = 0;
    bool failed_ = false;
    std::string limitMessage_;
    std::set<std::string> expanding_;
    std::shared_ptr<std::map<std::string, CompiledDefine>> defines_ =
        std::make_shared<std::map<std::string, CompiledDefine>>();
    Expression expr_;
};

Expression compileExpression(std::string_view text, const SourceLocation& loc,
                             const ExpressionScope& scope, DiagnosticList& diags) {
    return ExpressionCompiler(text, loc, scope, diags).compile();
}

Expression compileElementAddress(std::string_view text, const SourceLocation& loc,
                                 const ExpressionScope& scope, DiagnosticList& diags) {
    return ExpressionCompiler(text, loc, scope, diags).compileAddress();
}

double evaluateConstant(std::string_view text, const SourceLocation& loc,
                        const std::map<std::string, std::string>& defines) {
    DiagnosticList diags;
    ExpressionScope scope;
    scope.defines = &defines;
    Expression e = compileExpression(text, loc, scope, diags);
    if (diags.hasErrors()) throw Error(diags.items());
    if (e.usesRandom()) throw Error(loc, "a constant cannot use ran() or nran()");
    return e.evaluate({});
}

static double apply1(std::uint8_t fn, double x) {
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
    }
    return 0;
}

static double apply2(std::uint8_t fn, double a, double b) {
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

// A gamma(shape, 1) deviate (Marsaglia and Tsang), from uniform numbers.
template <class Uniform>
static double gammaDeviate(double shape, Uniform& uniform) {
    if (shape < 1) {
        double u = uniform();
        return gammaDeviate(shape + 1, uniform) * std::pow(u > 0 ? u : 1e-300, 1 / shape);
    }
    const double d = shape - 1.0 / 3, c = 1 / std::sqrt(9 * d);
    for (int tries = 0; tries < 1000; ++tries) {
        double u1 = uniform(), u2 = uniform();
        if (u1 < 1e-300) u1 = 1e-300;
        double x = std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * 3.14159265358979323846 * u2);
        double v = 1 + c * x;
        if (v <= 0) continue;
        v = v * v * v;
        double u = uniform();
        if (u > 0 && std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v;
    }
    return d;
}

// C's printf conversions applied to doubles: %d %i %c %o %x %u take the value as an
// integer, %e %f %g as a double; %% is a percent sign.
std::string formatPrintf(std::string_view format, std::span<const double> values) {
    std::string out;
    std::size_t next = 0;
    for (std::size_t i = 0; i < format.size(); ++i) {
        if (format[i] != '%') {
            out += format[i];
            continue;
        }
        std::size_t start = i++;
        while (i < format.size() && std::strchr("-+ #0123456789.lh", format[i])) ++i;
        if (i >= format.size()) {
            out += format.substr(start);
            break;
        }
        char conv = format[i];
        if (conv == '%') {
            out += '%';
            continue;
        }
        std::string spec(format.substr(start, i - start));
        std::erase_if(spec, [](char c) { return c == 'l' || c == 'h'; });
        double v = next < values.size() ? values[next++] : 0.0;
        char buf[512];
        if (std::strchr("diouxXc", conv)) {
            spec += std::strchr("di", conv) ? "lld" : conv == 'c' ? "c" : std::string("ll") + conv;
            if (conv == 'c')
                std::snprintf(buf, sizeof buf, spec.c_str(), static_cast<int>(v));
            else
                std::snprintf(buf, sizeof buf, spec.c_str(), static_cast<long long>(v));
        } else if (std::strchr("eEfFgGaA", conv)) {
            spec += conv;
            std::snprintf(buf, sizeof buf, spec.c_str(), v);
        } else {
            out += format.substr(start, i - start + 1);
            continue;
        }
        out += buf;
    }
    return out;
}

void Expression::findShape() {
    shape_ = Shape::Program;
    auto isConst = [&](const Instr& in) { return in.op == Op::Const; };
    auto isVar = [&](const Instr& in) { return in.op == Op::Var; };
    if (code_.size() == 1 && isConst(code_[0])) {
        shape_ = Shape::Constant;
        a_ = constants_[code_[0].arg];
    } else if (code_.size() == 1 && isVar(code_[0])) {
        shape_ = Shape::Variable;
        slot_ = code_[0].arg;
    } else if (code_.size() == 3) {
        Op op = code_[2].op;
        bool simple = op == Op::Add || op == Op::Sub || op == Op::Mul;
        if (isVar(code_[0]) && isConst(code_[1]) &&
            (simple || (op == Op::Div && constants_[code_[1].arg] != 0))) {
            shape_ = Shape::VariableConstant;
            slot_ = code_[0].arg;
            a_ = constants_[code_[1].arg];
            op_ = op;
        } else if (isConst(code_[0]) && isVar(code_[1]) && simple) {
            shape_ = Shape::ConstantVariable;
            a_ = constants_[code_[0].arg];
            slot_ = code_[1].arg;
            op_ = op;
        }
    }
}

double Expression::run(std::span<const double> slots, const EvalContext* ctx) const {
    std::array<double, 64> small;
    std::vector<double> big;
    double* st = small.data();
    if (maxStack_ > small.size()) {
        big.resize(maxStack_);
        st = big.data();
    }
    int sp = -1;
    // sqrt(-1), log(0), asin(2), (-8)^0.5: a value the L-system cannot go on with.
    auto checkDomain = [&](double v, const char* what) {
        if (!std::isfinite(v))
            throw Error(location_, std::string("'") + text_ + "' is undefined here: " + what +
                                       " was given an argument outside its domain");
    };
    auto uniform = [&]() -> double {
        if (!ctx || !ctx->uniform)
            throw Error(location_, "ran()/nran() used where no random stream exists");
        return ctx->uniform();
    };
    for (std::size_t pc = 0; pc < code_.size(); ++pc) {
        const Instr& in = code_[pc];
        switch (in.op) {
            case Op::Const:
                st[++sp] = constants_[in.arg];
                break;
            case Op::Var:
                st[++sp] = slots[in.arg];
                break;
            case Op::Neg:
                st[sp] = -st[sp];
                break;
            case Op::Not:
                st[sp] = st[sp] == 0 ? 1 : 0;
                break;
            case Op::Add:
                st[sp - 1] += st[sp];
                --sp;
                break;
            case Op::Sub:
                st[sp - 1] -= st[sp];
                --sp;
                break;
            case Op::Mul:
                st[sp - 1] *= st[sp];
                --sp;
                break;
            case Op::Div:
                // cpfg divides by 1 instead, with a warning.
                if (st[sp] == 0) {
                    if (ctx && ctx->print && *ctx->print)
                        (*ctx->print)(Diagnostic{Severity::Warning, location_,
                                                 "division by zero in '" + text_ +
                                                     "'; dividing by 1 instead (as cpfg)"}
                                          .toString() +
                                      "\n");
                    st[sp] = 1;
                }
                st[sp - 1] /= st[sp];
                --sp;
                break;
            case Op::Mod: {
                // cpfg's % works on whole numbers: both operands are truncated first.
                double a = std::trunc(st[sp - 1]), b = std::trunc(st[sp]);
                if (b == 0) throw Error(location_, "modulo by zero in '" + text_ + "'");
                st[sp - 1] = std::fmod(a, b);
                --sp;
                break;
            }
            case Op::Pow:
                st[sp - 1] = std::pow(st[sp - 1], st[sp]);
                --sp;
                checkDomain(st[sp], "^");
                break;
            case Op::Lt:
                st[sp - 1] = st[sp - 1] < st[sp];
                --sp;
                break;
            case Op::Le:
                st[sp - 1] = st[sp - 1] <= st[sp];
                --sp;
                break;
            case Op::Gt:
                st[sp - 1] = st[sp - 1] > st[sp];
                --sp;
                break;
            case Op::Ge:
                st[sp - 1] = st[sp - 1] >= st[sp];
                --sp;
                break;
            case Op::Eq:
                st[sp - 1] = st[sp - 1] == st[sp];
                --sp;
                break;
            case Op::Ne:
                if (in.arg == 0) {
                    st[sp] = st[sp] != 0;
                } else {
                    st[sp - 1] = st[sp - 1] != st[sp];
                    --sp;
                }
                break;
            case Op::And:
                st[sp - 1] = (st[sp - 1] != 0) && (st[sp] != 0);
                --sp;
                break;
            case Op::Or:
                st[sp - 1] = (st[sp - 1] != 0) || (st[sp] != 0);
                --sp;
                break;
            case Op::Call1:
                st[sp] = apply1(in.fn, st[sp]);
                checkDomain(st[sp], "a function");
                break;
            case Op::Call2:
                st[sp - 1] = apply2(in.fn, st[sp - 1], st[sp]);
                --sp;
                checkDomain(st[sp], "a function");
                break;
            case Op::Ran:
                st[sp] = st[sp] * uniform();
                break;
            case Op::Nran: {
                // Box–Muller: two uniforms give one normal deviate.
                double u1 = uniform(), u2 = uniform();
                if (u1 < 1e-300) u1 = 1e-300;
                double z =
                    std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * 3.14159265358979323846 * u2);
                st[sp - 1] = st[sp - 1] + st[sp] * z;
                --sp;
                break;
            }
            case Op::JumpIfFalse:
                if (st[sp] == 0) {
                    st[sp] = 0;
                    pc = in.arg - 1;
                } else {
                    --sp;
                }
                break;
            case Op::JumpIfTrue:
                if (st[sp] != 0) {
                    st[sp] = 1;
                    pc = in.arg - 1;
                } else {
                    --sp;
                }
                break;
            case Op::Jump:
                pc = in.arg - 1;
                break;
            case Op::Pop:
                --sp;
                break;
            case Op::Func: {
                double id = st[sp - 1], x = st[sp];
                --sp;
                std::size_t count = ctx && ctx->functions ? ctx->functions->size() : 0;
                if (!(id >= 1 && id < static_cast<double>(count) + 1))
                    throw Error(
                        location_,
                        "'" + text_ + "': func(" + formatNumber(id) + ", x) names no function: " +
                            (count == 0
                                 ? std::string("the view file names none "
                                               "('function:' or 'function set:')")
                                 : "there are " + std::to_string(count) + ", counted from 1"));
                st[sp] = (*ctx->functions)[static_cast<std::size_t>(id) - 1].value(x);
                break;
            }
            case Op::Curve:
            case Op::CurveLength: {
                const bool length = in.op == Op::CurveLength;
                double id = length ? st[sp] : st[sp - 1];
                std::size_t count = ctx && ctx->curves ? ctx->curves->size() : 0;
                static constexpr const char* kNames[] = {"curveX", "curveY", "curveZ"};
                if (!(id >= 1 && id < static_cast<double>(count) + 1))
                    throw Error(
                        location_,
                        "'" + text_ + "': " + (length ? "curveGAL" : kNames[in.fn % 3]) + "(" +
                            formatNumber(id) + (length ? "" : ", t") + ") names no curve: " +
                            (count == 0
                                 ? std::string("the view file names none ('curve:')")
                                 : "there are " + std::to_string(count) + ", counted from 1"));
                const CurveXYZ& c = (*ctx->curves)[static_cast<std::size_t>(id) - 1];
                if (length) {
                    st[sp] = c.length();
                } else {
                    Vec3 p = c.atLength(st[sp]);
                    --sp;
                    st[sp] = in.fn == 0 ? p.x : in.fn == 1 ? p.y : p.z;
                }
                break;
            }
            case Op::Load:
                if (!ctx || !ctx->state)
                    throw Error(location_, "'" + text_ + "' reads a variable where none exists");
                st[++sp] = ctx->state[in.arg];
                break;
            case Op::Fopen:
            case Op::Fprintf:
            case Op::Fclose:
            case Op::Fflush: {
                if (!ctx || !ctx->files)
                    throw Error(location_, "'" + text_ +
                                               "' writes a file where files cannot be "
                                               "written");
                if (in.op == Op::Fopen) {
                    // The parser marks the mode: '+' appends, '=' truncates.
                    const std::string& name = strings_[in.arg];
                    st[++sp] = ctx->files->open(name.substr(1), name[0] == '+', location_);
                } else if (in.op == Op::Fprintf) {
                    sp -= in.fn;
                    ctx->files->write(st[sp], formatPrintf(strings_[in.arg], {st + sp + 1, in.fn}),
                                      location_);
                    st[sp] = 0;
                } else {
                    if (in.op == Op::Fclose)
                        ctx->files->close(st[sp], location_);
                    else
                        ctx->files->flush(st[sp], location_);
                    st[sp] = 0;
                }
                break;
            }
            case Op::Printf: {
                sp -= in.fn;
                if (ctx && ctx->print && *ctx->print)
                    (*ctx->print)(formatPrintf(strings_[in.arg], {st + sp + 1, in.fn}));
                st[++sp] = 0;
                break;
            }
            case Op::Select:
                st[sp - 2] = st[sp - 2] != 0 ? st[sp - 1] : st[sp];
                sp -= 2;
                break;
            case Op::Bran: {
                double a = st[sp - 1], b = st[sp];
                if (!(a > 0) || !(b > 0))
                    throw Error(location_, "bran(a, b) needs a > 0 and b > 0 in '" + text_ + "'");
                double x = gammaDeviate(a, uniform), y = gammaDeviate(b, uniform);
                st[sp - 1] = x + y > 0 ? x / (x + y) : 0.5;
                --sp;
                break;
            }
            case Op::Biran: {
                double count = std::floor(st[sp - 1]), p = st[sp];
                if (!(count >= 0) || count > 1e7)
                    throw Error(location_,
                                "biran(n, p) needs n from 0 to 10000000 in '" + text_ + "'");
                double hits = 0;
                for (double k = 0; k < count; ++k) hits += uniform() < p ? 1 : 0;
                st[sp - 1] = hits;
                --sp;
                break;
            }
            case Op::Element: {
                const ArrayRef& a = arrays_[in.arg];
                std::size_t n = a.dims.size();
                sp -= static_cast<int>(n) - 1;
                std::size_t offset = 0;
                for (std::size_t d = 0; d < n; ++d) {
                    // cpfg: a fractional subscript is truncated; one out of range is
                    // clamped to the nearest element, with a warning.
                    double v = std::trunc(st[sp + static_cast<int>(d)]);
                    double last = a.dims[d] - 1.0;
                    double used = std::isnan(v) ? 0 : std::clamp(v, 0.0, last);
                    if (used != v && ctx && ctx->print && *ctx->print)
                        (*ctx->print)(Diagnostic{Severity::Warning, location_,
                                                 "subscript " + std::to_string(d + 1) + " of " +
                                                     a.name + " is " + formatNumber(v) +
                                                     ", out of range; using " + formatNumber(used)}
                                          .toString() +
                                      "\n");
                    offset = offset * a.dims[d] + static_cast<std::size_t>(used);
                }
                std::uint32_t slot = a.base + static_cast<std::uint32_t>(offset);
                if (in.fn == 1) {
                    st[sp] = slot;
                } else {
                    if (!ctx || !ctx->state)
                        throw Error(location_, "'" + text_ + "' reads an array where none exists");
                    st[sp] = ctx->state[slot];
                }
                break;
            }
            case Op::Srand:
                if (!ctx || !ctx->reseed)
                    throw Error(location_, "srand() used where no random stream exists");
                ctx->reseed(st[sp]);
                st[sp] = 0;
                break;
        }
    }
    return sp >= 0 ? st[sp] : 0.0;
}

std::ostream& operator<<(std::ostream& os, const Expression& e) {
    e.print(os);
    return os;
}

}  // namespace graftal
