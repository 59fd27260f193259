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
#include "graftal/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "graftal/diagnostics.hpp"
#include "graftal/generalized_cylinder.hpp"
#include "graftal/surface.hpp"
#include "graftal/vec3.hpp"
#include "polygon_triangulation.hpp"
#include "round_shapes.hpp"
#include "tube_mesher.hpp"

namespace graftal {

namespace {

constexpr int kMaxTubeSides = 1024;
constexpr int kMaxSurfaceDivisions = 1024;
// A patch normal that vanishes (where control points coincide, as at a leaf's tip) is
// taken this far inside the patch instead.
constexpr double kNormalInset = 1e-3;

Error meshError(const std::string& message) {
    return Error(SourceLocation{}, message);
}

void checkOptions(const MeshOptions& o) {
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
}

// The surface each SurfaceInstance::surface index names, looked up once per name.
std::vector<const Surface*> resolveSurfaces(const Scene& scene, const SurfaceLibrary* library) {
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

// Polygons: flat-shaded, every outline vertex kept so that the triangulator's indices
// apply as they are.
void appendPolygons(const Scene& scene, Mesh& mesh) {
    PolygonTriangulator triangulator;
    std::vector<std::uint32_t> triangles;
    const std::size_t count = std::min(
        scene.polygonColor.size(), scene.polygonStart.empty() ? 0 : scene.polygonStart.size() - 1);
    for (std::size_t k = 0; k < count; ++k) {
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

// Where a surface lands: its contact point at the turtle, its heading along H, its up
// along U, scaled by the placement's scale over the surface's own size (cpfg's SIZE is the
// size the surface has at scale 1, as the .s parser documents).
class SurfacePlacement {
  public:
    SurfacePlacement(const Surface& surface, const SurfaceInstance& instance)
        : contact_(surface.contactPoint),
          origin_(instance.origin),
          scale_(instance.scale /
                 (surface.size > 0 && std::isfinite(surface.size) ? surface.size : 1)) {
        hs_ = normalizedOr(Vec3(surface.heading), {0, 1, 0});
        us_ = perpendicularPart(Vec3(surface.up), hs_);
        ls_ = cross(us_, hs_);
        h_ = normalizedOr(Vec3(instance.heading), {0, 1, 0});
        l_ = perpendicularPart(Vec3(instance.left), h_);
        u_ = cross(h_, l_);
        // A mirrored turtle frame mirrors the surface.
        if (dot(u_, Vec3(instance.up)) < 0) u_ = -u_;
    }

    bool valid() const { return isFinite(origin_) && std::isfinite(scale_); }
    Vec3 point(const Vec3& p) const { return origin_ + scale_ * direction(p - contact_); }
    Vec3 direction(const Vec3& v) const {
        return dot(v, hs_) * h_ + dot(v, ls_) * l_ + dot(v, us_) * u_;
    }
    Vec3 up() const { return u_; }

  private:
    Vec3 contact_, origin_;
    double scale_;
    Vec3 hs_, ls_, us_;  // the surface's own frame
    Vec3 h_, l_, u_;     // the turtle's
};

class SurfaceTessellator {
  public:
    explicit SurfaceTessellator(int divisions)
        : divisions_(divisions),
          points_((divisions + 1) * (divisions + 1)),
          normals_(points_.size()) {}

    void append(const BezierPatch& patch, const SurfacePlacement& place, std::uint16_t color,
                Mesh& mesh) {
        const int d = divisions_;
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (int row = 0; row <= d; ++row) {
            for (int col = 0; col <= d; ++col) {
                const double s = static_cast<double>(col) / d, t = static_cast<double>(row) / d;
                const std::size_t k = static_cast<std::size_t>(row * (d + 1) + col);
                Vec3 n;
                points_[k] = place.point(Vec3(evaluatePatch(patch, s, t, &n)));
                normals_[k] = place.direction(Vec3(n));
                if (!usableNormal(normals_[k])) {
                    auto inset = [](double x) {
                        return std::clamp(x, kNormalInset, 1 - kNormalInset);
                    };
                    evaluatePatch(patch, inset(s), inset(t), &n);
                    normals_[k] = place.direction(Vec3(n));
                }
                normals_[k] =
                    usableNormal(normals_[k]) ? normalizedOr(normals_[k], place.up()) : place.up();
                mesh.positions.push_back(toVec3f(points_[k]));
                mesh.normals.push_back(toVec3f(normals_[k]));
            }
        }
        for (int row = 0; row < d; ++row) {
            for (int col = 0; col < d; ++col) {
                const auto k = static_cast<std::uint32_t>(row * (d + 1) + col);
                quad(k, k + 1, k + d + 2, k + d + 1, base, color, mesh);
            }
        }
    }

  private:
    static bool usableNormal(const Vec3& n) { return isFinite(n) && length(n) > 1e-12; }

    // Splits a grid cell along a diagonal, wound to face the way the patch normals do:
    // which way that is depends on the patch's parametrisation and on mirroring.
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
              std::uint32_t base, std::uint16_t color, Mesh& mesh) const {
        const Vec3 facing = cross(points_[c] - points_[a], points_[d] - points_[b]);
        const Vec3 normal = normals_[a] + normals_[b] + normals_[c] + normals_[d];
        if (dot(facing, normal) < 0) std::swap(b, d);
        triangle(a, b, c, base, color, mesh);
        triangle(a, c, d, base, color, mesh);
    }

    // Triangles collapsed by coinciding control points (a leaf's tip) are left out.
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t base,
                  std::uint16_t color, Mesh& mesh) const {
        const Vec3f& pa = mesh.positions[base + a];
        const Vec3f& pb = mesh.positions[base + b];
        const Vec3f& pc = mesh.positions[base + c];
        if (pa == pb || pb == pc || pc == pa) return;
        mesh.indices.insert(mesh.indices.end(), {base + a, base + b, base + c});
        mesh.triangleColor.push_back(color);
    }

    int divisions_;
    std::vector<Vec3> points_, normals_;
};

void appendSurfaces(const Scene& scene, const std::vector<const Surface*>& resolved, int divisions,
                    Mesh& mesh) {
    SurfaceTessellator tessellator(divisions);
    for (const SurfaceInstance& instance : scene.surfaces) {
        const Surface& surface = *resolved[instance.surface];
        const SurfacePlacement place(surface, instance);
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

Mesh buildMesh(const Scene& scene, const MeshOptions& options, const SurfaceLibrary* surfaces) {
    if (!scene.sweptTubes.empty()) return buildMeshWithSweptTubes(scene, options, surfaces);
    checkOptions(options);
    const std::vector<const Surface*> resolved = resolveSurfaces(scene, surfaces);
    const TubeMesher tubes(scene, options);

    // Everything is counted first so that the arrays are allocated once: a big plant's
    // mesh is hundreds of megabytes, and growing it by doubling would copy it repeatedly.
    std::size_t vertices = tubes.vertexCount(), triangles = tubes.triangleCount();
    vertices += scene.polygonVertices.size();
    for (std::size_t k = 0; k + 1 < scene.polygonStart.size(); ++k) {
        const std::uint32_t begin = scene.polygonStart[k], end = scene.polygonStart[k + 1];
        if (end > begin + 2) triangles += end - begin - 2;
    }
    // Discs and spheres: round enough at twice the sides of a stem.
    const int roundSides = std::max(16, 2 * options.tubeSides);
    vertices += meshing::roundShapeVertices(scene, roundSides);
    triangles += meshing::roundShapeTriangles(scene, roundSides);
    const std::size_t grid = static_cast<std::size_t>(options.surfaceDivisions);
    for (const SurfaceInstance& instance : scene.surfaces) {
        const std::size_t patches = resolved[instance.surface]->patches.size();
        vertices += patches * (grid + 1) * (grid + 1);
        triangles += patches * 2 * grid * grid;
    }
    if (vertices > std::numeric_limits<std::uint32_t>::max())
        throw meshError("the mesh would have " + std::to_string(vertices) +
                        " vertices, more than 32-bit indices allow; use fewer tube sides or "
                        "surface divisions");

    Mesh mesh;
    mesh.palette = scene.palette;
    mesh.positions.reserve(vertices);
    mesh.normals.reserve(vertices);
    mesh.indices.reserve(3 * triangles);
    mesh.triangleColor.reserve(triangles);
    tubes.append(mesh);
    appendPolygons(scene, mesh);
    meshing::appendRoundShapes(scene, roundSides, mesh);
    appendSurfaces(scene, resolved, options.surfaceDivisions, mesh);
    return mesh;
}

}  // namespace graftal
