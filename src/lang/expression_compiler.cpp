// The expression compiler: recursive descent from expression text to a postfix program,
// resolving names (parameters, #defines, state, arrays) and checking arities; #defines
// without parameters or random numbers fold to constants.
#include "graftal/lang/expression.hpp"

#include "graftal/core/number_chars.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "expression_builtins.hpp"

namespace graftal {

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

    // A backslash is blank here too: cpfg's lexer drops a character no rule of an
    // expression matches, so the `\` a macro continued with (`#define w(x) \\`) and one
    // continuing a line of a block are passed over.
    void skipSpace() {
        while (pos_ < text_.size() &&
               (std::isspace(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '\\'))
            ++pos_;
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
        auto r = numberFromChars(text_.data() + start, text_.data() + pos_, v);
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
        const FunctionInfo* fn = findFunction(name);
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

}  // namespace graftal
