// Uniform cubic B-spline smoothing of turtle paths: the consecutive positions of the turtle
// used as control points of a smooth curve (the book's Figures 2.10 and 2.11).
#pragma once

#include <span>
#include <vector>

#include "graftal/geometry/scene.hpp"

namespace graftal {

// How a chain that ends where it starts (a closed outline such as a Koch island) is smoothed.
enum class ClosedChains {
    Clamped,   // like an open chain: the curve passes through the closing point, a corner there
    Periodic,  // one closed B-spline, smooth all round; it no longer touches the closing point
};

// Points of the uniform cubic B-spline with the given control points, `subdivisions` straight
// pieces per span (at least 1).
//
// Open (the default): the ends are clamped with the phantom points 2 P0 - P1 and
// 2 Pn - Pn-1, so the curve starts exactly at the first control point and ends exactly at
// the last, tangent to the control polygon there, and stays in the convex hull of the
// control points. n + 1 control points give n spans: n * subdivisions + 1 points.
//
// Closed: the control points are a loop (the first is not repeated at the end); n of them
// give n spans and n * subdivisions + 1 points, the last equal to the first. Fewer than
// three control points are treated as open.
std::vector<Vec3> bsplineCurve(std::span<const Vec3> controlPoints, int subdivisions,
                               bool closed = false);

// Replaces every chain of consecutive segments by the B-spline curve of the chain's points,
// each segment becoming `subdivisions` segments (so a chain of n segments becomes
// n * subdivisions). The pieces of a segment keep its width, colour and up vector;
// polygons, surfaces and the palette are copied unchanged. Throws Error when subdivisions
// is below 1 or the result would not fit the 32-bit segment indices.
//
// A segment continues the one named by its `previous` (3D axes); a segment without one
// continues the latest earlier segment that ends exactly where it starts (2D paths). Where
// several segments continue the same one (a branch point), the last of them in drawing
// order — the module after the brackets — carries the chain on, and every other starts a
// chain of its own whose first point is pinned to the point the smoothed parent passes
// there, so branches stay attached. Chain ends are clamped (see bsplineCurve), so every
// path starts and ends where the turtle's did.
//
// Each piece's `previous` is the piece before it; the first piece of a segment continues
// the last piece of the segment's original `previous`.
Scene smoothSegments(const Scene& scene, int subdivisions,
                     ClosedChains closed = ClosedChains::Clamped);

}  // namespace graftal
