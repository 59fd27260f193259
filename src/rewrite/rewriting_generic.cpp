// The generic rewriting step of RewritingEngine: parallel in two passes. The first chooses a
// production for every module and sums, per chunk, the modules and parameters the
// successors make; the second writes every successor at the offsets the sums give, so the
// string is the same for any thread count.
#include <algorithm>
#include <cstring>
#include <numeric>
#include <type_traits>

#include "graftal/core/parallel.hpp"
#include "rewriting_engine.hpp"
#include "rewriting_engine_detail.hpp"

namespace graftal {

using namespace rewriting_detail;

// ---- generic path -----------------------------------------------------------------------

// The first pass of a generic step: the production for every module (into choice_), and
// per chunk the modules and parameters its successors make and how many were rewritten.
void RewritingEngine::chooseAll(const ModuleString& cur, int stepNumber, int table,
                                const std::vector<std::uint8_t>* activeIn, std::size_t chunks,
                                std::vector<std::size_t>& modCount,
                                std::vector<std::size_t>& paramCount,
                                std::vector<std::size_t>& rewritten) {
    std::size_t n = cur.size();
    if (needBrackets_) brackets_.build(cur.symbols());
    // Every element is written below: no copy of the old ones, and room for later steps.
    if (choice_.capacity() < n) {
        choice_.clear();
        choice_.reserve(2 * n);
    }
    choice_.resize(n);
    modCount.assign(chunks, 0);
    paramCount.assign(chunks, 0);
    rewritten.assign(chunks, 0);
    const Symbol* syms = cur.symbols().data();
    // Module i's parameters are params[start[i] .. start[i + 1]) (none without start).
    const std::uint32_t* start = cur.hasParameters() ? cur.paramStarts().data() : nullptr;
    const QuickChoice* quick = quick_[static_cast<std::size_t>(table)].data();

    ChoiceCode* choice = choice_.data();
    forEachChunk(
        n, chunks, [&, syms, start, quick, choice](std::size_t c, std::size_t b, std::size_t e) {
            // Locals, not captures: the stores below could alias the closure for the compiler.
            const Symbol* in = syms;
            const std::uint32_t* from = start;
            const QuickChoice* fast = quick;
            ChoiceCode* chosen = choice;
            const std::uint32_t* successorModules = successorModules_.data();
            const std::uint32_t* successorParams = successorParams_.data();
            const std::uint8_t* active = activeIn ? activeIn->data() : nullptr;
            const bool genericOnly = genericOnly_;
            std::vector<double> slots(static_cast<std::size_t>(maxSlots_));
            std::vector<double> weights;
            std::size_t mods = 0, paramsOut = 0, applied = 0;
            for (std::size_t i = b; i < e; ++i) {
                std::int32_t k = kIdentity;
                std::uint32_t arity = from ? from[i + 1] - from[i] : 0;
                if (!active || active[i]) {
                    const QuickChoice& q = fast[in[i]];
                    if (q.simple && arity < kQuickArity && !genericOnly) {
                        k = q.byArity[arity];
                    } else {
                        try {
                            k = choose(cur, i, i, stepNumber, table, slots.data(), weights);
                        } catch (const Error& err) {
                            rethrowAt(err, cur, i, stepNumber);
                        }
                    }
                }
                chosen[i] = encodeChoice(k);
                if (k == kIdentity) {
                    ++mods;
                    paramsOut += arity;
                    continue;
                }
                ++applied;
                mods += successorModules[k];
                paramsOut += successorParams[k];
                std::size_t extra =
                    productions_[static_cast<std::size_t>(k)].predecessor.size() - 1;
                if (extra > 0) [[unlikely]] {
                    for (std::size_t q = 1; q <= extra; ++q) chosen[i + q] = kConsumedCode;
                    i += extra;
                }
            }
            modCount[c] = mods;
            paramCount[c] = paramsOut;
            rewritten[c] = applied;
        });
}

bool RewritingEngine::stepGeneric(const ModuleString& cur, ModuleString& next, int stepNumber,
                                  int table, std::size_t limit,
                                  const std::vector<std::uint8_t>* activeIn,
                                  std::vector<std::uint8_t>* activeOut) {
    const std::size_t n = cur.size();
    const std::size_t chunks = chunkCount(n);
    std::vector<std::size_t> modCount, paramCount, rewritten;
    chooseAll(cur, stepNumber, table, activeIn, chunks, modCount, paramCount, rewritten);
    const bool parametricOut = parametric_ || cur.hasParameters();

    std::size_t totalMods = std::accumulate(modCount.begin(), modCount.end(), std::size_t(0));
    std::size_t totalParams = std::accumulate(paramCount.begin(), paramCount.end(), std::size_t(0));
    checkLimit(stepNumber, totalMods, totalParams, n * sizeof(ChoiceCode), cur, limit);

    std::vector<std::size_t> modOff(chunks), paramOff(chunks);
    std::exclusive_scan(modCount.begin(), modCount.end(), modOff.begin(), std::size_t(0));
    std::exclusive_scan(paramCount.begin(), paramCount.end(), paramOff.begin(), std::size_t(0));

    prepareOutput(cur, next, totalMods, totalParams, parametricOut, n * sizeof(ChoiceCode), limit);
    Symbol* outSyms = next.rawSymbols().data();
    std::uint32_t* outStart = parametricOut ? next.rawParamStart().data() : nullptr;
    if (parametricOut) outStart[totalMods] = static_cast<std::uint32_t>(totalParams);
    if (activeOut) activeOut->assign(totalMods, 0);
    if (cur.precision() == Precision::Single)
        writeGeneric(cur, cur.floatParams().data(), next.rawFloats().data(), outSyms, outStart,
                     modOff, paramOff, chunks, stepNumber, activeOut);
    else
        writeGeneric(cur, cur.doubleParams().data(), next.rawParams().data(), outSyms, outStart,
                     modOff, paramOff, chunks, stepNumber, activeOut);
    return std::accumulate(rewritten.begin(), rewritten.end(), std::size_t(0)) > 0;
}

// The second pass of a generic step: every module's successor (or the module itself)
// written at the offsets the first pass summed. T is how the strings store parameters.
template <class T>
void RewritingEngine::writeGeneric(const ModuleString& cur, const T* params, T* outParams,
                                   Symbol* outSyms, std::uint32_t* outStart,
                                   const std::vector<std::size_t>& modOff,
                                   const std::vector<std::size_t>& paramOff, std::size_t chunks,
                                   int stepNumber, std::vector<std::uint8_t>* activeOut) {
    const std::size_t n = cur.size();
    const bool parametricOut = outStart != nullptr;
    const Symbol* syms = cur.symbols().data();
    const std::uint32_t* start = cur.hasParameters() ? cur.paramStarts().data() : nullptr;
    const ChoiceCode* choice = choice_.data();
    forEachChunk(
        n, chunks,
        [&, syms, start, params, outSyms, outStart, outParams, choice](std::size_t c, std::size_t b,
                                                                       std::size_t e) {
            // Locals, not captures: the stores below could alias the closure for the compiler.
            const Symbol* in = syms;
            const std::uint32_t* from = start;
            const T* values = params;
            const ChoiceCode* chosen = choice;
            Symbol* symOut = outSyms;
            std::uint32_t* startOut = outStart;
            T* paramOut = outParams;
            std::vector<double> slots(static_cast<std::size_t>(maxSlots_));
            std::size_t o = modOff[c], po = paramOff[c];
            for (std::size_t i = b; i < e; ++i) {
                const ChoiceCode code = chosen[i];
                if (code == kConsumedCode) continue;
                if (code == kIdentityCode) {
                    // A run of copies is copied at once: its parameters are contiguous in both
                    // strings, only shifted.
                    std::size_t j = i + 1;
                    while (j < e && chosen[j] == kIdentityCode) ++j;
                    std::memcpy(symOut + o, in + i, (j - i) * sizeof(Symbol));
                    if (parametricOut && from) {
                        auto shift = static_cast<std::uint32_t>(po) - from[i];
                        for (std::size_t t = 0; t < j - i; ++t)
                            startOut[o + t] = from[i + t] + shift;
                        std::size_t count = from[j] - from[i];
                        if (count > 0)
                            std::memcpy(paramOut + po, values + from[i], count * sizeof(T));
                        po += count;
                    } else if (parametricOut) {
                        std::fill(startOut + o, startOut + o + (j - i),
                                  static_cast<std::uint32_t>(po));
                    }
                    o += j - i;
                    i = j - 1;
                    continue;
                }
                const std::int32_t k = decodeChoice(code);
                const Production& p = productions_[static_cast<std::size_t>(k)];
                if (activeOut)
                    std::fill(
                        activeOut->begin() + static_cast<std::ptrdiff_t>(o),
                        activeOut->begin() + static_cast<std::ptrdiff_t>(o + p.successor.size()),
                        1);
                if (!parametricOut) {
                    for (const auto& m : p.successor) symOut[o++] = m.symbol;
                    continue;
                }
                try {
                    if (const Flat& f = flat_[static_cast<std::size_t>(k)];
                        f.direct && !genericOnly_) {
                        // Without contexts the predecessor's parameters are the slots, in order.
                        std::span<const double> vars;
                        if (from) {
                            const std::size_t arity = from[i + 1] - from[i];
                            if constexpr (std::is_same_v<T, double>) {
                                vars = {values + from[i], arity};
                            } else {
                                for (std::size_t a = 0; a < arity; ++a)
                                    slots[a] = static_cast<double>(values[from[i] + a]);
                                vars = {slots.data(), arity};
                            }
                        }
                        const std::size_t modules = f.symbols.size(), args = f.args.size();
                        for (std::size_t m = 0; m < modules; ++m) {
                            symOut[o + m] = f.symbols[m];
                            startOut[o + m] = static_cast<std::uint32_t>(po + f.argStart[m]);
                        }
                        for (std::size_t a = 0; a < args; ++a)
                            paramOut[po + a] = static_cast<T>(f.args[a]->evaluate(vars));
                        o += modules;
                        po += args;
                        continue;
                    }
                    matches(p, cur, i, slots.data());
                    Draws draws{this, static_cast<std::uint64_t>(stepNumber), i, 1ull << 32};
                    for (const auto& m : p.successor) {
                        symOut[o] = m.symbol;
                        startOut[o++] = static_cast<std::uint32_t>(po);
                        for (const auto& a : m.args)
                            paramOut[po++] = static_cast<T>(evaluate(a, slots.data(), draws));
                    }
                } catch (const Error& err) {
                    rethrowAt(err, cur, i, stepNumber, &p);
                }
            }
        });
}

bool RewritingEngine::countStep(const ModuleString& cur, std::vector<std::uint64_t>& counts,
                                int stepNumber, int table, std::size_t limit) {
    table = std::clamp(table, 0, static_cast<int>(tableCount_) - 1);
    // Blocks run per module in string order.
    if (sequential_) return false;
    const std::size_t n = cur.size();
    const std::size_t chunks = chunkCount(n);
    const std::size_t symbolCount = ls_.symbols.size();
    if (!genericOnly_ && !cur.hasParameters() && fast_) {
        // Each module's successor is fixed by its symbol: count the symbols, then add each
        // symbol's successor as many times.
        std::vector<std::vector<std::uint64_t>> seen(chunks);
        const Symbol* syms = cur.symbols().data();
        forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
            seen[c].assign(symbolCount, 0);
            for (std::size_t i = b; i < e; ++i) ++seen[c][syms[i]];
        });
        const std::vector<std::uint32_t>& start = fastStart_[static_cast<std::size_t>(table)];
        const std::vector<Symbol>& successors = fastSymbols_[static_cast<std::size_t>(table)];
        std::uint64_t total = 0;
        counts.assign(symbolCount, 0);
        for (std::size_t s = 0; s < symbolCount; ++s) {
            std::uint64_t times = 0;
            for (const auto& t : seen) times += t[s];
            if (times == 0) continue;
            for (std::uint32_t k = start[s]; k < start[s + 1]; ++k) counts[successors[k]] += times;
            total += times * (start[s + 1] - start[s]);
        }
        checkLimit(stepNumber, static_cast<std::size_t>(total), 0, 0, cur, limit);
        return true;
    }
    if (!genericOnly_ && !cur.hasParameters() && context_) {
        counts.assign(symbolCount, 0);
        const std::size_t total = context_->chooseAndCount(cur, stepNumber, table, chunks, counts);
        checkLimit(stepNumber, total, 0, 0, cur, limit);
        return true;
    }
    std::vector<std::size_t> modCount, paramCount, rewritten;
    chooseAll(cur, stepNumber, table, nullptr, chunks, modCount, paramCount, rewritten);
    // The string is not written, but the limit is the one the step would meet.
    checkLimit(stepNumber, std::accumulate(modCount.begin(), modCount.end(), std::size_t(0)),
               std::accumulate(paramCount.begin(), paramCount.end(), std::size_t(0)),
               n * sizeof(ChoiceCode), cur, limit);
    std::vector<std::vector<std::uint64_t>> tallies(chunks);
    const Symbol* syms = cur.symbols().data();
    const ChoiceCode* choice = choice_.data();
    forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
        std::vector<std::uint64_t>& t = tallies[c];
        t.assign(symbolCount, 0);
        for (std::size_t i = b; i < e; ++i) {
            const ChoiceCode code = choice[i];
            if (code == kIdentityCode) {
                ++t[syms[i]];
            } else if (code != kConsumedCode) {
                for (Symbol s : flat_[static_cast<std::size_t>(decodeChoice(code))].symbols) ++t[s];
            }
        }
    });
    counts.assign(symbolCount, 0);
    for (const auto& t : tallies)
        for (std::size_t k = 0; k < symbolCount; ++k) counts[k] += t[k];
    return true;
}

}  // namespace graftal
