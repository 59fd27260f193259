// A derived map as plain geometry (a Scene) for the picture writers: the walls as straight
// lines whose width grows with their age (the book's Figs 5.2a, 5.2b), or each cell as a
// closed B-spline through its vertices (Fig 5.2c); cells optionally filled.
#pragma once

#include <optional>
#include <string>

#include "graftal/geometry/scene.hpp"
#include "graftal/maps/plane_map.hpp"

namespace graftal {

enum class MapFill {
    None,
    Age,     // by the step the cell was made: older cells darker
    Sides,   // by the number of walls
    Labels,  // by the cycle of wall labels: cells in the same state share a colour
};

struct MapDrawingOptions {
    bool splines = false;  // cells as closed uniform cubic B-splines (Beta-splines with
                           // bias 1 and tension 0) through their vertices
    int splineSubdivisions = 8;
    bool widthByAge = true;  // a wall made k steps ago is drawn k + 1 times as wide
    MapFill fill = MapFill::None;
};

Scene mapScene(const PlaneMap& map, const MapDrawingOptions& options = {});

// "none", "age", "sides", "labels"; nullopt for anything else.
std::optional<MapFill> mapFillFromName(const std::string& name);

}  // namespace graftal
