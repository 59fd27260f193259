// Placements as translation, rotation and scale, and mirrored prototypes.
#include "instance_transform.hpp"

#include <cmath>

namespace graftal::instance_transform {

namespace {

// Columns whose cosine is below this are taken as orthogonal: a turtle frame rounded to
// floats is orthogonal to about 1e-7; what is left over moves a vertex by less than 1e-4
// of the organ's size.
constexpr double kOrthogonality = 1e-4;

double dot(const Vec3f& a, const Vec3f& b) {
    return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y +
           static_cast<double>(a.z) * b.z;
}

// A unit quaternion (x, y, z, w) of the rotation whose columns are c[0..2], by the branch
// that divides by the largest of the four candidates (Shepperd's method).
std::array<float, 4> quaternionOf(const double c[3][3]) {
    // r(i, j): row i, column j.
    auto r = [&](int i, int j) { return c[j][i]; };
    const double trace = r(0, 0) + r(1, 1) + r(2, 2);
    double q[4];  // x, y, z, w
    if (trace > 0) {
        const double s = 2 * std::sqrt(trace + 1);
        q[3] = s / 4;
        q[0] = (r(2, 1) - r(1, 2)) / s;
        q[1] = (r(0, 2) - r(2, 0)) / s;
        q[2] = (r(1, 0) - r(0, 1)) / s;
    } else if (r(0, 0) > r(1, 1) && r(0, 0) > r(2, 2)) {
        const double s = 2 * std::sqrt(1 + r(0, 0) - r(1, 1) - r(2, 2));
        q[3] = (r(2, 1) - r(1, 2)) / s;
        q[0] = s / 4;
        q[1] = (r(0, 1) + r(1, 0)) / s;
        q[2] = (r(0, 2) + r(2, 0)) / s;
    } else if (r(1, 1) > r(2, 2)) {
        const double s = 2 * std::sqrt(1 + r(1, 1) - r(0, 0) - r(2, 2));
        q[3] = (r(0, 2) - r(2, 0)) / s;
        q[0] = (r(0, 1) + r(1, 0)) / s;
        q[1] = s / 4;
        q[2] = (r(1, 2) + r(2, 1)) / s;
    } else {
        const double s = 2 * std::sqrt(1 + r(2, 2) - r(0, 0) - r(1, 1));
        q[3] = (r(1, 0) - r(0, 1)) / s;
        q[0] = (r(0, 2) + r(2, 0)) / s;
        q[1] = (r(1, 2) + r(2, 1)) / s;
        q[2] = s / 4;
    }
    const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    // One sign for every instance (w >= 0) keeps the stream of rotations smooth, which
    // compresses better; q and -q are the same rotation.
    const double sign = q[3] < 0 ? -1 : 1;
    return {static_cast<float>(sign * q[0] / length), static_cast<float>(sign * q[1] / length),
            static_cast<float>(sign * q[2] / length), static_cast<float>(sign * q[3] / length)};
}

}  // namespace

std::optional<Trs> decompose(const Affine3f& a) {
    double length[3];
    for (int k = 0; k < 3; ++k) {
        length[k] = std::sqrt(dot(a.columns[k], a.columns[k]));
        if (!(length[k] > 0) || !std::isfinite(length[k])) return std::nullopt;
    }
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (std::abs(dot(a.columns[i], a.columns[j])) > kOrthogonality * length[i] * length[j])
                return std::nullopt;
    if (!(a.determinant() > 0)) return std::nullopt;
    const Vec3f& t = a.columns[3];
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z)) return std::nullopt;

    double rotation[3][3];
    for (int k = 0; k < 3; ++k) {
        rotation[k][0] = a.columns[k].x / length[k];
        rotation[k][1] = a.columns[k].y / length[k];
        rotation[k][2] = a.columns[k].z / length[k];
    }
    Trs trs;
    trs.translation = {t.x, t.y, t.z};
    trs.rotation = quaternionOf(rotation);
    trs.scale = {static_cast<float>(length[0]), static_cast<float>(length[1]),
                 static_cast<float>(length[2])};
    return trs;
}

Affine3f compose(const Trs& trs) {
    const double x = trs.rotation[0], y = trs.rotation[1], z = trs.rotation[2], w = trs.rotation[3];
    // The rotation's columns, each times its scale.
    const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                            {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                            {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};
    Affine3f a;
    for (int k = 0; k < 3; ++k)
        a.columns[k] = {static_cast<float>(m[k][0] * trs.scale[k]),
                        static_cast<float>(m[k][1] * trs.scale[k]),
                        static_cast<float>(m[k][2] * trs.scale[k])};
    a.columns[3] = {trs.translation[0], trs.translation[1], trs.translation[2]};
    return a;
}

Mesh mirroredPrototype(const Mesh& prototype) {
    Mesh m = prototype;
    for (Vec3f& p : m.positions) p.z = -p.z;
    for (Vec3f& n : m.normals) n.z = -n.z;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
        std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
}

Affine3f withMirroredPrototype(const Affine3f& a) {
    Affine3f b = a;
    b.columns[2] = {-a.columns[2].x, -a.columns[2].y, -a.columns[2].z};
    return b;
}

}  // namespace graftal::instance_transform
