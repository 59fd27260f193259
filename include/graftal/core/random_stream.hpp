// Counter-based random numbers: each draw is a pure function of (seed, step, module
// position, draw number). No generator state is carried from module to module, so the
// result is the same for any number of threads and for streamed derivations.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace graftal {

inline std::uint64_t mix64(std::uint64_t z) {
    // splitmix64's finaliser: a bijection with good avalanche.
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// The top 53 bits of `h` as a double in [0, 1).
inline double unitDouble(std::uint64_t h) {
    return static_cast<double>(h >> 11) * 0x1.0p-53;
}

inline double uniformAt(std::uint64_t seed, std::uint64_t step, std::uint64_t position,
                        std::uint64_t draw) {
    std::uint64_t h = mix64(seed + 0x9e3779b97f4a7c15ULL);
    h = mix64(h ^ (step * 0xd1b54a32d192ed03ULL));
    h = mix64(h ^ position);
    h = mix64(h ^ (draw * 0x8cb92ba72f3d8dd7ULL));
    return unitDouble(h);
}

// A standard normal deviate (Box–Muller) from two uniform numbers in [0, 1), drawn from
// `uniform` in this order. A first draw of 0 is taken as 1e-300, where the logarithm is
// finite.
template <class Uniform>
double normalDeviate(Uniform&& uniform) {
    double u1 = uniform();
    const double u2 = uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
}

}  // namespace graftal
