// The public API of graftal: text -> LSystem -> module string -> geometry -> output.
#pragma once

#include "graftal/derivation.hpp"
#include "graftal/diagnostics.hpp"
#include "graftal/expression.hpp"
#include "graftal/lsystem.hpp"
#include "graftal/module_string.hpp"
#include "graftal/output.hpp"
#include "graftal/scene.hpp"
#include "graftal/turtle.hpp"
