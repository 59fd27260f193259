// Running a compiled expression: the stack interpreter, and the shapes evaluate() runs
// inline without it.
#include "graftal/lang/expression.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "expression_builtins.hpp"
#include "graftal/core/cpfg_random.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/core/random_stream.hpp"

namespace graftal {

// Which of the inline shapes of evaluate() the compiled program has, if any.
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

namespace {

// The program's function func(id, x) calls for `id`, when it gives one.
const UserFunction* userFunction(const EvalContext* ctx, double id) {
    if (!ctx || !ctx->userFunctions) return nullptr;
    const auto& table = *ctx->userFunctions;
    if (!(id >= 1 && id < static_cast<double>(table.size()) + 1)) return nullptr;
    const UserFunction& f = table[static_cast<std::size_t>(id) - 1];
    return f ? &f : nullptr;
}

}  // namespace

// A function of the program, its failure worded as this expression's: the caller then adds
// the production, the module and the step, as for any error of an expression.
double Expression::callUserFunction(const UserFunction& f, double id, double x) const {
    const std::string call = "func(" + formatNumber(id) + ", " + formatNumber(x) + ")";
    double y = 0;
    try {
        y = f(x);
    } catch (const Error& e) {
        throw Error(location_, "'" + text_ + "': " + call + " failed: " + e.messages());
    }
    if (!std::isfinite(y))
        throw Error(location_, "'" + text_ + "': " + call + " gave " + formatNumber(y) +
                                   ", not a finite number");
    return y;
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
                st[sp] = applyFunction1(in.fn, st[sp]);
                checkDomain(st[sp], "a function");
                break;
            case Op::Call2:
                st[sp - 1] = applyFunction2(in.fn, st[sp - 1], st[sp]);
                --sp;
                checkDomain(st[sp], "a function");
                break;
            case Op::Ran:
                if (ctx && ctx->cpfgRandom)
                    st[sp] = ctx->cpfgRandom->ran(st[sp]);
                else
                    st[sp] = st[sp] * uniform();
                break;
            case Op::Nran: {
                if (ctx && ctx->cpfgRandom) {
                    st[sp - 1] = ctx->cpfgRandom->nran(st[sp - 1], st[sp]);
                    --sp;
                    break;
                }
                double z = normalDeviate(uniform);
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
                if (const UserFunction* user = userFunction(ctx, id)) {
                    st[sp] = callUserFunction(*user, id, x);
                    break;
                }
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
                st[sp - 1] = ctx && ctx->cpfgRandom ? ctx->cpfgRandom->bran(a, b)
                                                    : betaDeviate(a, b, uniform);
                --sp;
                break;
            }
            case Op::Biran: {
                double count = std::floor(st[sp - 1]), p = st[sp];
                if (!(count >= 0) || count > 1e7)
                    throw Error(location_,
                                "biran(n, p) needs n from 0 to 10000000 in '" + text_ + "'");
                double hits = 0;
                if (ctx && ctx->cpfgRandom)
                    hits = ctx->cpfgRandom->biran(count, p);
                else
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
                if (ctx && ctx->cpfgRandom) {
                    ctx->cpfgRandom->srand(st[sp]);
                    st[sp] = 0;
                    break;
                }
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
