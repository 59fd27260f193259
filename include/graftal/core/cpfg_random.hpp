// cpfg's random numbers, drawn exactly as cpfg draws them, so that a cpfg model gives the
// string cpfg gives. They come from POSIX's 48-bit linear congruential generator (the
// drand48 family: X' = (0x5DEECE66D X + 0xB) mod 2^48, a draw being X' / 2^48) on two states:
// - the productions' state (cpfg's drand48()): one draw for every module a stochastic
//   L-system rewrites; it starts where the C library starts (X = 0), as in cpfg's batch
//   run, or, given a seed s other than 0, as seed48({s, 0, 155}) sets it (cpfg's
//   interactive run with `seed: s`);
// - the functions' state (cpfg's erand48 on its own state): ran, nran, bran and biran draw
//   from it; srand(s) sets it to {0x330E, low 16 bits of s, high 16 bits}, and it starts as
//   srand(0) would leave it.
// The distributions are cpfg's own: nran is the polar method in pairs (its first call before
// any srand() gives the mean, as cpfg's does), bran the rejection method cpfg uses, biran
// counts draws <= p. graftal's own streams (random_stream.hpp) give the same string for any
// thread count; these are sequential by nature, so a derivation that uses them runs on one
// thread in the string's order.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace graftal {

class Rand48 {
  public:
    static constexpr std::uint64_t kMask = (std::uint64_t{1} << 48) - 1;

    constexpr Rand48() = default;
    // The state from its three 16-bit words, low word first (as seed48 and erand48 take it).
    constexpr Rand48(std::uint16_t x0, std::uint16_t x1, std::uint16_t x2)
        : x_(std::uint64_t{x0} | std::uint64_t{x1} << 16 | std::uint64_t{x2} << 32) {}

    // The next number in [0, 1): the new state over 2^48, exactly.
    double next() {
        x_ = (0x5DEECE66DULL * x_ + 0xB) & kMask;
        return std::ldexp(static_cast<double>(x_), -48);
    }
    std::uint64_t state() const { return x_; }

  private:
    std::uint64_t x_ = 0;
};

class CpfgRandom {
  public:
    // `seed`: 0 for the C library's initial state, else seed48's {seed, 0, 155}.
    explicit CpfgRandom(long seed = 0) {
        if (static_cast<int>(seed) != 0)
            productions_ = Rand48(static_cast<std::uint16_t>(seed), 0, 155);
    }

    // The number a stochastic L-system draws at a module.
    double production() { return productions_.next(); }

    void srand(double value) {
        const long a = std::fabs(value) < 9e18 ? static_cast<long>(value) : 0;
        functions_ = Rand48(0x330E, static_cast<std::uint16_t>(a & 0xFFFF),
                            static_cast<std::uint16_t>((a >> 16) & 0xFFFF));
        haveSpare_ = false;
    }
    double uniform() { return functions_.next(); }
    double ran(double max) { return uniform() * max; }

    double nran(double mean, double deviation) {
        if (haveSpare_) {
            haveSpare_ = false;
            return spare_ * deviation + mean;
        }
        double v1, v2, rsq;
        do {
            v1 = 2.0 * uniform() - 1.0;
            v2 = 2.0 * uniform() - 1.0;
            rsq = v1 * v1 + v2 * v2;
        } while (rsq >= 1.0 || rsq == 0.0);
        const double fac = std::sqrt(-2.0 * std::log(rsq) / rsq);
        spare_ = v1 * fac;
        haveSpare_ = true;
        return v2 * fac * deviation + mean;
    }

    // Beta-distributed in (0, 1) (Cheng's rejection method, as cpfg computes it).
    double bran(double a, double b) {
        const double s = a + b;
        const double lambda =
            std::min(a, b) <= 1 ? std::min(a, b) : std::sqrt((2 * a * b - s) / (s - 2));
        const double u = a + lambda;
        double u1, u2, v, y;
        do {
            do u1 = uniform();
            while (u1 == 0);
            do u2 = uniform();
            while (u2 == 0);
            v = (1 / lambda) * std::log(u1 / (1 - u1));
            y = a * std::exp(v);
        } while (s * std::log(s / (b + y)) + u * v - std::log(4.0) < std::log(u1 * u1 * u2));
        return y / (b + y);
    }

    double biran(double n, double p) {
        const int count = static_cast<int>(n);
        int hits = 0;
        for (int i = 1; i <= count; ++i) hits += uniform() <= p ? 1 : 0;
        return hits;
    }

  private:
    Rand48 productions_;
    Rand48 functions_{0x330E, 0, 0};
    // cpfg's nran keeps the second number of each pair; before the first srand() it acts
    // as if a pair were waiting, with 0 as its second number.
    bool haveSpare_ = true;
    double spare_ = 0;
};

}  // namespace graftal
