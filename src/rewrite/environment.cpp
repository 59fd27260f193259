// The environment factory: reads an L-system's `environment:` lines and builds the
// environment they name. Also the small environments that need no file of their own.
#include "graftal/rewrite/environment.hpp"

#include <cctype>
#include <cmath>

#include "environment_detail.hpp"
#include "graftal/lang/expression.hpp"
#include "graftal/lang/lsystem.hpp"

namespace graftal {

// Shared by the environment_*.cpp files. No private header declares them, so each of those
// files repeats the declarations it uses; the definitions live here.
namespace environment_detail {

std::vector<EnvironmentLine> splitWords(const EnvironmentLine& line) {
    std::vector<EnvironmentLine> words;
    const std::string& t = line.text;
    std::size_t i = 0;
    while (i < t.size()) {
        while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
        std::size_t start = i;
        while (i < t.size() && !std::isspace(static_cast<unsigned char>(t[i]))) ++i;
        if (i == start) break;
        SourceLocation at = line.location;
        at.column += static_cast<int>(start);
        words.push_back({t.substr(start, i - start), at});
    }
    return words;
}

SourceLocation endOfLine(const EnvironmentLine& line) {
    std::size_t end = line.text.find_last_not_of(" \t\r\n");
    SourceLocation at = line.location;
    at.column += end == std::string::npos ? 0 : static_cast<int>(end + 1);
    return at;
}

// Numbers may be constant expressions without spaces (`2*R`), so that obstacles can share
// #define constants with the productions that draw them.
double numberWord(const EnvironmentLine& word, const std::string& what, const LSystem& lsystem) {
    double v = 0;
    try {
        v = evaluateConstant(word.text, word.location, lsystem.defines);
    } catch (const Error&) {
        throw Error(word.location, "expected " + what + " (a number), found '" + word.text + "'");
    }
    if (!std::isfinite(v))
        throw Error(word.location,
                    "expected " + what + " (a finite number), found '" + word.text + "'");
    return v;
}

}  // namespace environment_detail

namespace {

using environment_detail::splitWords;

constexpr const char* kEnvironmentNames = "obstacles, occupancy, light, clock, process";

// Answers every ?E with the number of the derivation step that produced the string (0 for
// the axiom): the environment's time. It is what reproduces the lecture's open L-system
// derivation exactly (examples/lecture-open-lsystem-distance-limit.l explains why).
class ClockEnvironment : public Environment {
  public:
    std::string name() const override { return "clock"; }
    void respond(int step, std::span<CommunicationRequest> requests) override {
        for (auto& r : requests)
            if (!r.params.empty()) r.params[0] = step;
    }
};

std::unique_ptr<Environment> makeClockEnvironment(const LSystem& lsystem) {
    for (std::size_t i = 0; i < lsystem.environment.size(); ++i) {
        auto words = splitWords(lsystem.environment[i]);
        if (words.size() > (i == 0 ? 1u : 0u)) {
            const EnvironmentLine& extra = words[i == 0 ? 1 : 0];
            throw Error(extra.location,
                        "the clock environment takes no arguments; found '" + extra.text + "'");
        }
    }
    return std::make_unique<ClockEnvironment>();
}

}  // namespace

std::unique_ptr<Environment> makeEnvironment(const LSystem& lsystem) {
    if (lsystem.environment.empty()) return nullptr;
    const EnvironmentLine& first = lsystem.environment.front();
    auto words = splitWords(first);
    if (words.empty())
        throw Error(first.location, "expected an environment name after 'environment:' (one of " +
                                        std::string(kEnvironmentNames) + ")");
    const std::string& name = words.front().text;
    if (name == "obstacles") return environment_detail::makeObstacleEnvironment(lsystem);
    if (name == "occupancy") return environment_detail::makeOccupancyEnvironment(lsystem, false);
    if (name == "light") return environment_detail::makeOccupancyEnvironment(lsystem, true);
    if (name == "clock") return makeClockEnvironment(lsystem);
    if (name == "process") return environment_detail::makeProcessEnvironment(lsystem);
    std::string hint;
    if (name == "sphere" || name == "box" || name == "plane")
        hint = " (obstacles follow a first line 'environment: obstacles')";
    throw Error(words.front().location,
                "unknown environment '" + name + "'; expected one of " + kEnvironmentNames + hint);
}

}  // namespace graftal
