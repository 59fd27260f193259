// Streamed derivation: the final string expanded depth-first, module by module, straight
// into a consumer (usually the turtle), with memory proportional to the derivation depth.
// For L-systems without context; the result is the same string, in the same order, with
// the same random choices as a materialised derivation.
#pragma once

#include <span>
#include <string>

#include "graftal/rewrite/derivation.hpp"

namespace graftal {

class ModuleSink {
  public:
    virtual ~ModuleSink() = default;
    virtual void module(Symbol symbol, std::span<const double> params) = 0;
};

// Empty when `lsystem` can be streamed; otherwise what prevents it (context, cut,
// decomposition, query modules or an environment, homomorphism).
std::string streamingObstacle(const LSystem& lsystem);

// Calls sink.module() for every module of the string derived in `steps` steps, in order.
// Throws Error when the L-system cannot be streamed.
void streamDerivation(const LSystem& lsystem, int steps, ModuleSink& sink,
                      const DerivationOptions& options = {});

}  // namespace graftal
