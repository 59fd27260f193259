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
#include <span>
#include <vector>

#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/rewrite/streaming.hpp"
#include "graftal/turtle/streamed_interpretation.hpp"

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
    SubtreeSummaries(const Model& model, int steps, std::size_t memoryLimit = std::size_t(2) << 30);

    bool available() const { return available_; }
    int steps() const { return steps_; }
    std::size_t symbolCount() const { return symbolCount_; }
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

// The first pass of a summarised picture: bounds, ink and segment count of the
// derivation, expanding only subtrees whose extent could still move the bounds by more
// than `pixelTolerance` of a pixel of an image whose larger side is `imageSide` pixels.
StreamedMeasure measureSummarised(const Model& model, const SubtreeSummaries& summaries,
                                  int imageSide, double pixelTolerance = 0.02);

// The second pass: walks the derivation as drawStreamed does, but expands only subtrees
// whose radius times `scale` (pixels per model unit) exceeds `dotRadius`; each smaller one
// goes to `drawing` as one segment from its start to its end.
void drawSummarised(const Model& model, const SubtreeSummaries& summaries, double scale,
                    double dotRadius, StreamedDrawing& drawing);

// How many segments drawSummarised would hand over with these `scale` and `dotRadius`
// (at most; segments the turtle skips, such as zero widths, are counted), from the
// summaries alone: one sum per (symbol, string), not a walk of the derivation.
double summarisedStrokeCount(const SubtreeSummaries& summaries, double scale, double dotRadius);

// The smallest dot radius from `dotRadius` up (in steps of a quarter) at which
// drawSummarised hands over at most `strokeBudget` segments, but no more than
// `largestDotRadius`: a path that covers its picture many times over (a curve of dimension
// 2) would otherwise give many strokes per pixel, each darkening pixels already drawn.
double dotRadiusWithin(const SubtreeSummaries& summaries, double scale, double dotRadius,
                       double strokeBudget, double largestDotRadius);

}  // namespace graftal
