// Growth prediction: module counts per step from the production matrix, without deriving.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "graftal/lang/lsystem.hpp"

namespace graftal {

// An unsigned integer of any size: counts of a D0L system grow exponentially and pass
// 2^64 after a few dozen steps.
class BigCount {
  public:
    BigCount() = default;
    explicit BigCount(std::uint64_t v);

    BigCount& operator+=(const BigCount& o);
    BigCount times(std::uint64_t k) const;
    friend bool operator==(const BigCount&, const BigCount&) = default;
    friend bool operator<(const BigCount& a, const BigCount& b);

    std::string toString() const;  // exact decimal
    std::size_t digits() const;    // decimal digits of toString()
    double toDouble() const;
    std::optional<std::uint64_t> toUint64() const;

  private:
    std::vector<std::uint32_t> limbs_;  // base 10^9, least significant first
};

struct GrowthPrediction {
    bool exact = false;                   // deterministic context-free: counts are exact
    bool expected = false;                // stochastic: counts are expected values
    std::string reason;                   // why nothing can be predicted (both flags false)
    std::vector<BigCount> modules;        // exact count per step 0..n (exact only)
    std::vector<double> expectedModules;  // expected count per step 0..n (exact or expected)
    // Per symbol counts at the last step (exact only), indexed by symbol id.
    std::vector<BigCount> symbolsAtEnd;
};

// Exact counts stop at this many decimal digits: past it (a million doublings would make
// numbers of 300,000 digits at every step) the prediction continues as expected values.
constexpr std::size_t kMaxExactDigits = 1000;

// Predicts module counts for steps 0..steps. Exact for deterministic context-free
// L-systems (tables follow their schedule); expected values when productions are chosen
// with constant probabilities; otherwise `reason` says why not (context, parameters,
// conditions, decomposition, cut or environment make the count depend on the string).
GrowthPrediction predictGrowth(const LSystem& lsystem, int steps);

}  // namespace graftal
