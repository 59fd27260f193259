// The one 3D vector of graftal, with its arithmetic: the turtle, the meshes, the writers
// and the ray tracer all compute with it. Angles are given in degrees and turned into
// radians by radians().
#pragma once

#include <cmath>
#include <numbers>
#include <ostream>

namespace graftal {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    friend bool operator==(const Vec3&, const Vec3&) = default;
};

// "(x, y, z)", with -0 printed as 0.
std::ostream& operator<<(std::ostream& os, const Vec3& v);

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator-(const Vec3& a) {
    return {-a.x, -a.y, -a.z};
}
inline Vec3 operator*(const Vec3& a, double k) {
    return {a.x * k, a.y * k, a.z * k};
}
inline Vec3 operator*(double k, const Vec3& a) {
    return a * k;
}
inline double dot(const Vec3& a, const Vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) {
    return std::sqrt(dot(a, a));
}
inline bool isFinite(const Vec3& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// The unit vector along `a`; a zero vector stays zero.
inline Vec3 normalized(const Vec3& a) {
    double n = length(a);
    return n > 0 ? a * (1 / n) : a;
}

// The unit vector along `a`; the zero vector when `a` has no length or is not a number.
inline Vec3 unitOrZero(const Vec3& a) {
    const double n = length(a);
    return n > 0 ? a * (1 / n) : Vec3{};
}

// The unit vector along `a`, or `fallback` when `a` has no usable direction (a length
// that is tiny, infinite or not a number).
inline Vec3 normalizedOr(const Vec3& a, const Vec3& fallback) {
    const double l = length(a);
    if (!(l > 1e-300) || !std::isfinite(l)) return fallback;
    return (1.0 / l) * a;
}

// A unit vector perpendicular to the unit vector `d`.
inline Vec3 anyPerpendicular(const Vec3& d) {
    // Crossing with the axis least aligned with d keeps the result well conditioned.
    const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
    const Vec3 axis = ax <= ay && ax <= az ? Vec3{1, 0, 0}
                      : ay <= az           ? Vec3{0, 1, 0}
                                           : Vec3{0, 0, 1};
    return normalizedOr(cross(d, axis), Vec3{1, 0, 0});
}

// The unit part of `v` perpendicular to the unit vector `d`, or any perpendicular when `v`
// is (nearly) parallel to d.
inline Vec3 perpendicularPart(const Vec3& v, const Vec3& d) {
    const Vec3 p = v - dot(v, d) * d;
    if (length(p) <= 1e-9 * length(v)) return anyPerpendicular(d);
    return normalizedOr(p, anyPerpendicular(d));
}

// An angle in degrees in radians, computed as degrees * π / 180 in that order: every turn
// graftal makes has always been computed so, and the pictures must not move in their last
// bit.
inline double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

// Where the turtle is when it reaches a module, and which way it faces (H x L = U).
struct TurtleFrame {
    Vec3 position;
    Vec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, 1};
};

}  // namespace graftal
