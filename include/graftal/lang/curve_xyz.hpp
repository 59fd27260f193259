// cpfg's curves for curveX(id, t), curveY(id, t), curveZ(id, t) and curveGAL(id): a curve
// drawn in vlab's curve editor, kept in a file the view file names with `curve: FILE
// [samples]` (ids count from 1 in the order of those lines). t runs along the curve's
// length: cpfg samples the curve at `samples` evenly spaced parameters (100 when the line
// gives none), measures the polyline through them, and maps t in [0, 1] (clamped) to the
// parameter at that share of the length, interpolating linearly between samples.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/vec3.hpp"

namespace graftal {

class CurveXYZ {
  public:
    // cpfg's curve kinds (the file's `type:` line; anything unknown is a B-spline).
    enum class Kind {
        BSpline,
        BSplineClosed,
        BSplineEndPoint,
        BSplinePhantom,
        Bezier,
        BezierSurface
    };

    CurveXYZ() = default;
    // `points`: the control points, each already repeated by its multiplicity.
    CurveXYZ(std::string name, Kind kind, std::vector<Vec3> points, int samples);

    const std::string& name() const { return name_; }
    Kind kind() const { return kind_; }
    // The point at share t of the curve's length (t clamped to [0, 1]).
    Vec3 atLength(double t) const;
    // The point at curve parameter u in [0, 1] (cpfg's parameterisation, not by length).
    Vec3 atParameter(double u) const;
    // The length of the sampled polyline (curveGAL).
    double length() const { return length_; }

  private:
    std::string name_;
    Kind kind_ = Kind::BSpline;
    std::vector<Vec3> points_;    // after multiplicities, closing and phantom points
    std::vector<double> shares_;  // cumulative length at each sample, 0 to 1
    double length_ = 0;
};

// Reads a curve file: lines `points: n`, `dimension: d` (or `dim:`; 2 by default), `type:
// bspline|bspline-closed|bspline-endpoint|bspline-phantom|bezier|bezier-surface`, and n
// point lines of d numbers (x y [z [multiplicity]]); `version:`, `contact:`, `end:`,
// `heading:`, `up:`, `size:`, `range:` and `//` lines are read and not used, as in cpfg. A
// `points:` line inside the points opens the sub-curve cpfg keeps for the point before it
// (read and skipped: curveX never looks at it). `samples` must be at least 2.
// Throws Error at fileName:line:column naming what was expected.
CurveXYZ parseCurveFile(std::string_view text, const std::string& fileName, int samples);

}  // namespace graftal
