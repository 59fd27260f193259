// Discs and spheres (cpfg's @o, @c and @O) as triangles for the mesh.
#pragma once

#include <cstddef>
#include <optional>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal::meshing {

// Vertices and triangles appendRoundShapes() adds for `scene` with `sides` around.
std::size_t roundShapeVertices(const Scene& scene, int sides);
std::size_t roundShapeTriangles(const Scene& scene, int sides);

// Each disc as a fan facing its normal (a single sheet, as polygons are), each sphere as
// a closed latitude-longitude ball with smooth normals.
void appendRoundShapes(const Scene& scene, int sides, Mesh& mesh);

// The prototypes an instanced scene places: a disc of radius 1 about the origin facing +z
// and a ball of radius 1 about the origin, each as appendRoundShapes() draws them.
Mesh unitDisc(int sides, std::uint16_t color);
Mesh unitSphere(int sides, std::uint16_t color);
// Where those go: unitDisc() onto `d` (its outline's frame as discOutline() draws it) and
// unitSphere() onto `s`. Empty when the shape is not finite or has no size.
std::optional<Affine3f> discPlacement(const Disc& d);
std::optional<Affine3f> spherePlacement(const Sphere& s);

}  // namespace graftal::meshing
