// Subtree summaries: pictures of strings far larger than the picture's pixels.
//
// In a deterministic, context-free, non-parametric L-system the string that a module
// derives in its remaining steps is fixed, so it moves the turtle by a fixed rigid motion
// (a displacement and a turn, both relative to the turtle's frame) and never strays farther
// than a fixed radius from where it starts. Both compose from the successors' summaries, so
// every (symbol, step) pair is summarised once, bottom up. A streamed drawing then expands
// only the subtrees that are larger than a pixel and draws each smaller one as a single
// short stroke: the quadratic Koch island at n = 11 (3.4·10^10 segments) becomes about a
// million strokes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "graftal/lsystem.hpp"
#include "graftal/model.hpp"
#include "graftal/output.hpp"
#include "graftal/streaming.hpp"

namespace graftal {

// The net effect on the turtle of the string one module derives. With the frame (H, L)
// at the start: the turtle ends at start + along·H + aside·L, and its frame turns as
// rotatePair(H, L, cos, sin) turns it.
struct SubtreeMotion {
    double along = 0, aside = 0;
    double cos = 1, sin = 0;
    double radius = 0;        // no point of the subtree's path is farther from its start
    double segments = 0;      // segments drawn (F and G)
    double length = 0;        // their total length
    bool summarised = false;  // false: the subtree does something a motion cannot say
};

class SubtreeSummaries {
  public:
    // Summaries of the derivation of `lsystem` in `steps` steps. Unavailable (available()
    // false) for parameters, random choices, conditions, context, tropism or polygons, and
    // when the table (symbols x (steps + 1) motions) would take more than half of
    // `memoryLimit` bytes.
    SubtreeSummaries(const Model& model, int steps,
                     std::size_t memoryLimit = std::size_t(2) << 30);

    bool available() const { return available_; }
    int steps() const { return steps_; }
    std::span<const Symbol> axiom() const { return axiom_; }

    // What a module `symbol` of string `level` derives by the last step.
    const SubtreeMotion& motion(Symbol symbol, int level) const {
        return motions_[static_cast<std::size_t>(level) * symbolCount_ + symbol];
    }
    // False when no later step rewrites the symbol: the module reaches the last string as
    // it is.
    bool rewrittenAfter(Symbol symbol, int level) const { return lastRewrite_[symbol] > level; }
    // The successor of a module `symbol` of string `level` (itself when not rewritten).
    std::span<const Symbol> successor(Symbol symbol, int level) const;
    // Segments of the whole picture.
    double segments() const;

  private:
    SubtreeMotion leaf(Symbol symbol) const;
    SubtreeMotion fold(std::span<const Symbol> modules, int level) const;

    const LSystem& ls_;
    const ViewSettings& view_;
    bool available_ = false;
    int steps_ = 0;
    std::size_t symbolCount_ = 0;
    std::vector<Symbol> axiom_;
    std::vector<int> tableOfLevel_;  // the table that rewrites string `level` into level+1
    // Per table: successor start per symbol, and the successors flattened.
    std::vector<std::vector<std::uint32_t>> successorStart_;
    std::vector<std::vector<Symbol>> successorSymbols_;
    std::vector<int> lastRewrite_;  // per symbol: the last level whose step rewrites it
    std::vector<SubtreeMotion> motions_;
};

// A 2D PNG of the derivation, as renderStreamedPng draws it, but expanding only subtrees
// wider than `dotRadius` pixels; each smaller one is one stroke from its start to its end.
// The first pass finds the bounds to within `pixelTolerance` of a pixel.
void renderSummarisedPng(const Model& model, const SubtreeSummaries& summaries,
                         const RenderOptions& render, const std::filesystem::path& path,
                         double dotRadius = 0.25, double pixelTolerance = 0.02);

// The first pass alone: bounds, ink and segment count of the derivation, expanding only
// subtrees whose extent could still move the bounds by more than `pixelTolerance` of a
// pixel of an image of `render`'s size.
StreamedMeasure measureSummarised(const Model& model, const SubtreeSummaries& summaries,
                                  const RenderOptions& render, double pixelTolerance = 0.02);

}  // namespace graftal
