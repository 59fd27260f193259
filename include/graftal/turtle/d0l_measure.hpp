// The measures of `graftal stats` (segments, symbol counts, the box) for a derivation that
// is never written: a flat D0L-system's modules are walked straight from its productions.
//
// In a deterministic, context-free, non-parametric L-system the string a module derives in
// its remaining steps is fixed, so the walk goes depth first through the derivation tree
// and runs each small subtree from a precompiled list of turtle operations; symbol counts
// come from the productions alone (counts per step, multiplied out). A subtree that
// starts again from a frame it already started from (the same bits of H and L) makes the
// same moves: the second time its displacements are kept, and later it is replayed as a
// run of additions with no turn computed (Zucker, "Optimizing L-Systems", 2020, memoises
// subtrees the same way, by heading). Positions are still summed one move after another,
// in the generic turtle's order, so every count and every bit of the box is the same as
// the turtle's on the derived string, while the string (a byte per module) is never held.
#pragma once

#include <optional>

#include "graftal/core/cancellation.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"

namespace graftal {

// Which box the walk reports.
enum class MeasuredBox {
    Drawing,         // the drawn segments' ends: measureModules()'s bounds
    CpfgViewVolume,  // cpfgViewVolume() of the derived string
};

// measureModules(model, derive(model, steps)) (with `box` saying which bounds) without
// deriving; the ink is not summed (0). nullopt when the model is not a flat D0L-system
// this walk can follow: parameters, conditions, random choices, context, decomposition or
// homomorphism, polygons, @ and ~ commands, 3D turns, tropism, rewritten brackets, a ']'
// that would pop an empty stack, or a step length or turn that is not finite. Throws
// Cancelled when `cancel` is raised.
std::optional<StreamedMeasure> measureD0L(const Model& model, int steps, MeasuredBox box,
                                          const CancellationToken& cancel = {});

}  // namespace graftal
