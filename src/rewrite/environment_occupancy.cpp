// The `occupancy` and `light` environments: every ?E occupies the point where the turtle
// reaches it, and learns how many others share its neighbourhood, so that crowded apices
// can stop. One hashed grid per step: O(n) for n modules, independent of thread count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <unordered_map>

#include "environment_detail.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/rewrite/environment.hpp"

namespace graftal {

namespace {

struct Cell {
    std::int64_t x = 0, y = 0, z = 0;
    friend bool operator==(const Cell&, const Cell&) = default;
};

struct CellHash {
    std::size_t operator()(const Cell& c) const {
        std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

// Turtle positions carry rounding noise (0.9999999999 for 1); without the nudge a point
// that is meant to lie on a cell boundary would fall on either side of it.
// Indices are clamped to +-2^62 (a tiny cell or a far position would overflow the cast, which
// is undefined): cells beyond that, unreachable in practice, share the outermost index.
std::int64_t cellIndex(double coordinate, double size) {
    constexpr double kLimit = 4611686018427387904.0;  // 2^62
    const double c = std::floor(coordinate / size + 1e-9);
    if (!(c > -kLimit)) return c < 0 ? -static_cast<std::int64_t>(kLimit) : 0;  // or nan
    if (c >= kLimit) return static_cast<std::int64_t>(kLimit);
    return static_cast<std::int64_t>(c);
}

Cell cellOf(const Vec3& p, double size) {
    return {cellIndex(p.x, size), cellIndex(p.y, size), cellIndex(p.z, size)};
}

class OccupancyEnvironment : public Environment {
  public:
    // radius > 0: neighbours are the modules within that distance; otherwise the modules
    // in the same cube of side `cell`.
    OccupancyEnvironment(double cell, double radius, bool light)
        : cell_(cell), radius_(radius), light_(light) {}

    std::string name() const override { return light_ ? "light" : "occupancy"; }

    void respond(int, std::span<CommunicationRequest> requests) override {
        std::vector<std::size_t> counts =
            radius_ > 0 ? countWithinRadius(requests) : countPerCell(requests);
        for (std::size_t i = 0; i < requests.size(); ++i) {
            double others = static_cast<double>(counts[i]);
            double lightValue = 1 / (1 + others);
            double answer[2] = {light_ ? lightValue : others, light_ ? others : lightValue};
            auto& p = requests[i].params;
            for (std::size_t k = 0; k < p.size() && k < 2; ++k) p[k] = answer[k];
        }
    }

  private:
    std::vector<std::size_t> countPerCell(std::span<CommunicationRequest> requests) const {
        std::unordered_map<Cell, std::size_t, CellHash> occupants;
        occupants.reserve(requests.size());
        std::vector<Cell> cells;
        cells.reserve(requests.size());
        for (const auto& r : requests) {
            cells.push_back(cellOf(r.frame.position, cell_));
            ++occupants[cells.back()];
        }
        std::vector<std::size_t> counts(requests.size());
        for (std::size_t i = 0; i < cells.size(); ++i) counts[i] = occupants[cells[i]] - 1;
        return counts;
    }

    // Buckets of side radius/2, so that a bucket's diagonal is shorter than the radius: the
    // modules sharing a bucket are all neighbours and count as a whole, and so does every
    // bucket wholly within the radius. Only the buckets the radius sphere cuts are compared
    // module by module; many modules at one point (a common case: ?E(x) --> ?E(x)?E(x))
    // stay O(n) where comparing every pair was O(n^2).
    std::vector<std::size_t> countWithinRadius(std::span<CommunicationRequest> requests) const {
        const double side = radius_ / 2;
        std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> buckets;
        buckets.reserve(requests.size());
        std::vector<Cell> cells;
        cells.reserve(requests.size());
        for (std::size_t i = 0; i < requests.size(); ++i) {
            cells.push_back(cellOf(requests[i].frame.position, side));
            buckets[cells.back()].push_back(static_cast<std::uint32_t>(i));
        }
        // Compared squared, with the same tolerance as the cells: points exactly one radius
        // apart count as neighbours.
        const double limit = radius_ * radius_ * (1 + 1e-9);
        // Bucket bounds are nudged by the cells' 1e-9 tolerance; a margin keeps the whole
        // and none tests conservative, so they agree with the module-by-module test.
        const double margin = side * 1e-6;
        std::vector<std::size_t> counts(requests.size(), 0);
        for (const auto& [cell, members] : buckets) {
            for (std::int64_t dx = -2; dx <= 2; ++dx)
                for (std::int64_t dy = -2; dy <= 2; ++dy)
                    for (std::int64_t dz = -2; dz <= 2; ++dz) {
                        auto it = buckets.find({cell.x + dx, cell.y + dy, cell.z + dz});
                        if (it == buckets.end()) continue;
                        const auto& others = it->second;
                        double nearest = 0, farthest = 0;
                        for (std::int64_t d : {dx, dy, dz}) {
                            const double gap = std::max(
                                0.0, (static_cast<double>(std::abs(d)) - 1) * side - margin);
                            const double span =
                                (static_cast<double>(std::abs(d)) + 1) * side + margin;
                            nearest += gap * gap;
                            farthest += span * span;
                        }
                        if (nearest > limit) continue;
                        const bool self = dx == 0 && dy == 0 && dz == 0;
                        if (self || farthest <= radius_ * radius_) {
                            // All neighbours (within a bucket: side * sqrt(3) < radius).
                            for (std::uint32_t i : members)
                                counts[i] += others.size() - (self ? 1 : 0);
                            continue;
                        }
                        for (std::uint32_t i : members) {
                            const Vec3& p = requests[i].frame.position;
                            for (std::uint32_t j : others) {
                                const Vec3& q = requests[j].frame.position;
                                double ex = p.x - q.x, ey = p.y - q.y, ez = p.z - q.z;
                                if (ex * ex + ey * ey + ez * ez <= limit) ++counts[i];
                            }
                        }
                    }
        }
        return counts;
    }

    double cell_ = 1, radius_ = 0;
    bool light_ = false;
};

}  // namespace

std::unique_ptr<Environment> environment_detail::makeOccupancyEnvironment(const LSystem& lsystem,
                                                                          bool light) {
    double cell = 1, radius = 0;
    std::optional<EnvironmentLine> sizeWord;  // the `cell` or `radius` already given
    for (std::size_t i = 0; i < lsystem.environment.size(); ++i) {
        const EnvironmentLine& line = lsystem.environment[i];
        auto words = splitWords(line);
        for (std::size_t k = i == 0 ? 1 : 0; k < words.size(); ++k) {
            const EnvironmentLine& word = words[k];
            if (word.text != "cell" && word.text != "radius")
                throw Error(word.location, "expected 'cell SIZE' or 'radius R' for the " +
                                               std::string(light ? "light" : "occupancy") +
                                               " environment, found '" + word.text + "'");
            if (sizeWord)
                throw Error(word.location,
                            "the neighbourhood is already given by '" + sizeWord->text + "' at " +
                                sizeWord->location.toString() + "; give either 'cell' or 'radius'");
            if (k + 1 >= words.size())
                throw Error(endOfLine(line), "expected a size (a number) after '" + word.text +
                                                 "' before the end of the line");
            const EnvironmentLine& value = words[++k];
            double v = numberWord(value, "the " + word.text + " size", lsystem);
            if (v <= 0) throw Error(value.location, "the " + word.text + " size must be > 0");
            (word.text == "cell" ? cell : radius) = v;
            sizeWord = word;
        }
    }
    return std::make_unique<OccupancyEnvironment>(cell, radius, light);
}

}  // namespace graftal
