// A 2D PNG drawn while the derivation streams (streamed_interpretation.hpp), for strings
// too large to hold: memory stays proportional to the derivation depth and the image.
#pragma once

#include <filesystem>

#include "graftal/lang/model.hpp"
#include "graftal/output/output.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal {

// True when renderStreamedPng draws this derivation from subtree summaries: a picture with
// far more segments than pixels, whose subtrees smaller than a pixel are drawn as one
// stroke each, so that its time grows with the image rather than with the string: more
// than four segments per pixel of `picture` (at most 2e7). The summaries' table must fit in
// half of `memoryLimit` bytes. render() then draws the picture this way even when the
// string would fit in memory.
bool streamedPictureIsSummarised(const Model& model, int steps,
                                 std::size_t memoryLimit = std::size_t(2) << 30,
                                 const RenderOptions& picture = {});

// A 2D PNG of the derivation drawn while streaming (two passes: measure, then draw).
void renderStreamedPng(const Model& model, int steps, const DerivationOptions& options,
                       const RenderOptions& render, const Destination& destination);

}  // namespace graftal
