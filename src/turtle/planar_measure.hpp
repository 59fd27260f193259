// Measuring a module string (counts, bounds, ink) with a turtle that stays in the z = 0
// plane: what `graftal stats` walks over hundreds of millions of modules. It is the
// generic turtle (turtle_machine.hpp) with everything a flat walk cannot change taken out,
// and gives bit for bit the same StreamedMeasure.
//
// Why it is exact: while only + - | [ ] turn the frame, the z components of H and L are
// zeros and the position's z stays +0 (a sum is -0 only when both terms are), so the same
// operations on x and y give the same doubles as the 3D frame, orthonormalised at the
// same turns; the zeros' signs can only reach other zeros, never a position, a bound or
// an ink length. The walk extends the bounds by a segment's start only when it may not be
// in the box yet (extending by a point already in changes nothing), and takes hypot()
// from a table of the sides it has seen (planar_length.hpp).
#pragma once

#include <optional>

#include "graftal/core/module_string.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"

namespace graftal::turtle {

// True when nothing the L-system derives turns the turtle out of the plane: no & ^ \ / @
// and no ~surface in the axiom or any successor, and no tropism.
bool staysPlanar(const Model& model);

// measureModules() by the planar walk. nullopt when the string leaves the plane after all
// (a module staysPlanar() could not see), takes a step or turn that is not finite, or is
// malformed: the generic walk then measures it, or words the error.
std::optional<StreamedMeasure> measurePlanar(const Model& model, const ModuleString& modules);

// measureModules() by the generic 3D turtle (streamed_interpretation.cpp): the reference
// the planar walk must match.
StreamedMeasure measureGeneric(const Model& model, const ModuleString& modules);

}  // namespace graftal::turtle
