// The length of a segment's projection on the z = 0 plane, which inkLength() takes and the
// measuring sinks add up over hundreds of millions of segments.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "graftal/core/bit_cast.hpp"

namespace graftal::turtle {

// std::hypot of a segment's sides, which the ink sum needs bit for bit. The library call
// costs more than the rest of a step, but a step along an axis (nearly every step of a
// 90-degree curve) needs none: hypot(x, +-0) is |x|. Other steps repeat a few pairs of
// sides, so a direct-mapped table keyed by their exact magnitudes remembers them (hypot
// ignores the signs: C Annex F, as glibc does).
class PlanarLength {
  public:
    double operator()(double dx, double dy) {
        if ((dx == 0) | (dy == 0)) return std::fabs(dx) + std::fabs(dy);
        auto ax = bitCast<std::uint64_t>(std::fabs(dx));
        auto ay = bitCast<std::uint64_t>(std::fabs(dy));
        Entry& e = entries_[slot(ax, ay)];
        if (e.ax != ax || e.ay != ay) e = {ax, ay, std::hypot(dx, dy)};
        return e.length;
    }

    // The remembered hypot(dx, dy) of two non-zero sides, or null.
    const double* find(double dx, double dy) const {
        auto ax = bitCast<std::uint64_t>(std::fabs(dx));
        auto ay = bitCast<std::uint64_t>(std::fabs(dy));
        const Entry& e = entries_[slot(ax, ay)];
        return e.ax == ax && e.ay == ay ? &e.length : nullptr;
    }

  private:
    static std::size_t slot(std::uint64_t ax, std::uint64_t ay) {
        return static_cast<std::size_t>((ax * kMixX + ay * kMixY) >> (64 - kBits));
    }
    struct Entry {
        std::uint64_t ax = 0, ay = 0;  // the bits of |dx| and |dy|
        double length = 0;             // hypot(0, 0)
    };
    static constexpr int kBits = 10;  // 24 KiB: stays in the L1 cache
    static constexpr std::uint64_t kMixX = 0x9E3779B97F4A7C15u, kMixY = 0xC2B2AE3D27D4EB4Fu;
    std::vector<Entry> entries_ = std::vector<Entry>(std::size_t{1} << kBits);
};

// inkLength(s, baseWidth) is inkTerm(hypot of the sides, inkWeight(s.width, baseWidth)):
// the same doubles, computed the same way (the weight in float, then widened).
inline double inkWeight(float width, float baseWidth) {
    return width > 0 && baseWidth > 0 ? width / baseWidth : 0;
}
inline double inkTerm(double length, double weight) {
    return std::isfinite(length) ? length * weight : 0;
}

}  // namespace graftal::turtle
