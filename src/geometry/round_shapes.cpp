// Discs and spheres: their outlines for line art and their triangles for the mesh.
#include "round_shapes.hpp"

#include <cmath>
#include <numbers>

#include "graftal/core/vec3.hpp"

namespace graftal {

std::vector<Vec3> discOutline(const Disc& d, int sides) {
    const Vec3 n = normalizedOr(d.normal, {0, 0, 1});
    const Vec3 u = anyPerpendicular(n), v = cross(n, u);
    const Vec3 c = d.centre;
    std::vector<Vec3> out;
    out.reserve(static_cast<std::size_t>(sides));
    // Counter-clockwise seen from the side the normal points to (u x v = n).
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * std::numbers::pi * i / sides;
        out.push_back(c + u * (d.radius * std::cos(a)) + v * (d.radius * std::sin(a)));
    }
    return out;
}

namespace meshing {

namespace {
int rings(int sides) {
    return sides / 2 < 2 ? 2 : sides / 2;
}
}  // namespace

std::size_t roundShapeVertices(const Scene& scene, int sides) {
    const auto s = static_cast<std::size_t>(sides), r = static_cast<std::size_t>(rings(sides));
    return scene.discs.size() * (s + 1) + scene.spheres.size() * (r + 1) * (s + 1);
}

std::size_t roundShapeTriangles(const Scene& scene, int sides) {
    const auto s = static_cast<std::size_t>(sides), r = static_cast<std::size_t>(rings(sides));
    return scene.discs.size() * s + scene.spheres.size() * 2 * r * s;
}

namespace {

// A disc as a fan about its centre: the centre, then `outline` (counter-clockwise seen
// from the side `n` faces).
void appendDiscFan(const Vec3& centre, const std::vector<Vec3>& outline, const Vec3f& n,
                   std::uint16_t color, Mesh& mesh) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const auto sides = static_cast<std::uint32_t>(outline.size());
    mesh.positions.push_back(toVec3f(centre));
    mesh.normals.push_back(n);
    for (const Vec3& p : outline) {
        mesh.positions.push_back(toVec3f(p));
        mesh.normals.push_back(n);
    }
    for (std::uint32_t i = 0; i < sides; ++i) {
        mesh.indices.push_back(base);
        mesh.indices.push_back(base + 1 + i);
        mesh.indices.push_back(base + 1 + (i + 1) % sides);
        mesh.triangleColor.push_back(color);
    }
}

void appendBall(const Vec3& c, double radius, int sides, std::uint16_t color, Mesh& mesh) {
    const int r = rings(sides);
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    // Rings from the south pole (-z) to the north pole, each with sides + 1 vertices (the
    // seam repeated) so that every quad has its own four corners.
    for (int i = 0; i <= r; ++i) {
        const double theta = std::numbers::pi * i / r - std::numbers::pi / 2;
        for (int j = 0; j <= sides; ++j) {
            const double phi = 2 * std::numbers::pi * j / sides;
            const Vec3 n{std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi),
                         std::sin(theta)};
            mesh.positions.push_back(toVec3f(c + n * radius));
            mesh.normals.push_back(toVec3f(n));
        }
    }
    const auto row = static_cast<std::uint32_t>(sides + 1);
    for (int i = 0; i < r; ++i) {
        for (int j = 0; j < sides; ++j) {
            const std::uint32_t a = base + static_cast<std::uint32_t>(i) * row +
                                    static_cast<std::uint32_t>(j),
                                b = a + 1, c2 = a + row, d = c2 + 1;
            // Counter-clockwise seen from outside: phi grows to the east, theta north.
            for (std::uint32_t k : {a, b, d, a, d, c2}) mesh.indices.push_back(k);
            mesh.triangleColor.push_back(color);
            mesh.triangleColor.push_back(color);
        }
    }
}

}  // namespace

void appendRoundShapes(const Scene& scene, int sides, Mesh& mesh) {
    for (const Disc& d : scene.discs) {
        if (!isFinite(d.centre) || !std::isfinite(d.radius)) continue;
        appendDiscFan(d.centre, discOutline(d, sides), toVec3f(normalizedOr(d.normal, {0, 0, 1})),
                      d.color, mesh);
    }
    for (const Sphere& s : scene.spheres) {
        if (!isFinite(s.centre) || !std::isfinite(s.radius)) continue;
        appendBall(s.centre, s.radius, sides, s.color, mesh);
    }
}

Mesh unitDisc(int sides, std::uint16_t color) {
    Mesh mesh;
    std::vector<Vec3> outline;
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * std::numbers::pi * i / sides;
        outline.push_back({std::cos(a), std::sin(a), 0});
    }
    appendDiscFan({0, 0, 0}, outline, {0, 0, 1}, color, mesh);
    return mesh;
}

Mesh unitSphere(int sides, std::uint16_t color) {
    Mesh mesh;
    appendBall({0, 0, 0}, 1, sides, color, mesh);
    return mesh;
}

std::optional<Affine3f> discPlacement(const Disc& d) {
    if (!isFinite(d.centre) || !std::isfinite(d.radius) || d.radius == 0) return std::nullopt;
    // The frame discOutline() draws in.
    const Vec3 n = normalizedOr(d.normal, {0, 0, 1});
    const Vec3 u = anyPerpendicular(n), v = cross(n, u);
    Affine3f a;
    a.columns[0] = toVec3f(u * d.radius);
    a.columns[1] = toVec3f(v * d.radius);
    a.columns[2] = toVec3f(n * d.radius);
    a.columns[3] = toVec3f(d.centre);
    return a;
}

std::optional<Affine3f> spherePlacement(const Sphere& s) {
    if (!isFinite(s.centre) || !std::isfinite(s.radius) || s.radius == 0) return std::nullopt;
    Affine3f a;
    const auto r = static_cast<float>(s.radius);
    a.columns[0] = {r, 0, 0};
    a.columns[1] = {0, r, 0};
    a.columns[2] = {0, 0, r};
    a.columns[3] = toVec3f(s.centre);
    return a;
}

}  // namespace meshing

}  // namespace graftal
