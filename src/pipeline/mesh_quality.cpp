// --quality: named mesh resolutions. Medium is what graftal always drew; low halves the
// triangles of a big plant for a quick look, high rounds stems seen close up.
#include <charconv>
#include <optional>
#include <string_view>

#include "graftal/pipeline/pipeline.hpp"

namespace graftal {

std::optional<MeshResolution> meshResolutionFor(std::string_view quality) {
    if (quality == "low") return MeshResolution{5, 4};
    if (quality == "medium") return MeshResolution{8, 8};
    if (quality == "high") return MeshResolution{16, 16};
    int n = 0;
    const auto [end, error] = std::from_chars(quality.data(), quality.data() + quality.size(), n);
    if (error != std::errc{} || end != quality.data() + quality.size() || n < 3 || n > 64)
        return std::nullopt;
    return MeshResolution{n, n};
}

}  // namespace graftal
