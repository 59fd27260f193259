// Turtle interpretation: a module string becomes plain geometry (a Scene).
#pragma once

#include <functional>
#include <vector>

#include "graftal/core/module_string.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal {

// Interprets `modules` with the model's symbol table and view settings.
// Throws Error for a ']' with an empty stack or an unclosed '{'.
Scene interpret(const Model& model, const ModuleString& modules);
// The same for a grammar and a view held apart.
Scene interpret(const LSystem& lsystem, const ViewSettings& view, const ModuleString& modules);

// Walks the turtle over `modules` without building geometry, calling visit(i, frame) for
// every module whose symbol is flagged in `wanted` (indexed by symbol id).
void traceTurtle(const Model& model, const ModuleString& modules, const std::vector<bool>& wanted,
                 const std::function<void(std::size_t, const TurtleFrame&)>& visit);
void traceTurtle(const LSystem& lsystem, const ViewSettings& view, const ModuleString& modules,
                 const std::vector<bool>& wanted,
                 const std::function<void(std::size_t, const TurtleFrame&)>& visit);

// traceTurtle as a derivation's QueryResolver: the turtle, set up by `view` (a copy is
// kept), answers query modules.
QueryResolver turtleQueryResolver(ViewSettings view = {});

// derive() with the turtle answering query modules (unless `options` brings a resolver).
ModuleString deriveWithQueries(const LSystem& lsystem, int steps = -1,
                               DerivationOptions options = {});
ModuleString deriveWithQueries(const Model& model, int steps = -1, DerivationOptions options = {});

}  // namespace graftal
