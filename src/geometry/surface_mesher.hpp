// Placed bicubic surfaces as triangles: the private interface between the mesh builders
// (buildMesh copies every placed surface, buildMeshScene tessellates each surface once and
// places it by transform) and the tessellator.
#pragma once

#include <cstdint>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"
#include "graftal/geometry/surface.hpp"

namespace graftal::meshing {

// Where a surface lands: its contact point at the turtle, its heading along H, its up
// along U, scaled by the placement's scale over the surface's own size (cpfg's SIZE is the
// size the surface has at scale 1, as the .s parser documents). A mirrored turtle frame
// mirrors the surface.
class SurfacePlacement {
  public:
    SurfacePlacement(const Surface& surface, const SurfaceInstance& instance);
    // The surface in its own coordinates (what an instanced scene stores once).
    static SurfacePlacement own(const Surface& surface);

    bool valid() const;
    Vec3 point(const Vec3& p) const;
    Vec3 direction(const Vec3& v) const;
    Vec3 up() const { return u_; }
    // The same map in single precision: point(p) = affine().point(p) up to rounding.
    Affine3f affine() const;

  private:
    SurfacePlacement() = default;

    bool identity_ = false;
    Vec3 contact_, origin_;
    double scale_ = 1;
    Vec3 hs_, ls_, us_;  // the surface's own frame
    Vec3 h_, l_, u_;     // the turtle's
};

// Triangles of one patch grid at a time, with `divisions` cells per patch side.
class SurfaceTessellator {
  public:
    explicit SurfaceTessellator(int divisions);

    void append(const BezierPatch& patch, const SurfacePlacement& place, std::uint16_t color,
                Mesh& mesh);

    // Vertices and triangles (at most) one patch adds.
    std::size_t vertexCount() const { return points_.size(); }
    std::size_t triangleCount() const {
        return 2 * static_cast<std::size_t>(divisions_) * static_cast<std::size_t>(divisions_);
    }

  private:
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
              std::uint32_t base, std::uint16_t color, Mesh& mesh) const;
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t base,
                  std::uint16_t color, Mesh& mesh) const;

    int divisions_;
    std::vector<Vec3> points_, normals_;
};

}  // namespace graftal::meshing
