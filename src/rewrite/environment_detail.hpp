// What the environment files share: reading the words of `environment:` lines, and the
// factories of the built-in environments (environment.cpp picks one by name).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "graftal/lang/lsystem.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal::environment_detail {

// The line's words, each with its own location (for errors that point at the word).
std::vector<EnvironmentLine> splitWords(const EnvironmentLine& line);
SourceLocation endOfLine(const EnvironmentLine& line);
// A word read as a constant expression (with the file's #define names); Error if not.
double numberWord(const EnvironmentLine& word, const std::string& what, const LSystem& lsystem);

std::unique_ptr<Environment> makeObstacleEnvironment(const LSystem& lsystem);
std::unique_ptr<Environment> makeOccupancyEnvironment(const LSystem& lsystem, bool light);
std::unique_ptr<Environment> makeProcessEnvironment(const LSystem& lsystem);

}  // namespace graftal::environment_detail
