// The triangle mesh of a scene: tubes for the segments (tube_mesher), triangles for the
// polygons (polygon_triangulation), discs and spheres (round_shapes) and tessellated
// patches for the placed surfaces.
//
// Conventions every writer and the ray tracer rely on: triangles are counter-clockwise
// seen from the side their vertex normals point to. Tubes are closed. Polygons and surface
// patches are single sheets: a polygon faces the side its outline runs counter-clockwise
// around (its Newell normal) and is flat-shaded; a patch faces along the normals of its
// Bézier surface. Duplicating every leaf back to back would double the polygons and put two
// coincident surfaces into the ray tracer, so viewers are asked to light both sides
// instead (the glTF materials are double-sided).
#include "graftal/geometry/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/huge_pages.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/geometry/generalized_cylinder.hpp"
#include "graftal/geometry/surface.hpp"
#include "mesh_parts.hpp"
#include "polygon_instancing.hpp"
#include "polygon_triangulation.hpp"
#include "round_shapes.hpp"
#include "surface_mesher.hpp"
#include "tube_mesher.hpp"

namespace graftal {

namespace {

constexpr int kMaxTubeSides = 1024;
constexpr int kMaxSurfaceDivisions = 1024;

Error meshError(const std::string& message) {
    return Error(SourceLocation{}, message);
}

}  // namespace

void meshing::checkMeshOptions(const MeshOptions& o) {
    if (o.tubeSides < 3 || o.tubeSides > kMaxTubeSides)
        throw meshError("tube sides must be between 3 and " + std::to_string(kMaxTubeSides) +
                        ", not " + std::to_string(o.tubeSides));
    if (o.surfaceDivisions < 1 || o.surfaceDivisions > kMaxSurfaceDivisions)
        throw meshError("surface divisions must be between 1 and " +
                        std::to_string(kMaxSurfaceDivisions) + ", not " +
                        std::to_string(o.surfaceDivisions));
    if (!(o.minimumRadius >= 0) || !std::isfinite(o.minimumRadius))
        throw meshError("the minimum radius must be a finite number >= 0");
    if (!(o.widthScale >= 0) || !std::isfinite(o.widthScale))
        throw meshError("the width scale must be a finite number >= 0");
    if (!(o.curveRadius >= 0) || !std::isfinite(o.curveRadius))
        throw meshError("the curve radius must be a finite number >= 0");
}

std::vector<const Surface*> meshing::resolveSurfaces(const Scene& scene,
                                                     const SurfaceLibrary* library) {
    std::vector<const Surface*> resolved(scene.surfaceNames.size(), nullptr);
    for (const SurfaceInstance& instance : scene.surfaces) {
        if (instance.surface >= scene.surfaceNames.size())
            throw meshError("a placed surface refers to surface number " +
                            std::to_string(instance.surface) + ", but the scene names only " +
                            std::to_string(scene.surfaceNames.size()));
        if (resolved[instance.surface]) continue;
        const std::string& name = scene.surfaceNames[instance.surface];
        if (!library)
            throw meshError("the scene places surface '" + name +
                            "' but no surface library was given");
        resolved[instance.surface] = library->find(name);
        if (!resolved[instance.surface]) {
            std::string known;
            for (const std::string& n : library->names()) known += (known.empty() ? "" : ", ") + n;
            throw meshError("unknown surface '" + name + "'" +
                            (known.empty() ? std::string(": the library is empty")
                                           : ": expected one of " + known));
        }
    }
    return resolved;
}

namespace {

// Polygons: flat-shaded, every outline vertex kept so that the triangulator's indices
// apply as they are.
void appendPolygons(const Scene& scene, const meshing::PolygonShapes* shapes, Mesh& mesh) {
    PolygonTriangulator triangulator;
    std::vector<std::uint32_t> triangles;
    const std::size_t count = std::min(
        scene.polygonColor.size(), scene.polygonStart.empty() ? 0 : scene.polygonStart.size() - 1);
    for (std::size_t k = 0; k < count; ++k) {
        if (shapes && shapes->instanced(k)) continue;
        const std::uint32_t begin = scene.polygonStart[k], end = scene.polygonStart[k + 1];
        if (begin > end || end > scene.polygonVertices.size()) continue;
        const std::span<const Vec3> outline(scene.polygonVertices.data() + begin, end - begin);
        triangles.clear();
        const Vec3 normal(triangulator.triangulate(outline, triangles));
        if (triangles.empty()) continue;
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (const Vec3& v : outline) {
            mesh.positions.push_back(toVec3f(v));
            mesh.normals.push_back(toVec3f(normal));
        }
        for (std::uint32_t i : triangles) mesh.indices.push_back(base + i);
        mesh.triangleColor.insert(mesh.triangleColor.end(), triangles.size() / 3,
                                  scene.polygonColor[k]);
    }
}

void appendSurfaces(const Scene& scene, const std::vector<const Surface*>& resolved, int divisions,
                    Mesh& mesh) {
    meshing::SurfaceTessellator tessellator(divisions);
    for (const SurfaceInstance& instance : scene.surfaces) {
        const Surface& surface = *resolved[instance.surface];
        const meshing::SurfacePlacement place(surface, instance);
        if (!place.valid()) continue;
        for (const BezierPatch& patch : surface.patches)
            tessellator.append(patch, place, instance.color, mesh);
    }
}

}  // namespace

Bounds Mesh::bounds() const {
    Bounds b;
    for (const Vec3f& p : positions)
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
            b.extend(Vec3{p.x, p.y, p.z});
    return b;
}

void Mesh::append(const Mesh& other) {
    if (palette.empty()) {
        palette = other.palette;
    } else if (!other.palette.empty() && other.palette != palette) {
        throw meshError("cannot append a mesh with a different palette");
    }
    if (positions.size() + other.positions.size() > std::numeric_limits<std::uint32_t>::max())
        throw meshError("the mesh would have more than 4294967295 vertices");
    const auto offset = static_cast<std::uint32_t>(positions.size());
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    normals.insert(normals.end(), other.normals.begin(), other.normals.end());
    indices.reserve(indices.size() + other.indices.size());
    for (std::uint32_t i : other.indices) indices.push_back(offset + i);
    triangleColor.insert(triangleColor.end(), other.triangleColor.begin(),
                         other.triangleColor.end());
}

void Mesh::print(std::ostream& os) const {
    std::vector<bool> used(std::numeric_limits<std::uint16_t>::max() + 1, false);
    std::size_t colors = 0;
    for (std::uint16_t c : triangleColor) {
        if (used[c]) continue;
        used[c] = true;
        ++colors;
    }
    os << "mesh: " << positions.size() << (positions.size() == 1 ? " vertex, " : " vertices, ")
       << triangleCount() << (triangleCount() == 1 ? " triangle, " : " triangles, ") << colors
       << (colors == 1 ? " colour" : " colours") << ", bounds " << bounds();
}

std::ostream& operator<<(std::ostream& os, const Mesh& m) {
    m.print(os);
    return os;
}

int meshing::roundShapeSides(const MeshOptions& options) {
    return std::max(16, 2 * options.tubeSides);
}

void meshing::buildSharedMesh(const Scene& scene, const MeshOptions& options,
                              const std::vector<const Surface*>& resolved, const TubeMesher& tubes,
                              const PolygonShapes* shapes, bool organs, Mesh& mesh) {
    // Everything is counted first so that the arrays are allocated once: a big plant's
    // mesh is hundreds of megabytes, and growing it by doubling would copy it repeatedly.
    std::size_t vertices = tubes.vertexCount(), triangles = tubes.triangleCount();
    for (std::size_t k = 0; k + 1 < scene.polygonStart.size(); ++k) {
        if (shapes && shapes->instanced(k)) continue;
        const std::uint32_t begin = scene.polygonStart[k], end = scene.polygonStart[k + 1];
        if (end > begin) vertices += end - begin;
        if (end > begin + 2) triangles += end - begin - 2;
    }
    const int roundSides = roundShapeSides(options);
    if (organs) {
        vertices += roundShapeVertices(scene, roundSides);
        triangles += roundShapeTriangles(scene, roundSides);
        const std::size_t grid = static_cast<std::size_t>(options.surfaceDivisions);
        for (const SurfaceInstance& instance : scene.surfaces) {
            const std::size_t patches = resolved[instance.surface]->patches.size();
            vertices += patches * (grid + 1) * (grid + 1);
            triangles += patches * 2 * grid * grid;
        }
    }
    if (vertices > std::numeric_limits<std::uint32_t>::max())
        throw meshError("the mesh would have " + std::to_string(vertices) +
                        " vertices, more than 32-bit indices allow; use fewer tube sides or "
                        "surface divisions");

    mesh.positions.clear();
    mesh.normals.clear();
    mesh.indices.clear();
    mesh.triangleColor.clear();
    mesh.palette = scene.palette;
    mesh.positions.reserve(vertices);
    mesh.normals.reserve(vertices);
    mesh.indices.reserve(3 * triangles);
    mesh.triangleColor.reserve(triangles);
    adviseHugePages(mesh.positions);
    adviseHugePages(mesh.normals);
    adviseHugePages(mesh.indices);
    adviseHugePages(mesh.triangleColor);
    tubes.append(mesh, options.threads);
    appendPolygons(scene, shapes, mesh);
    if (organs) {
        appendRoundShapes(scene, roundSides, mesh);
        appendSurfaces(scene, resolved, options.surfaceDivisions, mesh);
    }
}

Mesh buildMesh(const Scene& scene, const MeshOptions& options, const SurfaceLibrary* surfaces) {
    if (!scene.sweptTubes.empty()) {
        Mesh mesh = buildMesh(withoutSweptCentreLines(scene), options, surfaces);
        appendSweptTubes(scene, mesh);
        return mesh;
    }
    meshing::checkMeshOptions(options);
    MeshOptions tubesOnly = options;
    tubesOnly.curveRadius = 0;  // a Mesh has no curves
    const std::vector<const Surface*> resolved = meshing::resolveSurfaces(scene, surfaces);
    const TubeMesher tubes(scene, tubesOnly);
    Mesh mesh;
    meshing::buildSharedMesh(scene, tubesOnly, resolved, tubes, nullptr, true, mesh);
    return mesh;
}

}  // namespace graftal
