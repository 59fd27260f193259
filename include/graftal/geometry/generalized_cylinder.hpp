// cpfg's generalized cylinders: `@Gs` starts one at the turtle, `@Gc(n)` adds a control
// point and `@Ge(n)` adds the last one. Between two control points the centre line is a
// cubic Hermite curve whose end tangents are the turtle's headings scaled by the distance
// between the points times a tangent parameter (1.2 unless `@Gt` sets it); a cross-section
// (a contour, the circle unless `@#(id)` chose one) is swept along it in n steps, its radius
// going from half the line width at one point to half the width at the next.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "graftal/core/vec3.hpp"
#include "graftal/geometry/contour_points.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/scene.hpp"

namespace graftal {

// The turtle where a control point was set: its frame (H x L = U), its line width (a
// diameter) and what the @G, @# and @! modules had set when it was met.
struct CylinderControlPoint {
    Vec3 position;
    Vec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, 1};
    double width = 1;
    std::uint16_t color = 0;
    int contour = -1;  // index into the contour list; -1 the circle
    int sides = 8;     // points around a cross-section (@!, `contour sides:`)
    // `@Gt(a, b)`: a scales the tangent arriving at this point, b the one leaving it.
    double tangentArriving = 1.2, tangentLeaving = 1.2;
    // `@Gr(angle, length[, angle2, length2])`: the tangents (dt, dradius) of the radius
    // curve arriving at and leaving this point; zero means a straight change of radius.
    std::array<double, 2> radiusArriving{0, 0}, radiusLeaving{0, 0};
    bool scaleRadiusTangents = false;  // `@Gr(1)`: their radius parts scale with the distance
};

// One piece of a generalized cylinder: the rings swept between two control points.
struct CylinderRing {
    Vec3 centre, heading, left, up;  // the frame the cross-section is placed in
    double radius = 0.5;
    double blend = 0;  // how far the cross-section has turned from the first contour to the second
};

// The centre line's point between control points a and b at curve parameter t in [0, 1].
Vec3 hermiteCentre(const CylinderControlPoint& a, const CylinderControlPoint& b, double t);

// The up vector `up` of a frame with heading `from` carried to heading `to` by the smallest
// rotation between them (no twist about the heading), as cpfg keeps cylinders untwisted.
Vec3 carryUp(const Vec3& up, const Vec3& from, const Vec3& to);

// The rings of the piece from a to b in `steps` steps (at least 1): ring 0 is a's, the last
// b's. b's frame must already be carried from a's (carryUp). Empty when the points coincide
// (cpfg draws nothing then). The centre line is the Hermite curve above, or, given
// `bspline` (four control positions of a B-spline centre line, cpfg's `{(3)` and `{(4)`),
// that uniform cubic B-spline's span, which runs from a to b when a and b are placed by
// bsplineEnds().
std::vector<CylinderRing> cylinderRings(const CylinderControlPoint& a,
                                        const CylinderControlPoint& b, int steps,
                                        const std::array<Vec3, 4>* bspline = nullptr);

// The point of the uniform cubic B-spline span of p0..p3 at t in [0, 1], and its slope.
Vec3 bsplinePoint(const std::array<Vec3, 4>& p, double t);
Vec3 bsplineSlope(const std::array<Vec3, 4>& p, double t);

// The swept surface of those rings: each ring's cross-section (the two contours blended)
// placed across the centre line. `first` and `second` are the contour points of a and b
// (contourPoints() or circleContourPoints(), the same number of points each).
SweptTube sweepRings(const std::vector<CylinderRing>& rings, const std::vector<Vec3>& first,
                     const std::vector<Vec3>& second, bool closed, std::uint16_t color);

// The triangles of the scene's generalized cylinders, appended to `mesh` (counter-clockwise
// seen from outside, with smooth normals).
void appendSweptTubes(const Scene& scene, Mesh& mesh);

// The scene without its generalized cylinders' centre-line segments (what 2D pictures draw):
// the meshers draw the swept surfaces instead.
Scene withoutSweptCentreLines(const Scene& scene);

}  // namespace graftal
