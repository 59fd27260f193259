// Module counts from the production matrix M (M[s][t] = how many t a successor of s holds):
// the count vector of step k+1 is the count vector of step k times M.
#include "graftal/rewrite/growth.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

namespace graftal {

namespace {
constexpr std::uint32_t kBase = 1000000000u;
}

BigCount::BigCount(std::uint64_t v) {
    while (v) {
        limbs_.push_back(static_cast<std::uint32_t>(v % kBase));
        v /= kBase;
    }
}

BigCount& BigCount::operator+=(const BigCount& o) {
    if (limbs_.size() < o.limbs_.size()) limbs_.resize(o.limbs_.size(), 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < limbs_.size(); ++i) {
        std::uint64_t s = carry + limbs_[i] + (i < o.limbs_.size() ? o.limbs_[i] : 0);
        limbs_[i] = static_cast<std::uint32_t>(s % kBase);
        carry = s / kBase;
    }
    if (carry) limbs_.push_back(static_cast<std::uint32_t>(carry));
    return *this;
}

BigCount BigCount::times(std::uint64_t k) const {
    BigCount r;
    if (k == 0 || limbs_.empty()) return r;
    // k may exceed one limb: multiply by its base-10^9 digits and shift.
    BigCount factor(k);
    r.limbs_.assign(limbs_.size() + factor.limbs_.size() + 1, 0);
    for (std::size_t j = 0; j < factor.limbs_.size(); ++j) {
        std::uint64_t carry = 0;
        for (std::size_t i = 0; i < limbs_.size() || carry; ++i) {
            std::uint64_t cur =
                r.limbs_[i + j] + carry +
                (i < limbs_.size() ? std::uint64_t(limbs_[i]) * factor.limbs_[j] : 0);
            r.limbs_[i + j] = static_cast<std::uint32_t>(cur % kBase);
            carry = cur / kBase;
        }
    }
    while (!r.limbs_.empty() && r.limbs_.back() == 0) r.limbs_.pop_back();
    return r;
}

bool operator<(const BigCount& a, const BigCount& b) {
    if (a.limbs_.size() != b.limbs_.size()) return a.limbs_.size() < b.limbs_.size();
    for (std::size_t i = a.limbs_.size(); i-- > 0;)
        if (a.limbs_[i] != b.limbs_[i]) return a.limbs_[i] < b.limbs_[i];
    return false;
}

std::string BigCount::toString() const {
    if (limbs_.empty()) return "0";
    std::string s = std::to_string(limbs_.back());
    char buf[16];
    for (std::size_t i = limbs_.size() - 1; i-- > 0;) {
        std::snprintf(buf, sizeof buf, "%09u", limbs_[i]);
        s += buf;
    }
    return s;
}

std::size_t BigCount::digits() const {
    if (limbs_.empty()) return 1;
    return (limbs_.size() - 1) * 9 + std::to_string(limbs_.back()).size();
}

double BigCount::toDouble() const {
    double v = 0;
    for (std::size_t i = limbs_.size(); i-- > 0;) v = v * kBase + limbs_[i];
    return v;
}

std::optional<std::uint64_t> BigCount::toUint64() const {
    // 2^64 - 1 = 18 446744073 709551615 in base-10^9 limbs.
    if (limbs_.size() > 3) return std::nullopt;
    std::uint64_t low = 0;
    for (std::size_t i = std::min<std::size_t>(limbs_.size(), 2); i-- > 0;)
        low = low * kBase + limbs_[i];
    if (limbs_.size() < 3) return low;
    std::uint64_t high = limbs_[2];
    if (high > 18 || (high == 18 && low > 446744073709551615ull)) return std::nullopt;
    return high * 1000000000000000000ull + low;
}

namespace {

// Why a string's growth cannot be read off its productions alone; empty when it can.
std::string unpredictable(const LSystem& ls) {
    if (ls.hasContext()) return "context-sensitive productions make counts depend on the string";
    if (ls.hasMultiModulePredecessor())
        return "multi-module predecessors make counts depend on the string";
    if (!ls.decomposition.empty()) return "decomposition is not part of the prediction";
    if (ls.usesCut()) return "the cut symbol % makes counts depend on the string";
    if (!ls.environment.empty()) return "an environment makes counts depend on the simulation";
    for (const auto& p : ls.productions) {
        if (p.condition) return "conditions make counts depend on parameter values";
        if (p.probability && !p.probability->isConstant())
            return "probabilities that are expressions make counts depend on parameter values";
    }
    return {};
}

// Productions match a module by its symbol and its number of parameters: `L` and `L(i)`
// are rewritten by different productions (an `L(i) --> L` turns one kind into the other),
// so the prediction counts each (symbol, arity) as a kind of module of its own. Every kind
// a derivation can make is in the axiom or in a successor.
class ModuleKinds {
  public:
    explicit ModuleKinds(const LSystem& ls) {
        for (std::size_t i = 0; i < ls.axiom.size(); ++i)
            add(ls.axiom.symbol(i), ls.axiom.params(i).size());
        for (const auto& p : ls.productions)
            for (const auto& m : p.successor) add(m.symbol, m.args.size());
    }
    std::size_t size() const { return kinds_.size(); }
    Symbol symbol(std::size_t kind) const { return kinds_[kind].first; }
    std::size_t of(Symbol symbol, std::size_t arity) const { return index_.at({symbol, arity}); }
    std::optional<std::size_t> find(Symbol symbol, std::size_t arity) const {
        auto it = index_.find({symbol, arity});
        if (it == index_.end()) return std::nullopt;
        return it->second;
    }

  private:
    void add(Symbol symbol, std::size_t arity) {
        if (index_.emplace(std::pair{symbol, arity}, kinds_.size()).second)
            kinds_.emplace_back(symbol, arity);
    }
    std::vector<std::pair<Symbol, std::size_t>> kinds_;
    std::map<std::pair<Symbol, std::size_t>, std::size_t> index_;
};

}  // namespace

GrowthPrediction predictGrowth(const LSystem& ls, int steps) {
    GrowthPrediction g;
    g.reason = unpredictable(ls);
    if (!g.reason.empty()) return g;
    const ModuleKinds kinds(ls);
    const std::size_t n = kinds.size();
    bool stochastic = false;
    for (const auto& p : ls.productions) stochastic |= p.probability.has_value();

    std::size_t tables = std::max<std::size_t>(1, ls.tableNames.size());
    // Per table, per kind of module: (successor kind counts, weight) of each choice.
    struct Choice {
        std::vector<std::pair<std::size_t, std::uint64_t>> counts;
        double weight = 1;
    };
    std::vector<std::vector<std::vector<Choice>>> choices(tables,
                                                          std::vector<std::vector<Choice>>(n));
    for (std::size_t t = 0; t < tables; ++t) {
        for (const auto& p : ls.productions) {
            if (p.table >= 0 && static_cast<std::size_t>(p.table) != t) continue;
            // A production applies only to modules with as many parameters as its formals.
            const ModulePattern& pred = p.predecessor[0];
            std::optional<std::size_t> kind = kinds.find(pred.symbol, pred.formals.size());
            if (!kind) continue;  // no module it could rewrite ever exists
            auto& list = choices[t][*kind];
            // Deterministic: the first production wins, later ones never apply.
            if (!p.probability && !list.empty()) continue;
            if (p.probability && !list.empty() && list.front().weight < 0) continue;
            Choice c;
            std::map<std::size_t, std::uint64_t> hist;
            for (const auto& m : p.successor) ++hist[kinds.of(m.symbol, m.args.size())];
            c.counts.assign(hist.begin(), hist.end());
            c.weight = p.probability ? p.probability->evaluate({}) : -1;  // -1: deterministic
            list.push_back(std::move(c));
        }
    }

    std::vector<BigCount> exact(n);
    std::vector<double> expect(n, 0);
    for (std::size_t i = 0; i < ls.axiom.size(); ++i) {
        std::size_t k = kinds.of(ls.axiom.symbol(i), ls.axiom.params(i).size());
        exact[k] += BigCount(1);
        expect[k] += 1;
    }
    auto total = [&] {
        BigCount sum;
        double e = 0;
        for (std::size_t s = 0; s < n; ++s) {
            if (!stochastic) sum += exact[s];
            e += expect[s];
        }
        if (!stochastic) g.modules.push_back(sum);
        g.expectedModules.push_back(e);
    };
    total();
    for (int step = 1; step <= steps; ++step) {
        const auto& table = choices[static_cast<std::size_t>(ls.tableForStep(step))];
        std::vector<BigCount> nextExact(stochastic ? 0 : n);
        std::vector<double> nextExpect(n, 0);
        for (std::size_t s = 0; s < n; ++s) {
            if (expect[s] == 0) continue;
            const auto& list = table[s];
            if (list.empty()) {  // identity
                if (!stochastic) nextExact[s] += exact[s];
                nextExpect[s] += expect[s];
                continue;
            }
            double sum = 0;
            for (const auto& c : list) sum += std::max(c.weight, 0.0);
            bool deterministic = list.front().weight < 0;
            if (!deterministic && sum <= 0) {  // nothing can be chosen: identity
                nextExpect[s] += expect[s];
                continue;
            }
            for (const auto& c : list) {
                double share = deterministic ? 1.0 : std::max(c.weight, 0.0) / sum;
                for (auto [t, k] : c.counts) {
                    nextExpect[t] += expect[s] * share * static_cast<double>(k);
                    if (!stochastic) nextExact[t] += exact[s].times(k);
                }
                if (deterministic) break;
            }
        }
        exact = std::move(nextExact);
        expect = std::move(nextExpect);
        total();
        if (!stochastic && g.modules.back().digits() > kMaxExactDigits) {
            // Each further step would cost time and memory in proportion to the digits,
            // quadratic over a long derivation: go on with the expected values alone.
            stochastic = true;
            exact.clear();
            g.modules.clear();
        }
    }
    g.exact = !stochastic;
    g.expected = stochastic;
    if (stochastic)
        g.modules.clear();
    else {
        g.symbolsAtEnd.assign(ls.symbols.size(), BigCount());
        for (std::size_t k = 0; k < n; ++k) g.symbolsAtEnd[kinds.symbol(k)] += exact[k];
    }
    return g;
}

}  // namespace graftal
