// Open L-systems: the environment a plant talks to through communication modules ?E.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/lang/environment_line.hpp"

namespace graftal {

class LSystem;

// One ?E module: the environment reads its frame and parameters and writes its answer
// into the parameters.
struct CommunicationRequest {
    std::size_t module = 0;  // position in the module string
    TurtleFrame frame;
    std::span<double> params;
};

// Called after every derivation step (and once for the axiom) with all ?E modules of the
// string, in string order. Implementations must be deterministic.
class Environment {
  public:
    virtual ~Environment() = default;
    virtual std::string name() const = 0;
    virtual void respond(int step, std::span<CommunicationRequest> requests) = 0;
};

// Builds the environment an L-system's `environment:` lines ask for; nullptr when there
// are none. Throws Error (with the line's location) for an unknown environment or bad
// arguments.
std::unique_ptr<Environment> makeEnvironment(const LSystem& lsystem);

// Environments usable without a file, e.g. from C++.
std::unique_ptr<Environment> makeExternalProcessEnvironment(const std::string& command);

}  // namespace graftal
