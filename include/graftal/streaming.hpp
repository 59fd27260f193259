// Streamed derivation: the final string expanded depth-first, module by module, straight
// into a consumer (usually the turtle), with memory proportional to the derivation depth.
// For L-systems without context; the result is the same string, in the same order, with
// the same random choices as a materialised derivation.
#pragma once

#include <span>
#include <string>

#include "graftal/derivation.hpp"

namespace graftal {

class ModuleSink {
  public:
    virtual ~ModuleSink() = default;
    virtual void module(Symbol symbol, std::span<const double> params) = 0;
};

// Empty when `lsystem` can be streamed; otherwise what prevents it (context, cut,
// decomposition, query modules or an environment, homomorphism).
std::string streamingObstacle(const LSystem& lsystem);

// Calls sink.module() for every module of the string derived in `steps` steps, in order.
// Throws Error when the L-system cannot be streamed.
void streamDerivation(const LSystem& lsystem, int steps, ModuleSink& sink,
                      const DerivationOptions& options = {});

}  // namespace graftal

#include <filesystem>
#include <vector>

#include "graftal/model.hpp"
#include "graftal/output.hpp"
#include "graftal/scene.hpp"

namespace graftal {

// What a streamed pass learns without keeping the string or the geometry.
struct StreamedMeasure {
    std::uint64_t modules = 0;
    std::vector<std::uint64_t> symbolCounts;  // indexed by symbol id
    std::uint64_t segments = 0, polygons = 0;
    Bounds bounds;   // of segment ends and polygon vertices
    double ink = 0;  // sum of inkLength() over the segments
    float baseWidth = 1;
    bool is3D = false;
};

// Derives depth-first and walks the turtle over the modules as they come (when
// `geometry`), keeping only counts and bounds.
StreamedMeasure measureStreamed(const Model& model, int steps,
                                const DerivationOptions& options = {}, bool geometry = true);

// The same counts and bounds for a string already derived, walking the turtle without
// storing any geometry (what `graftal stats` needs, at any size).
StreamedMeasure measureModules(const Model& model, const ModuleString& modules);

// The Scene interpret(derive(...)) would give, built from a streamed derivation.
Scene interpretStreamed(const Model& model, int steps, const DerivationOptions& options = {});

// True when renderStreamedPng draws this derivation from subtree summaries: a picture with
// far more segments than pixels, whose subtrees smaller than a pixel are drawn as one
// stroke each, so that its time grows with the image rather than with the string. The
// summaries' table must fit in half of `memoryLimit` bytes.
bool streamedPictureIsSummarised(const Model& model, int steps,
                                 std::size_t memoryLimit = std::size_t(2) << 30);

// A 2D PNG of the derivation drawn while streaming (two passes: measure, then draw);
// memory stays proportional to the derivation depth and the image.
void renderStreamedPng(const Model& model, int steps, const DerivationOptions& options,
                       const RenderOptions& render, const std::filesystem::path& path);

}  // namespace graftal
