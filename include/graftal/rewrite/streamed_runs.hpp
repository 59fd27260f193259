// The streamed derivation of deterministic L-systems without parameters, in runs at memory
// speed: the same string as streamDerivation() and derive(), in order, never held, but
// every subtree of the derivation small enough is expanded once and then handed over as a
// copy of that run, so that a string of billions of modules costs about one memcpy per
// byte (`graftal derive` of the Koch island at n = 10: 8·10⁹ modules).
#pragma once

#include <functional>
#include <span>

#include "graftal/rewrite/derivation.hpp"

namespace graftal {

// Whether streamDerivationRuns() can derive `lsystem`: it can be streamed
// (streamingObstacle()), and nothing makes a module's expansion depend on where it is: no
// parameters, conditions or stochastic productions.
bool streamsInRuns(const LSystem& lsystem);

// Calls emit(run) with the modules of the string derived in `steps` steps (the file's
// derivation length when negative), in order, in runs of up to about 64 K modules. Memory:
// the expansions kept (at most a few MB) and one successor per step. Looks at
// options.cancel between runs and reports options.progress every million modules. Throws
// Error when !streamsInRuns(lsystem).
void streamDerivationRuns(const LSystem& lsystem, int steps,
                          const std::function<void(std::span<const Symbol>)>& emit,
                          const DerivationOptions& options = {});

}  // namespace graftal
