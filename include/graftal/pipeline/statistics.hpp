// A model's statistics as `graftal stats` reports them: the derived string's module and
// symbol counts and, when asked, what the turtle draws of it (segments, polygons and the
// bounding box), measured without keeping any geometry. The pipeline decides how: a string
// too large to hold is measured while it streams; counts alone skip writing the last step.
#pragma once

#include <cstdint>
#include <vector>

#include "graftal/geometry/scene.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/pipeline/pipeline.hpp"

namespace graftal {

struct ModelStatistics {
    int steps = 0;
    std::uint64_t modules = 0;
    std::vector<std::uint64_t> symbolCounts;  // indexed by symbol id
    bool measured = false;                    // the geometry below was measured
    std::uint64_t segments = 0, polygons = 0;
    // The drawing's box; for a cpfg file, cpfg's view volume (the box line of its output).
    Bounds bounds;
    bool streamed = false;  // measured while the derivation streamed
};

// Derives the model for the request and counts (and with `geometry`, measures the
// drawing). Throws Error (Cancelled when request.cancel is raised).
ModelStatistics measured(const Model& model, const DeriveRequest& request, bool geometry);

}  // namespace graftal
