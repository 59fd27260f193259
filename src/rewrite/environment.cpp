// The environment factory: reads an L-system's `environment:` lines.
#include "graftal/environment.hpp"

#include "graftal/lsystem.hpp"

namespace graftal {

std::unique_ptr<Environment> makeEnvironment(const LSystem& lsystem) {
    if (lsystem.environment.empty()) return nullptr;
    const EnvironmentLine& first = lsystem.environment.front();
    throw Error(first.location, "unknown environment '" + first.text + "'");
}

std::unique_ptr<Environment> makeExternalProcessEnvironment(const std::string& command) {
    throw Error(SourceLocation{"graftal", 0, 0}, "external environments are not available: " + command);
}

}  // namespace graftal
