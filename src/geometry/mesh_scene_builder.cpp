// buildMeshScene: the stems and the polygons drawn once in one mesh, every repeated organ
// (a placed surface, a disc, a ball, a polygon whose shape recurs) tessellated once as a
// prototype and placed by the transform that buildMesh applies to each copy, so that
// flattening the scene gives buildMesh's triangles (up to single-precision rounding).
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "graftal/geometry/generalized_cylinder.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/surface.hpp"
#include "mesh_parts.hpp"
#include "polygon_instancing.hpp"
#include "round_shapes.hpp"
#include "surface_mesher.hpp"
#include "tube_mesher.hpp"

namespace graftal {

namespace {

// A prototype is one organ in one colour (the colour is part of its triangles).
enum class OrganKind : std::uint8_t { Surface, Disc, Sphere };
using OrganKey = std::tuple<OrganKind, std::uint32_t, std::uint16_t>;

class PrototypeTable {
  public:
    explicit PrototypeTable(MeshScene& out) : out_(out) {}

    // The index of the prototype for `key`, made by `make` the first time it is asked for.
    template <class Make>
    std::uint32_t find(const OrganKey& key, Make&& make) {
        auto [it, fresh] = index_.try_emplace(key, 0);
        if (fresh) {
            it->second = static_cast<std::uint32_t>(out_.prototypes.size());
            Mesh m = make();
            m.palette = out_.mesh.palette;
            out_.prototypes.push_back(std::move(m));
        }
        return it->second;
    }

    void place(std::uint32_t prototype, const Affine3f& transform) {
        out_.placements.push_back({prototype, transform});
    }

  private:
    MeshScene& out_;
    std::map<OrganKey, std::uint32_t> index_;
};

// Whether a placement draws anything: a surface scaled to nothing collapses every triangle
// (which buildMesh leaves out), a non-finite one is skipped as buildMesh skips it.
bool drawable(const Affine3f& a) {
    const float det = a.determinant();
    return det != 0 && std::isfinite(det) && std::isfinite(a.columns[3].x) &&
           std::isfinite(a.columns[3].y) && std::isfinite(a.columns[3].z);
}

void instanceOrgans(const Scene& scene, const std::vector<const Surface*>& resolved,
                    const MeshOptions& options, MeshScene& out) {
    PrototypeTable table(out);
    out.placements.reserve(scene.surfaces.size() + scene.discs.size() + scene.spheres.size());
    meshing::SurfaceTessellator tessellator(options.surfaceDivisions);
    for (const SurfaceInstance& instance : scene.surfaces) {
        const Surface& surface = *resolved[instance.surface];
        const meshing::SurfacePlacement place(surface, instance);
        if (!place.valid()) continue;
        const Affine3f transform = place.affine();
        if (!drawable(transform)) continue;
        const std::uint32_t k =
            table.find({OrganKind::Surface, instance.surface, instance.color}, [&] {
                Mesh m;
                const meshing::SurfacePlacement own = meshing::SurfacePlacement::own(surface);
                for (const BezierPatch& patch : surface.patches)
                    tessellator.append(patch, own, instance.color, m);
                return m;
            });
        table.place(k, transform);
    }
    const int sides = meshing::roundShapeSides(options);
    for (const Disc& d : scene.discs) {
        const std::optional<Affine3f> transform = meshing::discPlacement(d);
        if (!transform || !drawable(*transform)) continue;
        table.place(table.find({OrganKind::Disc, 0, d.color},
                               [&] { return meshing::unitDisc(sides, d.color); }),
                    *transform);
    }
    for (const Sphere& s : scene.spheres) {
        const std::optional<Affine3f> transform = meshing::spherePlacement(s);
        if (!transform || !drawable(*transform)) continue;
        table.place(table.find({OrganKind::Sphere, 0, s.color},
                               [&] { return meshing::unitSphere(sides, s.color); }),
                    *transform);
    }
}

}  // namespace

MeshScene buildMeshScene(const Scene& scene, const MeshOptions& options,
                         const SurfaceLibrary* surfaces) {
    MeshScene out;
    buildMeshScene(scene, options, surfaces, out);
    return out;
}

void buildMeshScene(const Scene& scene, const MeshOptions& options, const SurfaceLibrary* surfaces,
                    MeshScene& out) {
    if (!scene.sweptTubes.empty()) {
        buildMeshScene(withoutSweptCentreLines(scene), options, surfaces, out);
        appendSweptTubes(scene, out.mesh);
        return;
    }
    meshing::checkMeshOptions(options);
    const std::vector<const Surface*> resolved = meshing::resolveSurfaces(scene, surfaces);
    const TubeMesher tubes(scene, options);
    std::optional<meshing::PolygonShapes> shapes;
    if (options.instancing) shapes.emplace(scene);
    out.prototypes.clear();
    out.placements.clear();
    out.curves.clear();
    meshing::buildSharedMesh(scene, options, resolved, tubes, shapes ? &*shapes : nullptr,
                             !options.instancing, out.mesh);
    if (options.instancing) {
        instanceOrgans(scene, resolved, options, out);
        shapes->instance(out);
    }
    tubes.appendCurves(out.curves);
}

}  // namespace graftal
