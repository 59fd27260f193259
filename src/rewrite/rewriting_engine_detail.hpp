// What the rewriting engine's files share (rewriting_engine.cpp: choosing and matching,
// rewriting_generic.cpp: the parallel two-pass step): how a step remembers its choices,
// when it splits across threads, how output buffers grow, and the random draws of one
// module.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "graftal/core/random_stream.hpp"
#include "rewriting_engine.hpp"

namespace graftal {

namespace rewriting_detail {

constexpr std::int32_t kIdentity = -1;  // no production applies: the module is copied
constexpr std::int32_t kConsumed = -2;  // part of a multi-module predecessor already rewritten

// A step remembers the production chosen for every module between its two passes, in two
// bytes per module (production k is k + 2): on a string of 10^8 modules that is 200 MB
// less than a 32-bit index, and fewer fresh pages to map.
using ChoiceCode = std::uint16_t;
constexpr ChoiceCode kIdentityCode = 1, kConsumedCode = 0;  // kIdentity + 2, kConsumed + 2
constexpr std::size_t kMaxChoiceProductions = 0xFFFF - 2;
inline ChoiceCode encodeChoice(std::int32_t k) {
    return static_cast<ChoiceCode>(k + 2);
}
inline std::int32_t decodeChoice(ChoiceCode c) {
    return static_cast<std::int32_t>(c) - 2;
}

// Below this many modules a step is not worth splitting across threads.
constexpr std::size_t kParallelThreshold = 1 << 16;

// How much larger than needed an output buffer is made when it has to grow (sizeOutput):
// a string that grows by 27% a step (Hogeweg-Hesper) then reallocates every ninth step.
constexpr std::size_t kHeadroom = 8;

inline bool arityMatches(const ModulePattern& p, const ModuleString& s, std::size_t j) {
    return p.formals.size() == s.params(j).size();
}

inline void bind(const ModulePattern& p, const ModuleString& s, std::size_t j, double* slots,
                 int& slot) {
    ParamView args = s.params(j);
    for (std::size_t k = 0; k < p.formals.size(); ++k) slots[slot++] = args[k];
}

// Sizes a step's output buffer to n elements, leaving its contents uninitialised. When it
// must grow, it grows to `most` elements: the buffer comes back two steps later for a
// longer string, and pages it already has cost nothing, while fresh pages are zeroed by the
// kernel first (the larger part of a step's time on big strings). Pages of the room it
// keeps are not touched until a string needs them.
template <class Vector>
void sizeOutput(Vector& v, std::size_t n, std::size_t most) {
    if (v.capacity() < n) {
        v.clear();
        v.reserve(std::max(n, most));
    }
    v.resize(n);
}

}  // namespace rewriting_detail

struct RewritingEngine::Draws {
    const RewritingEngine* engine;
    std::uint64_t step, position, next;
    bool reseeded = false;
    std::uint64_t seed = 0;
    double operator()() {
        return uniformAt(reseeded ? seed : engine->seed_, step, position, next++);
    }
    // srand(x): the same x restarts the same numbers (at this module of this step).
    void reseed(double x) {
        reseeded = true;
        if (!(std::fabs(x) < 9e18)) x = 0;
        seed = static_cast<std::uint64_t>(static_cast<std::int64_t>(x)) ^ 0x5eed5eed5eed5eedULL;
        next = 0;
    }
};

}  // namespace graftal
