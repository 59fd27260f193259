// Discs and spheres (cpfg's @o, @c and @O) as triangles for the mesh.
#pragma once

#include <cstddef>

#include "graftal/mesh.hpp"
#include "graftal/scene.hpp"

namespace graftal::meshing {

// Vertices and triangles appendRoundShapes() adds for `scene` with `sides` around.
std::size_t roundShapeVertices(const Scene& scene, int sides);
std::size_t roundShapeTriangles(const Scene& scene, int sides);

// Each disc as a fan facing its normal (a single sheet, as polygons are), each sphere as
// a closed latitude-longitude ball with smooth normals.
void appendRoundShapes(const Scene& scene, int sides, Mesh& mesh);

}  // namespace graftal::meshing
