// Continuous development: a string drawn at a fractional time between two steps, every
// module with a declared age (`age: I(i)`) older by the fraction. The string's modules stay
// the L-system's own; only the ages the geometry is computed from change.
#pragma once

#include <vector>

#include "graftal/core/module_string.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"

namespace graftal {

// The model's age declarations.
std::vector<ModuleAge> moduleAges(const Model& model);

// `modules` with `fraction` (a fraction of a step) added to the age parameter of every
// module with a declared age (and as many parameters as the declaration).
ModuleString agedString(const ModuleString& modules, const std::vector<ModuleAge>& ages,
                        double fraction);

}  // namespace graftal
