// Open L-systems: the environment a plant talks to through communication modules ?E.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "graftal/diagnostics.hpp"
#include "graftal/scene.hpp"

namespace graftal {

class LSystem;

// Where the turtle is when it reaches a module, and which way it faces (H x L = U).
struct TurtleFrame {
    Vec3 position;
    Vec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, 1};
};

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

// `environment:` lines of an L-system file, kept raw for the environment to read.
struct EnvironmentLine {
    std::string text;  // everything after "environment:"
    SourceLocation location;
};

// Builds the environment an L-system's `environment:` lines ask for; nullptr when there
// are none. Throws Error (with the line's location) for an unknown environment or bad
// arguments.
std::unique_ptr<Environment> makeEnvironment(const LSystem& lsystem);

// Environments usable without a file, e.g. from C++.
std::unique_ptr<Environment> makeExternalProcessEnvironment(const std::string& command);

}  // namespace graftal
