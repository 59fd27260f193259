#include "rewriting_engine.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>

#include "parallel.hpp"
#include "random_stream.hpp"

namespace graftal {

namespace {

constexpr std::int32_t kIdentity = -1;  // no production applies: the module is copied
constexpr std::int32_t kConsumed = -2;  // part of a multi-module predecessor already rewritten

// Below this many modules a step is not worth splitting across threads.
constexpr std::size_t kParallelThreshold = 1 << 16;

bool arityMatches(const ModulePattern& p, const ModuleString& s, std::size_t j) {
    return p.formals.size() == s.params(j).size();
}

void bind(const ModulePattern& p, const ModuleString& s, std::size_t j, double* slots, int& slot) {
    auto args = s.params(j);
    for (std::size_t k = 0; k < p.formals.size(); ++k) slots[slot++] = args[k];
}

}  // namespace

struct RewritingEngine::Draws {
    const RewritingEngine* engine;
    std::uint64_t step, position, next;
    double operator()() { return uniformAt(engine->seed_, step, position, next++); }
};

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
    }
    parametric_ |= ls.isParametric();
    tableCount_ = std::max<std::size_t>(1, ls.tableNames.size());
    fast_ = !multiPred_ && !parametric_ && !needBrackets_ && !stochastic;
    candidates_.assign(tableCount_, std::vector<std::vector<std::uint32_t>>(ls.symbols.size()));
    for (std::uint32_t k = 0; k < productions_.size(); ++k) {
        const Production& p = productions_[k];
        for (std::size_t t = 0; t < tableCount_; ++t)
            if (p.table < 0 || static_cast<std::size_t>(p.table) == t)
                candidates_[t][p.predecessor[0].symbol].push_back(k);
    }
    if (fast_) buildFastTables();
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
}

std::size_t RewritingEngine::chunkCount(std::size_t n) const {
    if (multiPred_ || n < kParallelThreshold) return 1;
    return threads_;
}

void RewritingEngine::checkLimit(int stepNumber, std::size_t modules, std::size_t params,
                                 std::size_t extra, const ModuleString& cur,
                                 std::size_t limit) const {
    double bytes = static_cast<double>(modules) * sizeof(Symbol) +
                   (parametric_ ? static_cast<double>(modules + 1) * 4 + params * 8.0 : 0.0);
    double total = bytes + static_cast<double>(cur.memoryBytes()) + static_cast<double>(extra);
    if (total > static_cast<double>(limit) || params > 0xFFFFFFFFull ||
        (needBrackets_ && modules > 0xFFFFFFFEull)) {
        throw Error(SourceLocation{ls_.file, 0, 0},
                    "derivation step " + std::to_string(stepNumber) + " would make a string of " +
                        std::to_string(modules) + " modules (" + formatBytes(bytes) + ", " +
                        formatBytes(total) +
                        " with the previous step), more than the memory limit of " +
                        formatBytes(static_cast<double>(limit)) +
                        "; lower the derivation length (-n) or raise --memory-limit");
    }
}

bool RewritingEngine::step(const ModuleString& cur, ModuleString& next, int stepNumber, int table,
                           std::size_t memoryLimit, const std::vector<std::uint8_t>* activeIn,
                           std::vector<std::uint8_t>* activeOut) {
    table = std::clamp(table, 0, static_cast<int>(tableCount_) - 1);
    if (fast_ && !activeIn && !activeOut)
        return stepFast(cur, next, stepNumber, table, memoryLimit);
    return stepGeneric(cur, next, stepNumber, table, memoryLimit, activeIn, activeOut);
}

// ---- fast path: deterministic, context-free, no parameters ------------------------------

bool RewritingEngine::stepFast(const ModuleString& cur, ModuleString& next, int stepNumber,
                               int table, std::size_t limit) {
    std::span<const Symbol> in = cur.symbols();
    std::size_t n = in.size();
    std::size_t chunks = chunkCount(n);
    std::vector<std::size_t> sizes(chunks, 0);
    const std::uint32_t* start = fastStart_[table].data();
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        std::size_t total = 0;
        for (std::size_t i = b; i < e; ++i) total += start[in[i] + 1] - start[in[i]];
        sizes[c] = total;
    });
    std::size_t total = std::accumulate(sizes.begin(), sizes.end(), std::size_t(0));
    checkLimit(stepNumber, total, 0, 0, cur, limit);
    next.clear();
    auto& out = next.rawSymbols();
    out.resize(total);
    std::vector<std::size_t> offsets(chunks, 0);
    std::exclusive_scan(sizes.begin(), sizes.end(), offsets.begin(), std::size_t(0));
    const Symbol* successors = fastSymbols_[table].data();
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        Symbol* o = out.data() + offsets[c];
        for (std::size_t i = b; i < e; ++i) {
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
    for (std::ptrdiff_t q = static_cast<std::ptrdiff_t>(pat.size()) - 1; q >= 0;) {
        if (j < 0) return false;
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
    for (std::size_t q = 0; q < p.right.size();) {
        const ModulePattern& m = p.right[q];
        if (m.symbol == ']') {
            if (depth == 0) return false;
            std::uint32_t close = brackets_.match(entered[--depth]);
            if (close == BracketIndex::kNone) return false;
            j = close + 1;
            ++q;
            continue;
        }
        if (j >= n) return false;
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
                                             int stepNumber) const {
    std::vector<Diagnostic> ds = err.diagnostics();
    std::string module = ls_.symbols.name(s.symbol(i));
    auto args = s.params(i);
    if (!args.empty()) {
        module += '(';
        for (std::size_t k = 0; k < args.size(); ++k)
            module += (k ? "," : "") + formatNumber(args[k]);
        module += ')';
    }
    if (!ds.empty())
        ds.back().message += " (while rewriting module " + std::to_string(i) + " '" + module +
                             "' in derivation step " + std::to_string(stepNumber) + ")";
    throw Error(std::move(ds));
}

double RewritingEngine::evaluate(const Expression& e, const double* slots, Draws& draws) const {
    std::span<const double> vars{slots, static_cast<std::size_t>(maxSlots_)};
    if (!e.usesRandom()) return e.evaluate(vars);
    EvalContext ctx;
    ctx.uniform = [&draws] { return draws(); };
    return e.evaluate(vars, &ctx);
}

std::int32_t RewritingEngine::choose(const ModuleString& s, std::size_t i, std::uint64_t position,
                                     int stepNumber, int table, double* slots,
                                     std::vector<double>& weights) const {
    const auto& cands = candidates_[static_cast<std::size_t>(table)][s.symbol(i)];
    Draws draws{this, static_cast<std::uint64_t>(stepNumber), position, 0};
    for (std::size_t k = 0; k < cands.size(); ++k) {
        const Production& p = productions_[cands[k]];
        if (!matches(p, s, i, slots)) continue;
        if (p.condition && evaluate(*p.condition, slots, draws) == 0) continue;
        if (!p.probability) return static_cast<std::int32_t>(cands[k]);
        // A stochastic group: every applicable production with a probability competes,
        // with weights normalised over the applicable ones (as cpfg does).
        weights.assign(cands.size(), 0.0);
        double sum = 0;
        for (std::size_t r = k; r < cands.size(); ++r) {
            const Production& q = productions_[cands[r]];
            if (!q.probability) continue;
            if (!matches(q, s, i, slots)) continue;
            if (r != k && q.condition && evaluate(*q.condition, slots, draws) == 0) continue;
            double w = evaluate(*q.probability, slots, draws);
            if (w > 0) {
                weights[r] = w;
                sum += w;
            }
        }
        if (sum <= 0) return kIdentity;
        double u =
            uniformAt(seed_, static_cast<std::uint64_t>(stepNumber), position, 1u << 20) * sum;
        std::size_t last = k;
        for (std::size_t r = k; r < cands.size(); ++r) {
            if (weights[r] <= 0) continue;
            last = r;
            if (u < weights[r]) return static_cast<std::int32_t>(cands[r]);
            u -= weights[r];
        }
        return static_cast<std::int32_t>(cands[last]);  // rounding left u at the top end
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
    matches(p, s, i, scratchSlots_.data());
    Draws draws{this, static_cast<std::uint64_t>(stepNumber), position, 1ull << 32};
    double args[64];
    for (const auto& m : p.successor) {
        std::size_t n = std::min<std::size_t>(m.args.size(), 64);
        for (std::size_t a = 0; a < n; ++a) {
            try {
                args[a] = evaluate(m.args[a], scratchSlots_.data(), draws);
            } catch (const Error& err) {
                rethrowAt(err, s, i, stepNumber);
            }
        }
        out.push(m.symbol, std::span<const double>(args, n));
    }
}

// ---- generic path -----------------------------------------------------------------------

bool RewritingEngine::stepGeneric(const ModuleString& cur, ModuleString& next, int stepNumber,
                                  int table, std::size_t limit,
                                  const std::vector<std::uint8_t>* activeIn,
                                  std::vector<std::uint8_t>* activeOut) {
    std::size_t n = cur.size();
    if (needBrackets_) brackets_.build(cur.symbols());
    choice_.resize(n);
    std::size_t chunks = chunkCount(n);
    std::vector<std::size_t> modCount(chunks, 0), paramCount(chunks, 0), rewritten(chunks, 0);
    const bool parametricOut = parametric_ || cur.hasParameters();

    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        std::vector<double> slots(static_cast<std::size_t>(maxSlots_));
        std::vector<double> weights;
        std::size_t mods = 0, params = 0, applied = 0;
        for (std::size_t i = b; i < e; ++i) {
            std::int32_t k = kIdentity;
            if (!activeIn || (*activeIn)[i]) {
                try {
                    k = choose(cur, i, i, stepNumber, table, slots.data(), weights);
                } catch (const Error& err) {
                    rethrowAt(err, cur, i, stepNumber);
                }
            }
            choice_[i] = k;
            if (k == kIdentity) {
                ++mods;
                params += cur.params(i).size();
                continue;
            }
            ++applied;
            const Production& p = productions_[static_cast<std::size_t>(k)];
            for (std::size_t q = 1; q < p.predecessor.size(); ++q) choice_[i + q] = kConsumed;
            i += p.predecessor.size() - 1;
            mods += p.successor.size();
            for (const auto& m : p.successor) params += m.args.size();
        }
        modCount[c] = mods;
        paramCount[c] = params;
        rewritten[c] = applied;
    });

    std::size_t totalMods = std::accumulate(modCount.begin(), modCount.end(), std::size_t(0));
    std::size_t totalParams = std::accumulate(paramCount.begin(), paramCount.end(), std::size_t(0));
    checkLimit(stepNumber, totalMods, totalParams, choice_.capacity() * sizeof(std::int32_t), cur,
               limit);

    std::vector<std::size_t> modOff(chunks), paramOff(chunks);
    std::exclusive_scan(modCount.begin(), modCount.end(), modOff.begin(), std::size_t(0));
    std::exclusive_scan(paramCount.begin(), paramCount.end(), paramOff.begin(), std::size_t(0));

    next.clear();
    auto& outSyms = next.rawSymbols();
    auto& outStart = next.rawParamStart();
    auto& outParams = next.rawParams();
    outSyms.resize(totalMods);
    if (parametricOut) {
        outStart.resize(totalMods + 1);
        outParams.resize(totalParams);
        outStart[totalMods] = static_cast<std::uint32_t>(totalParams);
    }
    if (activeOut) activeOut->assign(totalMods, 0);

    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        std::vector<double> slots(static_cast<std::size_t>(maxSlots_));
        std::size_t o = modOff[c], po = paramOff[c];
        for (std::size_t i = b; i < e; ++i) {
            std::int32_t k = choice_[i];
            if (k == kConsumed) continue;
            if (k == kIdentity) {
                outSyms[o] = cur.symbol(i);
                if (parametricOut) {
                    outStart[o] = static_cast<std::uint32_t>(po);
                    for (double v : cur.params(i)) outParams[po++] = v;
                }
                ++o;
                continue;
            }
            const Production& p = productions_[static_cast<std::size_t>(k)];
            if (activeOut)
                std::fill(activeOut->begin() + static_cast<std::ptrdiff_t>(o),
                          activeOut->begin() + static_cast<std::ptrdiff_t>(o + p.successor.size()),
                          1);
            if (!parametricOut) {
                for (const auto& m : p.successor) outSyms[o++] = m.symbol;
                continue;
            }
            matches(p, cur, i, slots.data());
            Draws draws{this, static_cast<std::uint64_t>(stepNumber), i, 1ull << 32};
            for (const auto& m : p.successor) {
                outSyms[o] = m.symbol;
                outStart[o] = static_cast<std::uint32_t>(po);
                for (const auto& a : m.args) {
                    try {
                        outParams[po++] = evaluate(a, slots.data(), draws);
                    } catch (const Error& err) {
                        rethrowAt(err, cur, i, stepNumber);
                    }
                }
                ++o;
            }
        }
    });
    return std::accumulate(rewritten.begin(), rewritten.end(), std::size_t(0)) > 0;
}

}  // namespace graftal
