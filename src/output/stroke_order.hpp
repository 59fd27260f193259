// The order in which the 2D writers stroke segments (shared so that SVG, PNG and PDF
// pictures look alike).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "graftal/geometry/scene.hpp"
#include "graftal/output/output.hpp"

namespace graftal {

// The order in which segments are stroked. Within a stretch of segments of one colour the
// order cannot be seen (an opaque colour over itself gives the same pixels in any order),
// so such a stretch is sorted by width, stably. A plant whose width changes at every
// branch (DFS order alternates widths) then costs a few dozen strokes instead of one per
// segment. Across colours, scene order is kept: there it decides which line is on top.
inline std::vector<std::uint32_t> strokeOrder(const Scene& scene, const RenderOptions& o) {
    const auto& segs = scene.segments;
    std::vector<std::uint32_t> order(segs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    auto colorOf = [&](std::uint32_t i) {
        return o.lineColor ? *o.lineColor : scene.colorOf(segs[i].color);
    };
    std::size_t begin = 0;
    while (begin < order.size()) {
        const Rgb color = colorOf(order[begin]);
        bool mixedWidths = false;
        std::size_t end = begin + 1;
        for (; end < order.size() && colorOf(order[end]) == color; ++end)
            mixedWidths = mixedWidths || segs[order[end]].width != segs[order[begin]].width;
        if (mixedWidths)
            std::stable_sort(
                order.begin() + static_cast<std::ptrdiff_t>(begin),
                order.begin() + static_cast<std::ptrdiff_t>(end),
                [&](std::uint32_t a, std::uint32_t b) { return segs[a].width < segs[b].width; });
        begin = end;
    }
    return order;
}

}  // namespace graftal
