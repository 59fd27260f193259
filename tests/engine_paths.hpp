// Tests of the engine's quick paths (context table, parametric binding): the same string,
// step by step, as the generic path that matches every module against every candidate.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "graftal/lang/lsystem.hpp"
#include "rewrite/rewriting_engine.hpp"

namespace graftal::testing {

// Rewrites `start` for `steps` steps with the generic path alone and, for each of
// `threads`, with the engine as derivations use it (step(), and stepConsuming(), which may
// write the context path's choices over the string it rewrites), and expects the same
// modules (and the same doubles) after every step. When `contextPath` is given, expects the engine to take
// (or not take) the single-module context path. Returns the last string.
inline ModuleString expectSameAsGenericPath(const LSystem& ls, const ModuleString& start, int steps,
                                            const std::string& what,
                                            std::initializer_list<unsigned> threads,
                                            std::optional<bool> contextPath = {}) {
    const std::size_t noLimit = std::size_t(1) << 40;
    RewritingEngine generic(ls, ls.productions, ls.seed, 1);
    generic.useGenericPathOnly();
    std::vector<ModuleString> expected{start};
    ModuleString next;
    for (int k = 1; k <= steps; ++k) {
        generic.step(expected.back(), next, k, ls.tableForStep(k), noLimit);
        expected.push_back(next);
    }
    for (unsigned t : threads) {
        for (bool consuming : {false, true}) {
            RewritingEngine engine(ls, ls.productions, ls.seed, t);
            if (contextPath) {
                EXPECT_EQ(engine.usesContextPath(), *contextPath) << what;
            }
            ModuleString s = start;
            for (int k = 1; k <= steps; ++k) {
                if (consuming)
                    engine.stepConsuming(s, next, k, ls.tableForStep(k), noLimit);
                else
                    engine.step(s, next, k, ls.tableForStep(k), noLimit);
                std::swap(s, next);
                if (!(s == expected[static_cast<std::size_t>(k)])) {
                    ADD_FAILURE() << what << ": step " << k << " with " << t << " threads"
                                  << (consuming ? ", consuming" : "") << " (" << s.size()
                                  << " modules, expected "
                                  << expected[static_cast<std::size_t>(k)].size() << ")";
                    break;
                }
            }
        }
    }
    return expected.back();
}

}  // namespace graftal::testing
