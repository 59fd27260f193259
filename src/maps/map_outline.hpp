// How the relaxation places the layer's outline (docs/maps.md, "The outline"): the rule that
// keeps the layer from collapsing while its interior vertices settle at their neighbours'
// centre of gravity.
#pragma once

#include "graftal/maps/plane_map.hpp"

namespace graftal {

// The axiom's polygon as the outline: its corners stay, and the vertices of each side are
// spread evenly along it.
void placeOutlineOnPolygon(PlaneMap& map);

// One round of the growing outline: every outline wall moves along its outward normal so
// that the cell behind it gains (or loses) a part of the difference between its area and
// the mean area of the cells along the outline, and every outline vertex slides halfway to
// the middle of its two outline neighbours. Moves are capped at a fraction of the vertex's
// outline walls, so the outline cannot fold over itself in one round.
void moveGrowingOutline(PlaneMap& map);

}  // namespace graftal
