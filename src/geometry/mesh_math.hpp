// Vector arithmetic for the mesher. A type of its own rather than operators on the public
// Vec3: the public header stays a plain value type, and nothing here can collide with
// operators another part of graftal might give Vec3.
#pragma once

#include <cmath>

#include "graftal/mesh.hpp"
#include "graftal/scene.hpp"

namespace graftal::meshing {

struct Vector3 {
    double x = 0, y = 0, z = 0;

    Vector3() = default;
    constexpr Vector3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    explicit Vector3(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}

    Vec3 toVec3() const { return {x, y, z}; }
    Vec3f toVec3f() const {
        return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
    }
};

inline Vector3 operator+(const Vector3& a, const Vector3& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vector3 operator-(const Vector3& a, const Vector3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vector3 operator-(const Vector3& a) {
    return {-a.x, -a.y, -a.z};
}
inline Vector3 operator*(double k, const Vector3& a) {
    return {k * a.x, k * a.y, k * a.z};
}
inline double dot(const Vector3& a, const Vector3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vector3 cross(const Vector3& a, const Vector3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vector3& a) {
    return std::sqrt(dot(a, a));
}
inline bool isFinite(const Vector3& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// The unit vector along `a`, or `fallback` when `a` has no usable direction.
inline Vector3 normalizedOr(const Vector3& a, const Vector3& fallback) {
    const double l = length(a);
    if (!(l > 1e-300) || !std::isfinite(l)) return fallback;
    return (1.0 / l) * a;
}

// A unit vector perpendicular to the unit vector `d`.
inline Vector3 anyPerpendicular(const Vector3& d) {
    // Crossing with the axis least aligned with d keeps the result well conditioned.
    const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
    const Vector3 axis = ax <= ay && ax <= az ? Vector3{1, 0, 0}
                         : ay <= az           ? Vector3{0, 1, 0}
                                              : Vector3{0, 0, 1};
    return normalizedOr(cross(d, axis), Vector3{1, 0, 0});
}

// The unit part of `v` perpendicular to the unit vector `d`, or any perpendicular when `v`
// is (nearly) parallel to d.
inline Vector3 perpendicularPart(const Vector3& v, const Vector3& d) {
    const Vector3 p = v - dot(v, d) * d;
    if (length(p) <= 1e-9 * length(v)) return anyPerpendicular(d);
    return normalizedOr(p, anyPerpendicular(d));
}

}  // namespace graftal::meshing
