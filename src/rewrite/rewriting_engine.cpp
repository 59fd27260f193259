#include "rewriting_engine.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <type_traits>

#include "graftal/core/cpfg_random.hpp"
#include "graftal/core/parallel.hpp"
#include "graftal/core/random_stream.hpp"
#include "rewriting_engine_detail.hpp"

namespace graftal {

using namespace rewriting_detail;

RewritingEngine::RewritingEngine(const LSystem& ls, const std::vector<Production>& productions,
                                 std::uint64_t seed, unsigned threads)
    : ls_(ls), productions_(productions), seed_(seed), threads_(threads) {
    bool stochastic = false;
    for (const auto& p : productions_) {
        maxSlots_ = std::max(maxSlots_, p.slotCount);
        stochastic |= p.probability.has_value();
        multiPred_ |= p.predecessor.size() > 1;
        needBrackets_ |= p.hasContext();
        parametric_ |= p.isParametric() || p.condition.has_value();
        sequential_ |= p.hasBlocks();
        for (const auto& m : p.successor)
            for (const auto& a : m.args) sequential_ |= a.prints();
        sequential_ |=
            (p.condition && p.condition->prints()) || (p.probability && p.probability->prints());
    }
    // A block with a condition-less production still needs the generic machinery.
    parametric_ |= sequential_;
    parametric_ |= ls.isParametric();
    tableCount_ = std::max<std::size_t>(1, ls.tableNames.size());
    if (productions_.size() > kMaxChoiceProductions)
        throw Error(SourceLocation{ls.file, 0, 0},
                    "too many productions: " + std::to_string(productions_.size()) + " (at most " +
                        std::to_string(kMaxChoiceProductions) + ")");
    fast_ = !multiPred_ && !parametric_ && !needBrackets_ && !stochastic && !sequential_;
    candidates_.assign(tableCount_, std::vector<std::vector<std::uint32_t>>(ls.symbols.size()));
    for (std::uint32_t k = 0; k < productions_.size(); ++k) {
        const Production& p = productions_[k];
        for (std::size_t t = 0; t < tableCount_; ++t)
            if (p.table < 0 || static_cast<std::size_t>(p.table) == t)
                candidates_[t][p.predecessor[0].symbol].push_back(k);
    }
    if (fast_) buildFastTables();
    buildQuickChoices();
    // The ContextRewriter's branch handling assumes brackets are seen.
    bool bracketsIgnored = ls.ignored['['] || ls.ignored[']'] || ls.ring;
    for (const auto& p : productions_) {
        int open = 0;  // a right context may leave a branch open (`> [!L`)
        for (const auto& m : p.right) {
            bracketsIgnored |= m.symbol == '=' || m.symbol == ']';
            open += m.symbol == '[' ? 1 : m.symbol == ']' && open > 0 ? -1 : 0;
        }
        bracketsIgnored |= open > 0;
    }
    if (!fast_ && !multiPred_ && !parametric_ && !bracketsIgnored) {
        context_ = std::make_unique<ContextRewriter>(ls, productions_, candidates_, seed_);
        if (!context_->usable()) context_.reset();
    }
}

RewritingEngine::~RewritingEngine() = default;

// Per production: the parameters its successor writes, and whether its arguments can be
// evaluated on the predecessor's own parameters. Per table and symbol: when every candidate
// is a plain production (one module, no context, condition or probability), choose() would
// take the first whose predecessor has the module's number of parameters.
void RewritingEngine::buildQuickChoices() {
    successorModules_.assign(productions_.size(), 0);
    successorParams_.assign(productions_.size(), 0);
    flat_.assign(productions_.size(), {});
    for (std::size_t k = 0; k < productions_.size(); ++k) {
        const Production& p = productions_[k];
        Flat& f = flat_[k];
        bool random = false;
        for (const auto& m : p.successor) {
            f.symbols.push_back(m.symbol);
            f.argStart.push_back(static_cast<std::uint32_t>(f.args.size()));
            for (const auto& a : m.args) {
                f.args.push_back(&a);
                random |= a.needsContext();
            }
        }
        f.direct = !p.hasContext() && p.predecessor.size() == 1 && !random;
        successorModules_[k] = static_cast<std::uint32_t>(f.symbols.size());
        successorParams_[k] = static_cast<std::uint32_t>(f.args.size());
    }
    quick_.assign(tableCount_, std::vector<QuickChoice>(ls_.symbols.size()));
    for (std::size_t t = 0; t < tableCount_; ++t) {
        for (std::size_t s = 0; s < ls_.symbols.size(); ++s) {
            QuickChoice& q = quick_[t][s];
            q.byArity.fill(kIdentity);
            q.simple = true;
            const auto& cands = candidates_[t][s];
            for (std::size_t c = cands.size(); c-- > 0;) {
                const Production& p = productions_[cands[c]];
                q.simple &=
                    p.predecessor.size() == 1 && !p.hasContext() && !p.condition && !p.probability;
                std::size_t arity = p.predecessor[0].formals.size();
                if (arity < kQuickArity) q.byArity[arity] = static_cast<std::int32_t>(cands[c]);
            }
        }
    }
}

void RewritingEngine::buildFastTables() {
    std::size_t n = ls_.symbols.size();
    fastStart_.assign(tableCount_, {});
    fastSymbols_.assign(tableCount_, {});
    for (std::size_t t = 0; t < tableCount_; ++t) {
        auto& start = fastStart_[t];
        auto& syms = fastSymbols_[t];
        start.assign(n + 1, 0);
        for (std::size_t s = 0; s < n; ++s) {
            start[s] = static_cast<std::uint32_t>(syms.size());
            if (candidates_[t][s].empty()) {
                syms.push_back(static_cast<Symbol>(s));
            } else {
                for (const auto& m : productions_[candidates_[t][s][0]].successor)
                    syms.push_back(m.symbol);
            }
        }
        start[n] = static_cast<std::uint32_t>(syms.size());
    }
    fastShort_.assign(tableCount_, {});
    fastLength_.assign(tableCount_, {});
    for (std::size_t t = 0; t < tableCount_; ++t) {
        const auto& start = fastStart_[t];
        bool allShort = true;
        for (std::size_t s = 0; s < n; ++s) allShort &= start[s + 1] - start[s] <= kShortSuccessor;
        if (!allShort) continue;
        fastShort_[t].assign(n, ShortSuccessor{});
        fastLength_[t].assign(n, 0);
        for (std::size_t s = 0; s < n; ++s) {
            fastLength_[t][s] = static_cast<std::uint8_t>(start[s + 1] - start[s]);
            std::copy(fastSymbols_[t].begin() + start[s], fastSymbols_[t].begin() + start[s + 1],
                      fastShort_[t][s].symbols);
        }
    }
}

std::size_t RewritingEngine::chunkCount(std::size_t n) const {
    if (multiPred_ || n < kParallelThreshold) return 1;
    return threads_;
}

// The previous string counts with what it holds, not with its buffers' capacity, which
// may include room kept for a later step (see sizeOutput).
double RewritingEngine::stringBytes(std::size_t modules, std::size_t params, bool parametric,
                                    std::size_t paramBytes) {
    return static_cast<double>(modules) * sizeof(Symbol) +
           (parametric ? static_cast<double>(modules + 1) * 4 +
                             static_cast<double>(params) * static_cast<double>(paramBytes)
                       : 0.0);
}

void RewritingEngine::checkLimit(int stepNumber, std::size_t modules, std::size_t params,
                                 std::size_t extra, const ModuleString& cur,
                                 std::size_t limit) const {
    double bytes = stringBytes(modules, params, parametric_, cur.paramBytes());
    double total =
        bytes + stringBytes(cur.size(), cur.paramCount(), cur.hasParameters(), cur.paramBytes()) +
        static_cast<double>(extra);
    if (total > static_cast<double>(limit) || params > 0xFFFFFFFFull ||
        (needBrackets_ && modules > 0xFFFFFFFEull)) {
        Diagnostic d{Severity::Error, SourceLocation{ls_.file, 0, 0},
                     "derivation step " + std::to_string(stepNumber) + " would make a string of " +
                         std::to_string(modules) + " modules (" + formatBytes(bytes) + ", " +
                         formatBytes(total) +
                         " with the previous step), more than the memory limit of " +
                         formatBytes(static_cast<double>(limit))};
        d.remedies = {Remedy::LowerSteps, Remedy::RaiseMemoryLimit};
        throw Error(std::move(d));
    }
}

bool RewritingEngine::step(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                           std::size_t memoryLimit, const std::vector<std::uint8_t>* activeIn,
                           std::vector<std::uint8_t>* activeOut) {
    table = std::clamp(table, 0, static_cast<int>(tableCount_) - 1);
    if (sequential_)
        return stepSequential(cur, next, stepNumber, table, memoryLimit, activeIn, activeOut);
    if (!genericOnly_ && !activeIn && !activeOut && !cur.hasParameters()) {
        if (fast_) return stepFast(cur, next, stepNumber, table, memoryLimit);
        if (context_) return stepContext(cur, next, stepNumber, table, memoryLimit);
    }
    return stepGeneric(cur, next, stepNumber, table, memoryLimit, activeIn, activeOut);
}

void RewritingEngine::prepareOutput(const ModuleString& cur, ModuleString& next,
                                    std::size_t modules, std::size_t params, bool parametric,
                                    std::size_t extra, std::size_t limit) const {
    // Up to kHeadroom times the room needed, within the memory limit as if every buffer
    // were full.
    double bytes = stringBytes(modules, params, parametric, cur.paramBytes());
    double spare =
        static_cast<double>(limit) -
        stringBytes(cur.size(), cur.paramCount(), cur.hasParameters(), cur.paramBytes()) -
        static_cast<double>(extra);
    double room = bytes > 0 ? std::clamp(spare / bytes, 1.0, static_cast<double>(kHeadroom)) : 1;
    auto most = [room](std::size_t n) { return static_cast<std::size_t>(room * n); };
    next.clear();
    if (next.precision() != cur.precision()) next = ModuleString(cur.precision());
    sizeOutput(next.rawSymbols(), modules, most(modules));
    if (!parametric) return;
    sizeOutput(next.rawParamStart(), modules + 1, most(modules + 1));
    if (cur.precision() == Precision::Single)
        sizeOutput(next.rawFloats(), params, most(params));
    else
        sizeOutput(next.rawParams(), params, most(params));
}

// ---- fast path: deterministic, context-free, no parameters ------------------------------

bool RewritingEngine::stepFast(const ModuleString& cur, ModuleString& next, int stepNumber,
                               int table, std::size_t limit) {
    std::span<const Symbol> in = cur.symbols();
    std::size_t n = in.size();
    std::size_t chunks = chunkCount(n);
    std::vector<std::size_t> sizes(chunks, 0);
    const std::uint32_t* start = fastStart_[table].data();
    const bool isShort = !fastShort_[table].empty();
    const std::uint8_t* length = isShort ? fastLength_[table].data() : nullptr;
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        std::size_t total = 0;
        if (isShort)
            for (std::size_t i = b; i < e; ++i) total += length[in[i]];
        else
            for (std::size_t i = b; i < e; ++i) total += start[in[i] + 1] - start[in[i]];
        sizes[c] = total;
    });
    std::size_t total = std::accumulate(sizes.begin(), sizes.end(), std::size_t(0));
    checkLimit(stepNumber, total, 0, 0, cur, limit);
    prepareOutput(cur, next, total, 0, false, 0, limit);
    auto& out = next.rawSymbols();
    std::vector<std::size_t> offsets(chunks, 0);
    std::exclusive_scan(sizes.begin(), sizes.end(), offsets.begin(), std::size_t(0));
    const Symbol* successors = fastSymbols_[table].data();
    const ShortSuccessor* slots = isShort ? fastShort_[table].data() : nullptr;
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        Symbol* o = out.data() + offsets[c];
        std::size_t i = b;
        if (isShort) {
            // A whole slot is stored and the pointer advances by the successor's length:
            // the bytes past it are overwritten by the next successors. Near the chunk's
            // end, where they would land in the next chunk's output, copy exactly.
            Symbol* safeEnd = out.data() + offsets[c] + sizes[c];
            for (; i < e && o + kShortSuccessor <= safeEnd; ++i) {
                std::memcpy(o, slots[in[i]].symbols, sizeof(ShortSuccessor));
                o += length[in[i]];
            }
        }
        for (; i < e; ++i) {
            std::uint32_t s0 = start[in[i]], len = start[in[i] + 1] - s0;
            if (len == 1) {
                *o++ = successors[s0];
            } else {
                std::memcpy(o, successors + s0, len * sizeof(Symbol));
                o += len;
            }
        }
    });
    return true;
}

bool RewritingEngine::stepConsuming(ModuleString& cur, ModuleString& next, int stepNumber,
                                    int table, std::size_t memoryLimit) {
    const std::size_t chunks = chunkCount(cur.size());
    const bool inPlace = !sequential_ && !genericOnly_ && !cur.hasParameters() && !fast_ &&
                         context_ && context_->fitsInPlace(cur, chunks);
    if (!inPlace) return step(cur, next, stepNumber, table, memoryLimit);
    table = std::clamp(table, 0, static_cast<int>(tableCount_) - 1);
    const std::size_t total = context_->chooseInPlace(cur, stepNumber, table, chunks);
    const bool grows = context_->growsInPlace(cur, total);
    try {
        checkLimit(stepNumber, total, 0, 0, cur, memoryLimit);
        if (!grows) prepareOutput(cur, next, total, 0, false, 0, memoryLimit);
    } catch (...) {
        context_->restore(cur);
        throw;
    }
    if (!grows) return context_->write(cur, next.rawSymbols().data());
    // The next string in the buffer of this one. The other buffer, whose string is two
    // steps old, is given back: at most one string's pages are held.
    const bool applied = context_->writeOverItself(cur, total);
    std::swap(cur, next);
    cur = ModuleString(next.precision());
    return applied;
}

bool RewritingEngine::stepContext(const ModuleString& cur, ModuleString& next, int stepNumber,
                                  int table, std::size_t limit) {
    std::size_t total = context_->choose(cur, stepNumber, table, chunkCount(cur.size()));
    checkLimit(stepNumber, total, 0, context_->scratchBytes(), cur, limit);
    prepareOutput(cur, next, total, 0, false, context_->scratchBytes(), limit);
    return context_->write(cur, next.rawSymbols().data());
}

// ---- matching ---------------------------------------------------------------------------

bool RewritingEngine::matchLeft(const Production& p, const ModuleString& s, std::size_t i,
                                double* slots, int& slot) const {
    // The pattern is walked right to left; its formals still fill slots in pattern order.
    const auto& pat = p.left;
    int count = 0;
    for (const auto& m : pat) count += static_cast<int>(m.formals.size());
    int fill = slot + count;
    std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) - 1;
    auto syms = s.symbols();
    bool wrapped = false;
    for (std::ptrdiff_t q = static_cast<std::ptrdiff_t>(pat.size()) - 1; q >= 0;) {
        if (j < 0) {
            // A ring's first module is preceded by its last, once round.
            if (!ls_.ring || wrapped || s.size() == 0) return false;
            wrapped = true;
            j = static_cast<std::ptrdiff_t>(s.size()) - 1;
            continue;
        }
        auto uj = static_cast<std::size_t>(j);
        Symbol c = syms[uj];
        if (c == '[') {
            --j;  // the parent axis continues before the branch
            continue;
        }
        if (c == ']') {
            std::uint32_t open = brackets_.match(uj);
            if (open == BracketIndex::kNone) return false;
            j = static_cast<std::ptrdiff_t>(open) - 1;  // skip a sibling branch whole
            continue;
        }
        if (ls_.ignored[c]) {
            --j;
            continue;
        }
        const ModulePattern& m = pat[static_cast<std::size_t>(q)];
        if (c != m.symbol || !arityMatches(m, s, uj)) return false;
        fill -= static_cast<int>(m.formals.size());
        int at = fill;
        bind(m, s, uj, slots, at);
        --q;
        --j;
    }
    slot += count;
    return true;
}

// cpfg's right context: lateral branches the pattern does not mention are skipped whole;
// a '[' in the pattern enters the string's next branch, and a ']' in the pattern skips
// what is left of that branch.
bool RewritingEngine::matchRight(const Production& p, const ModuleString& s, std::size_t from,
                                 double* slots, int& slot) const {
    std::size_t j = from, n = s.size();
    auto syms = s.symbols();
    std::uint32_t entered[64];
    int depth = 0;
    bool wrapped = false;
    for (std::size_t q = 0; q < p.right.size();) {
        const ModulePattern& m = p.right[q];
        if (m.symbol == '=') {
            // cpfg: skip the rest of the current branch, up to its ']' (or the string's end).
            while (j < n && syms[j] != ']') {
                if (syms[j] == '[') {
                    std::uint32_t close = brackets_.match(j);
                    if (close == BracketIndex::kNone) return false;
                    j = close;
                }
                ++j;
            }
            ++q;
            continue;
        }
        if (m.symbol == ']' && depth == 0) {
            // Out of the branch the predecessor stands in: its ']' must come next.
            while (j < n && syms[j] != ']' && syms[j] != '[' && ls_.ignored[syms[j]]) ++j;
            if (j >= n || syms[j] != ']') return false;
            ++j;
            ++q;
            continue;
        }
        if (m.symbol == ']') {
            if (depth == 0) return false;
            std::uint32_t close = brackets_.match(entered[--depth]);
            if (close == BracketIndex::kNone) return false;
            j = close + 1;
            ++q;
            continue;
        }
        if (j >= n) {
            if (!ls_.ring || wrapped || n == 0) return false;
            wrapped = true;  // a ring's last module is followed by its first
            j = 0;
            continue;
        }
        Symbol c = syms[j];
        if (m.symbol == '[') {
            if (c == '[') {
                if (depth == 64) return false;
                entered[depth++] = static_cast<std::uint32_t>(j);
                ++q;
                ++j;
                continue;
            }
            if (c != ']' && ls_.ignored[c]) {
                ++j;
                continue;
            }
            return false;
        }
        if ((c == '[' || c == ']') && ls_.ignored[c]) {
            // consider: without brackets: the context runs through branch ends (cpfg).
            ++j;
            continue;
        }
        if (c == '[') {
            std::uint32_t close = brackets_.match(j);
            if (close == BracketIndex::kNone) return false;
            j = close + 1;  // lateral branches are not on this axis
            continue;
        }
        if (c == ']') return false;  // the branch ends
        if (ls_.ignored[c]) {
            ++j;
            continue;
        }
        if (c != m.symbol || !arityMatches(m, s, j)) return false;
        bind(m, s, j, slots, slot);
        ++q;
        ++j;
    }
    return true;
}

bool RewritingEngine::matches(const Production& p, const ModuleString& s, std::size_t i,
                              double* slots) const {
    std::size_t n = s.size();
    if (i + p.predecessor.size() > n) return false;
    for (std::size_t q = 0; q < p.predecessor.size(); ++q)
        if (s.symbol(i + q) != p.predecessor[q].symbol || !arityMatches(p.predecessor[q], s, i + q))
            return false;
    int slot = 0;
    if (!p.left.empty() && !matchLeft(p, s, i, slots, slot)) return false;
    for (std::size_t q = 0; q < p.predecessor.size(); ++q)
        bind(p.predecessor[q], s, i + q, slots, slot);
    if (!p.right.empty() && !matchRight(p, s, i + p.predecessor.size(), slots, slot)) return false;
    return true;
}

[[noreturn]] void RewritingEngine::rethrowAt(const Error& err, const ModuleString& s, std::size_t i,
                                             int stepNumber, const Production* p) const {
    std::vector<Diagnostic> ds = err.diagnostics();
    if (p && !ds.empty()) ds.back().location = p->location;
    std::string module;
    appendModuleText(module, ls_.symbols, s.symbol(i), s.params(i));
    if (!ds.empty())
        ds.back().message += " (while rewriting module " + std::to_string(i) + " '" + module +
                             "' in derivation step " + std::to_string(stepNumber) + ")";
    throw Error(std::move(ds));
}

double RewritingEngine::evaluate(const Expression& e, const double* slots, Draws& draws) const {
    return evaluate(e, slots, draws, sequential_);
}

double RewritingEngine::evaluate(const Expression& e, const double* slots, Draws& draws,
                                 bool mayPrint) const {
    std::span<const double> vars;
    if (slots) vars = {slots, static_cast<std::size_t>(maxSlots_)};
    if (!e.needsContext()) return e.evaluate(vars);
    EvalContext ctx;
    ctx.uniform = [&draws] { return draws(); };
    ctx.reseed = [&draws](double x) { draws.reseed(x); };
    ctx.cpfgRandom = cpfg_;
    ctx.state = state_;
    // Only one thread rewrites when the productions print; elsewhere (parallel steps)
    // warnings are not printed, so the output never depends on the thread count.
    ctx.print = mayPrint ? print_ : nullptr;
    ctx.files = mayPrint ? files_ : nullptr;
    ctx.functions = &ls_.functions;
    ctx.userFunctions = ls_.userFunctions.get();
    ctx.curves = &ls_.curves;
    return e.evaluate(vars, &ctx);
}

void RewritingEngine::runStatements(const Block& block, double* slots, Draws& draws) const {
    // Loops are bounded so that a model cannot hang the program.
    constexpr long kMaxIterations = 10'000'000;
    for (const Statement& st : block) {
        switch (st.kind) {
            case Statement::Kind::Assign:
                state_[st.target] = evaluate(st.value, slots, draws, true);
                break;
            case Statement::Kind::AssignParameter:
                slots[st.target] = evaluate(st.value, slots, draws, true);
                break;
            case Statement::Kind::AssignElement: {
                double v = evaluate(st.value, slots, draws, true);
                state_[static_cast<std::size_t>(evaluate(st.address, slots, draws, true))] = v;
                break;
            }
            case Statement::Kind::Evaluate:
                evaluate(st.value, slots, draws, true);
                break;
            case Statement::Kind::If:
                if (evaluate(st.value, slots, draws, true) != 0)
                    runStatements(st.body, slots, draws);
                else
                    runStatements(st.elseBody, slots, draws);
                break;
            case Statement::Kind::While:
            case Statement::Kind::DoWhile: {
                long count = 0;
                bool first = st.kind == Statement::Kind::DoWhile;
                while (first || evaluate(st.value, slots, draws, true) != 0) {
                    first = false;
                    runStatements(st.body, slots, draws);
                    if (++count > kMaxIterations)
                        throw Error(st.value.location(), "the loop ran " +
                                                             std::to_string(kMaxIterations) +
                                                             " times without its condition '" +
                                                             st.value.text() + "' becoming false");
                }
                break;
            }
        }
    }
}

void RewritingEngine::runBlock(const Block& block, double* slots, int stepNumber,
                               std::uint64_t position) const {
    if (!state_) throw Error(SourceLocation{ls_.file, 0, 0}, "blocks need the L-system's state");
    Draws draws{this, static_cast<std::uint64_t>(stepNumber), position, 1ull << 40};
    runStatements(block, slots, draws);
}

std::int32_t RewritingEngine::choose(const ModuleString& s, std::size_t i, std::uint64_t position,
                                     int stepNumber, int table, double* slots,
                                     std::vector<double>& weights) const {
    if (cpfg_) return chooseCpfg(s, i, stepNumber, table, slots);
    const auto& cands = candidates_[static_cast<std::size_t>(table)][s.symbol(i)];
    Draws draws{this, static_cast<std::uint64_t>(stepNumber), position, 0};
    const Production* evaluating = nullptr;  // whose block, condition or probability runs
    try {
        for (std::size_t k = 0; k < cands.size(); ++k) {
            const Production& p = productions_[cands[k]];
            evaluating = &p;
            if (!matches(p, s, i, slots)) continue;
            if (!p.preBlock.empty()) runStatements(p.preBlock, slots, draws);
            const bool firstApplies = !p.condition || evaluate(*p.condition, slots, draws) != 0;
            if (!p.probability) {
                if (firstApplies) return static_cast<std::int32_t>(cands[k]);
                continue;
            }
            // Without blocks, a stochastic production whose condition fails does not start
            // the group (the next one does, with the same outcome).
            if (!firstApplies && !sequential_) continue;
            // A stochastic group: every applicable production with a probability competes,
            // with weights normalised over the applicable ones (as cpfg does).
            weights.assign(cands.size(), 0.0);
            double sum = 0;
            std::size_t firstApplicable = cands.size();
            // The slots of the candidates whose pre block ran (it may change parameters),
            // so that the chosen one's are handed back.
            std::vector<std::vector<double>> afterPre;
            auto keepSlots = [&](std::size_t r) {
                afterPre.resize(cands.size());
                afterPre[r].assign(slots, slots + maxSlots_);
            };
            if (!p.preBlock.empty()) keepSlots(k);
            // cpfg runs the pre block and tests the condition of every candidate.
            for (std::size_t r = k; r < cands.size(); ++r) {
                const Production& q = productions_[cands[r]];
                evaluating = &q;
                if (!q.probability) continue;
                if (r == k && !firstApplies) continue;
                if (!matches(q, s, i, slots)) continue;
                if (r != k && !q.preBlock.empty()) {
                    runStatements(q.preBlock, slots, draws);
                    keepSlots(r);
                }
                if (r != k && q.condition && evaluate(*q.condition, slots, draws) == 0) continue;
                if (firstApplicable == cands.size()) firstApplicable = r;
                double w = evaluate(*q.probability, slots, draws);
                if (w > 0) {
                    weights[r] = w;
                    sum += w;
                }
            }
            // The chosen production's slots, as its pre block left them.
            auto chosen = [&](std::size_t r) {
                if (r < afterPre.size() && !afterPre[r].empty())
                    std::copy(afterPre[r].begin(), afterPre[r].end(), slots);
                else
                    matches(productions_[cands[r]], s, i, slots);
                return static_cast<std::int32_t>(cands[r]);
            };
            // cpfg: when every applicable weight is 0, the first applicable production applies.
            if (sum <= 0)
                return firstApplicable == cands.size() ? kIdentity : chosen(firstApplicable);
            double u =
                uniformAt(seed_, static_cast<std::uint64_t>(stepNumber), position, 1u << 20) * sum;
            std::size_t last = k;
            for (std::size_t r = k; r < cands.size(); ++r) {
                if (weights[r] <= 0) continue;
                last = r;
                if (u < weights[r]) return chosen(r);
                u -= weights[r];
            }
            return chosen(last);  // rounding left u at the top end
        }
    } catch (const Error& err) {
        std::vector<Diagnostic> ds = err.diagnostics();
        if (evaluating && !ds.empty()) ds.back().location = evaluating->location;
        throw Error(std::move(ds));
    }
    return kIdentity;
}

// cpfg (generate.c): in a stochastic L-system every applicable production (predecessor,
// contexts, pre block and condition, in file order) adds its probability, a 32-bit float,
// to the total; one draw scaled by the total is then counted down through them in float
// arithmetic, and the first that takes it to 0 or below applies. The draw is made at every
// module, whether any production applies or not. Without `seed:` the first applicable
// production applies.
std::int32_t RewritingEngine::chooseCpfg(const ModuleString& s, std::size_t i, int stepNumber,
                                         int table, double* slots) const {
    const auto& cands = candidates_[static_cast<std::size_t>(table)][s.symbol(i)];
    Draws draws{this, static_cast<std::uint64_t>(stepNumber), i, 0};
    const Production* evaluating = nullptr;
    try {
        if (!cpfgStochastic_) {
            for (std::uint32_t k : cands) {
                const Production& p = productions_[k];
                evaluating = &p;
                if (!matches(p, s, i, slots)) continue;
                if (!p.preBlock.empty()) runStatements(p.preBlock, slots, draws);
                if (!p.condition || evaluate(*p.condition, slots, draws) != 0)
                    return static_cast<std::int32_t>(k);
            }
            return kIdentity;
        }
        struct Applicable {
            std::uint32_t production;
            float probability;
            std::vector<double> slots;  // as its pre block left them
        };
        std::vector<Applicable> applicable;
        float total = 0;
        for (std::uint32_t k : cands) {
            const Production& p = productions_[k];
            evaluating = &p;
            if (!matches(p, s, i, slots)) continue;
            if (!p.preBlock.empty()) runStatements(p.preBlock, slots, draws);
            if (p.condition && evaluate(*p.condition, slots, draws) == 0) continue;
            const float w =
                p.probability ? static_cast<float>(evaluate(*p.probability, slots, draws)) : 1.0f;
            total += w;
            applicable.push_back({k, w, std::vector<double>(slots, slots + maxSlots_)});
        }
        float u = static_cast<float>(static_cast<double>(total) * cpfg_->production());
        for (const Applicable& a : applicable) {
            u -= a.probability;
            if (u <= 0) {
                std::copy(a.slots.begin(), a.slots.end(), slots);
                return static_cast<std::int32_t>(a.production);
            }
        }
    } catch (const Error& err) {
        std::vector<Diagnostic> ds = err.diagnostics();
        if (evaluating && !ds.empty()) ds.back().location = evaluating->location;
        throw Error(std::move(ds));
    }
    return kIdentity;
}

bool RewritingEngine::rewrites(Symbol s) const {
    for (const auto& t : candidates_)
        if (s < t.size() && !t[s].empty()) return true;
    return false;
}

void RewritingEngine::expandOne(const ModuleString& s, std::size_t i, std::uint64_t position,
                                int stepNumber, int table, ModuleString& out) {
    table = std::clamp(table, 0, static_cast<int>(tableCount_) - 1);
    scratchSlots_.resize(static_cast<std::size_t>(maxSlots_));
    std::int32_t k;
    try {
        k = choose(s, i, position, stepNumber, table, scratchSlots_.data(), scratchWeights_);
    } catch (const Error& err) {
        rethrowAt(err, s, i, stepNumber);
    }
    if (k == kIdentity) {
        out.push(s.symbol(i), s.params(i));
        return;
    }
    const Production& p = productions_[static_cast<std::size_t>(k)];
    if (!parametric_) {
        for (const auto& m : p.successor) out.push(m.symbol);
        return;
    }
    // choose() left the chosen production's parameters in the slots.
    Draws draws{this, static_cast<std::uint64_t>(stepNumber), position, 1ull << 32};
    for (const auto& m : p.successor) {
        // As many values as the module has: a module may carry any number of parameters.
        std::size_t n = m.args.size();
        if (scratchArgs_.size() < n) scratchArgs_.resize(n);
        double* args = scratchArgs_.data();
        for (std::size_t a = 0; a < n; ++a) {
            try {
                args[a] = evaluate(m.args[a], scratchSlots_.data(), draws);
            } catch (const Error& err) {
                rethrowAt(err, s, i, stepNumber, &p);
            }
        }
        out.push(m.symbol, std::span<const double>(args, n));
    }
}

// ---- sequential path: productions with blocks ------------------------------------------

// cpfg's order: each module is rewritten in turn, its pre blocks and conditions run, then
// the chosen production's post block, then its successor's parameters. The order is the
// string's, on one thread, whatever the thread count.
bool RewritingEngine::stepSequential(const ModuleString& cur, ModuleString& next, int stepNumber,
                                     int table, std::size_t limit,
                                     const std::vector<std::uint8_t>* activeIn,
                                     std::vector<std::uint8_t>* activeOut) {
    std::size_t n = cur.size();
    if (needBrackets_) brackets_.build(cur.symbols());
    ModuleString out(cur.precision());
    out.reserve(n, cur.paramCount());
    if (parametric_ || cur.hasParameters()) out.rawParamStart().assign(1, 0);
    if (activeOut) activeOut->clear();
    std::vector<double> slots(static_cast<std::size_t>(maxSlots_)), weights, args;
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
        std::int32_t k = kIdentity;
        try {
            if (!activeIn || (*activeIn)[i])
                k = choose(cur, i, i, stepNumber, table, slots.data(), weights);
            if (k == kIdentity && cpfgCuts_ && cur.symbol(i) == '%') {
                // cpfg: the rest of the branch is left out, up to the ']' that closes it.
                int level = 1;
                while (i + 1 < n) {
                    const Symbol c = cur.symbol(i + 1);
                    if (c == '[') ++level;
                    if (c == ']' && --level == 0) break;
                    ++i;
                }
                continue;
            }
            if (k == kIdentity) {
                out.push(cur.symbol(i), cur.params(i));
                if (activeOut) activeOut->push_back(0);
                continue;
            }
            any = true;
            // choose() left the chosen production's parameters in the slots, as its pre
            // block may have changed them.
            const Production& p = productions_[static_cast<std::size_t>(k)];
            Draws draws{this, static_cast<std::uint64_t>(stepNumber), i, 1ull << 32};
            if (!p.postBlock.empty()) runStatements(p.postBlock, slots.data(), draws);
            for (const auto& m : p.successor) {
                args.clear();
                for (const auto& a : m.args) args.push_back(evaluate(a, slots.data(), draws));
                out.push(m.symbol, args);
                if (activeOut) activeOut->push_back(1);
            }
            i += p.predecessor.size() - 1;
        } catch (const Error& err) {
            rethrowAt(err, cur, i, stepNumber);
        }
        if ((i & 0xFFF) == 0) checkLimit(stepNumber, out.size(), out.paramCount(), 0, cur, limit);
    }
    checkLimit(stepNumber, out.size(), out.paramCount(), 0, cur, limit);
    next = std::move(out);
    return any;
}

}  // namespace graftal
