// What the parser keeps of an L-system's `environment:` lines; the environment layer
// (environment.hpp) reads them when the derivation starts.
#pragma once

#include <string>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

// `environment:` lines of an L-system file, kept raw for the environment to read.
struct EnvironmentLine {
    std::string text;  // everything after "environment:"
    SourceLocation location;
};

}  // namespace graftal
