// The pieces buildMesh and buildMeshScene share: the options' checks, the surfaces a scene
// names, and the mesh of everything that is not instanced.
#pragma once

#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/geometry/surface.hpp"

namespace graftal {
class TubeMesher;
}

namespace graftal::meshing {

class PolygonShapes;

// Throws Error for options out of range.
void checkMeshOptions(const MeshOptions& options);

// The surface each SurfaceInstance::surface index names, looked up once per name; throws
// Error for a name `library` does not hold.
std::vector<const Surface*> resolveSurfaces(const Scene& scene, const SurfaceLibrary* library);

// Discs and spheres: round enough at twice the sides of a stem.
int roundShapeSides(const MeshOptions& options);

// The tubes and polygons of `scene` (those `shapes` does not instance, all when it is
// null), and its discs, spheres and placed surfaces when `organs`, as one mesh, its
// storage allocated once (or kept: `mesh`'s arrays are reused).
void buildSharedMesh(const Scene& scene, const MeshOptions& options,
                     const std::vector<const Surface*>& resolved, const TubeMesher& tubes,
                     const PolygonShapes* shapes, bool organs, Mesh& mesh);

}  // namespace graftal::meshing
