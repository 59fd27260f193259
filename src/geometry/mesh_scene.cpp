// Instanced scenes: the transforms' arithmetic, what a scene counts and bounds as drawn,
// flattening for formats without instancing (the builder is mesh_scene_builder.cpp).
#include "graftal/geometry/mesh_scene.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

namespace {

Vec3f add(const Vec3f& a, const Vec3f& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3f scaled(const Vec3f& a, float s) {
    return {a.x * s, a.y * s, a.z * s};
}
Vec3f crossf(const Vec3f& a, const Vec3f& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float dotf(const Vec3f& a, const Vec3f& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace

Vec3f Affine3f::point(const Vec3f& p) const {
    return add(add(add(scaled(columns[0], p.x), scaled(columns[1], p.y)), scaled(columns[2], p.z)),
               columns[3]);
}

Vec3f Affine3f::normal(const Vec3f& n) const {
    // The inverse transpose is the cofactor matrix over the determinant; the determinant's
    // sign is kept so that a mirrored normal still points out of the mirrored surface.
    const Vec3f c0 = crossf(columns[1], columns[2]);
    const Vec3f c1 = crossf(columns[2], columns[0]);
    const Vec3f c2 = crossf(columns[0], columns[1]);
    Vec3f m = add(add(scaled(c0, n.x), scaled(c1, n.y)), scaled(c2, n.z));
    if (determinant() < 0) m = scaled(m, -1);
    const float length = std::sqrt(dotf(m, m));
    return length > 0 && std::isfinite(length) ? scaled(m, 1 / length) : n;
}

float Affine3f::determinant() const {
    return dotf(columns[0], crossf(columns[1], columns[2]));
}

std::size_t MeshScene::triangleCount() const {
    std::size_t n = mesh.triangleCount();
    for (const MeshPlacement& p : placements) n += prototypes[p.prototype].triangleCount();
    return n;
}

std::size_t MeshScene::vertexCount() const {
    std::size_t n = mesh.positions.size();
    for (const MeshPlacement& p : placements) n += prototypes[p.prototype].positions.size();
    return n;
}

Bounds MeshScene::bounds() const {
    Bounds b = mesh.bounds();
    for (const MeshPlacement& p : placements)
        for (const Vec3f& v : prototypes[p.prototype].positions) {
            const Vec3f w = p.transform.point(v);
            if (std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z)) b.extend(toVec3(w));
        }
    for (const CurveSegment& c : curves) {
        const Vec3 ra{c.radiusA, c.radiusA, c.radiusA}, rb{c.radiusB, c.radiusB, c.radiusB};
        b.extend(toVec3(c.a) - ra);
        b.extend(toVec3(c.a) + ra);
        b.extend(toVec3(c.b) - rb);
        b.extend(toVec3(c.b) + rb);
    }
    return b;
}

Mesh MeshScene::flattened() const {
    if (vertexCount() > std::numeric_limits<std::uint32_t>::max())
        throw Error(SourceLocation{}, "the flattened mesh would have " +
                                          std::to_string(vertexCount()) +
                                          " vertices, more than 32-bit indices allow");
    Mesh out = mesh;
    out.positions.reserve(vertexCount());
    out.normals.reserve(vertexCount());
    out.indices.reserve(3 * triangleCount());
    out.triangleColor.reserve(triangleCount());
    for (const MeshPlacement& p : placements) appendCopy(p, out);
    return out;
}

void MeshScene::appendCopy(const MeshPlacement& p, Mesh& out) const {
    const Mesh& proto = prototypes[p.prototype];
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (const Vec3f& v : proto.positions) out.positions.push_back(p.transform.point(v));
    for (const Vec3f& n : proto.normals) out.normals.push_back(p.transform.normal(n));
    const bool mirrored = p.transform.determinant() < 0;
    for (std::size_t t = 0; t + 2 < proto.indices.size(); t += 3) {
        const std::uint32_t a = proto.indices[t], b = proto.indices[t + 1],
                            c = proto.indices[t + 2];
        if (mirrored)
            out.indices.insert(out.indices.end(), {base + a, base + c, base + b});
        else
            out.indices.insert(out.indices.end(), {base + a, base + b, base + c});
    }
    out.triangleColor.insert(out.triangleColor.end(), proto.triangleColor.begin(),
                             proto.triangleColor.end());
}

void MeshScene::print(std::ostream& os) const {
    os << "mesh scene: " << vertexCount() << " vertices, " << triangleCount()
       << " triangles as drawn, " << prototypes.size()
       << (prototypes.size() == 1 ? " prototype, " : " prototypes, ") << placements.size()
       << (placements.size() == 1 ? " placement, " : " placements, ") << curves.size()
       << (curves.size() == 1 ? " curve" : " curves") << ", bounds " << bounds();
}

std::ostream& operator<<(std::ostream& os, const MeshScene& s) {
    s.print(os);
    return os;
}

}  // namespace graftal
