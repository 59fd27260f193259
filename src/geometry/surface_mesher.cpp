// Placed bicubic surfaces as triangles (see surface_mesher.hpp).
#include "surface_mesher.hpp"

#include <algorithm>
#include <cmath>

#include "graftal/core/vec3.hpp"

namespace graftal::meshing {

namespace {

// A patch normal that vanishes (where control points coincide, as at a leaf's tip) is
// taken this far inside the patch instead.
constexpr double kNormalInset = 1e-3;

bool usableNormal(const Vec3& n) {
    return isFinite(n) && length(n) > 1e-12;
}

}  // namespace

SurfacePlacement::SurfacePlacement(const Surface& surface, const SurfaceInstance& instance)
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
    if (dot(u_, Vec3(instance.up)) < 0) u_ = -u_;
}

SurfacePlacement SurfacePlacement::own(const Surface& surface) {
    SurfacePlacement p;
    p.identity_ = true;
    p.hs_ = normalizedOr(Vec3(surface.heading), {0, 1, 0});
    p.us_ = perpendicularPart(Vec3(surface.up), p.hs_);
    p.ls_ = cross(p.us_, p.hs_);
    p.h_ = p.hs_;
    p.l_ = p.ls_;
    p.u_ = p.us_;
    return p;
}

bool SurfacePlacement::valid() const {
    return isFinite(origin_) && std::isfinite(scale_);
}

Vec3 SurfacePlacement::point(const Vec3& p) const {
    return identity_ ? p : origin_ + scale_ * direction(p - contact_);
}

Vec3 SurfacePlacement::direction(const Vec3& v) const {
    if (identity_) return v;
    return dot(v, hs_) * h_ + dot(v, ls_) * l_ + dot(v, us_) * u_;
}

Affine3f SurfacePlacement::affine() const {
    Affine3f a;
    if (identity_) return a;
    // Column j is the image of the unit axis e_j: scale * direction(e_j).
    const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int j = 0; j < 3; ++j) a.columns[j] = toVec3f(scale_ * direction(axes[j]));
    a.columns[3] = toVec3f(origin_ - scale_ * direction(contact_));
    return a;
}

SurfaceTessellator::SurfaceTessellator(int divisions)
    : divisions_(divisions),
      points_(static_cast<std::size_t>((divisions + 1) * (divisions + 1))),
      normals_(points_.size()) {}

void SurfaceTessellator::append(const BezierPatch& patch, const SurfacePlacement& place,
                                std::uint16_t color, Mesh& mesh) {
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
                auto inset = [](double x) { return std::clamp(x, kNormalInset, 1 - kNormalInset); };
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

// Splits a grid cell along a diagonal, wound to face the way the patch normals do: which
// way that is depends on the patch's parametrisation and on mirroring.
void SurfaceTessellator::quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                              std::uint32_t base, std::uint16_t color, Mesh& mesh) const {
    const Vec3 facing = cross(points_[c] - points_[a], points_[d] - points_[b]);
    const Vec3 normal = normals_[a] + normals_[b] + normals_[c] + normals_[d];
    if (dot(facing, normal) < 0) std::swap(b, d);
    triangle(a, b, c, base, color, mesh);
    triangle(a, c, d, base, color, mesh);
}

// Triangles collapsed by coinciding control points (a leaf's tip) are left out.
void SurfaceTessellator::triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                  std::uint32_t base, std::uint16_t color, Mesh& mesh) const {
    const Vec3f& pa = mesh.positions[base + a];
    const Vec3f& pb = mesh.positions[base + b];
    const Vec3f& pc = mesh.positions[base + c];
    if (pa == pb || pb == pc || pc == pa) return;
    mesh.indices.insert(mesh.indices.end(), {base + a, base + b, base + c});
    mesh.triangleColor.push_back(color);
}

}  // namespace graftal::meshing
