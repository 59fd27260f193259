// The generalized cylinders of a scene's segments: the private interface between buildMesh
// and the tube mesher.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal {

// Plans the tubes of a scene on construction (which consecutive segments share a joint
// ring), so that buildMesh can reserve the whole mesh before anything is emitted.
//
// Each axis (a chain of segments linked by Segment::previous) becomes one tube: a ring of
// tubeSides vertices at every joint, shared by the two segments meeting there and lying
// in the plane that bisects their directions (a mitre), and a disc cap at either end of the
// axis, or a cone when the tube narrows to a point there. The cross-section frame starts at
// the turtle's up vector and is carried along the axis by parallel transport, so a tube
// never twists. A joint that bends by more than 120 degrees, or so sharply for the stem's
// thickness that the mitre would cut through a neighbouring ring, is not shared: both
// sides are capped instead.
//
// With MeshOptions::curveRadius > 0, a segment whose radius is below it is no tube but a
// CurveSegment (appendCurves): the tubes on either side of it are capped there, and a run
// of curves along an axis shares its joints (CurveSegment::previous).
//
// Per segment, with n = tubeSides: 2n side triangles; an unshared start or end adds a ring
// and a cap centre (n + 1 vertices, n triangles); a shared joint adds n vertices once.
class TubeMesher {
  public:
    TubeMesher(const Scene& scene, const MeshOptions& options);

    std::size_t vertexCount() const { return vertexCount_; }
    std::size_t triangleCount() const { return triangleCount_; }

    std::size_t curveCount() const { return curveCount_; }

    // Appends the tubes to `mesh` (whose capacity the caller has reserved), built by up to
    // `threads` threads (0: one per core). The result is the same for any thread count:
    // each segment's vertices and triangles have their own place, counted beforehand, in
    // the scene's segment order, and each thread writes the axes that start in its share
    // of the segments straight into the mesh.
    void append(Mesh& mesh, unsigned threads = 1) const;
    // Appends the thin segments, in the scene's order.
    void appendCurves(std::vector<CurveSegment>& curves) const;

  private:
    double radius(float width) const;
    double startRadius(std::uint32_t s) const;
    bool usable(std::uint32_t s) const { return (flags_[s] & kUsable) != 0; }
    bool curve(std::uint32_t s) const { return (flags_[s] & kCurve) != 0; }
    bool joinedStart(std::uint32_t s) const { return (flags_[s] & kJoinedStart) != 0; }
    bool joinedEnd(std::uint32_t s) const { return next_[s] != kNoSegment; }
    bool canJoin(std::uint32_t p, std::uint32_t s) const;
    void plan();
    struct Output;
    void writeAxis(std::uint32_t first, const Output& out) const;

    static constexpr std::uint8_t kUsable = 1, kJoinedStart = 2, kCurve = 4;

    const Scene& scene_;
    MeshOptions options_;
    std::vector<double> cos_, sin_;        // of the ring angles
    std::vector<std::uint32_t> previous_;  // the usable segment this one continues
    std::vector<std::uint32_t> next_;      // the segment sharing this one's end ring
    std::vector<std::uint8_t> flags_;
    // Where each segment's vertices and triangles begin among the tubes'.
    std::vector<std::uint64_t> firstVertex_, firstTriangle_;
    std::size_t vertexCount_ = 0, triangleCount_ = 0, curveCount_ = 0;
};

}  // namespace graftal
