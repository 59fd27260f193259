// The summarised streamed PNG (see turtle/subtree_summaries.hpp), on its own for tests.
#pragma once

#include <filesystem>

#include "graftal/output/output.hpp"
#include "graftal/turtle/subtree_summaries.hpp"

namespace graftal {

// A 2D PNG of the derivation, as renderStreamedPng draws it, but expanding only subtrees
// wider than `dotRadius` pixels; each smaller one is one stroke from its start to its end.
// The first pass finds the bounds to within `pixelTolerance` of a pixel.
void renderSummarisedPng(const Model& model, const SubtreeSummaries& summaries,
                         const RenderOptions& render, const Destination& destination,
                         double dotRadius = 0.25, double pixelTolerance = 0.02);

}  // namespace graftal
