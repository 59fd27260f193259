// Discs and spheres: their outlines for line art and their triangles for the mesh.
#include "round_shapes.hpp"

#include <cmath>

#include "graftal/vec3.hpp"

namespace graftal {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<Vec3> discOutline(const Disc& d, int sides) {
    const Vec3 n = normalizedOr(d.normal, {0, 0, 1});
    const Vec3 u = anyPerpendicular(n), v = cross(n, u);
    const Vec3 c = d.centre;
    std::vector<Vec3> out;
    out.reserve(static_cast<std::size_t>(sides));
    // Counter-clockwise seen from the side the normal points to (u x v = n).
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * kPi * i / sides;
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

void appendRoundShapes(const Scene& scene, int sides, Mesh& mesh) {
    for (const Disc& d : scene.discs) {
        if (!isFinite(d.centre) || !std::isfinite(d.radius)) continue;
        const Vec3f n = toVec3f(normalizedOr(d.normal, {0, 0, 1}));
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.push_back(toVec3f(d.centre));
        mesh.normals.push_back(n);
        for (const Vec3& p : discOutline(d, sides)) {
            mesh.positions.push_back(toVec3f(p));
            mesh.normals.push_back(n);
        }
        for (int i = 0; i < sides; ++i) {
            mesh.indices.push_back(base);
            mesh.indices.push_back(base + 1 + static_cast<std::uint32_t>(i));
            mesh.indices.push_back(base + 1 + static_cast<std::uint32_t>((i + 1) % sides));
            mesh.triangleColor.push_back(d.color);
        }
    }
    const int r = rings(sides);
    for (const Sphere& s : scene.spheres) {
        if (!isFinite(s.centre) || !std::isfinite(s.radius)) continue;
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        const Vec3 c = s.centre;
        // Rings from the south pole (-z) to the north pole, each with sides + 1 vertices
        // (the seam repeated) so that every quad has its own four corners.
        for (int i = 0; i <= r; ++i) {
            const double theta = kPi * i / r - kPi / 2;
            for (int j = 0; j <= sides; ++j) {
                const double phi = 2 * kPi * j / sides;
                const Vec3 n{std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi),
                             std::sin(theta)};
                mesh.positions.push_back(toVec3f(c + n * s.radius));
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
                mesh.triangleColor.push_back(s.color);
                mesh.triangleColor.push_back(s.color);
            }
        }
    }
}

}  // namespace meshing

}  // namespace graftal
