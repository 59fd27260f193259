// cpfg's graphical functions: `func(id, x)` reads a curve y(x) drawn in vlab's function
// editor. A function is a cubic B-spline over control points (x, y) with clamped uniform
// knots, read from a `.func` file (one function) or a `.fset` file (a set of them); the
// view file names them with `function:` and `function set:` lines.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace graftal {

class GraphicalFunction {
  public:
    struct Point {
        double x = 0, y = 0;
    };

    GraphicalFunction() = default;
    // `samples` > 2: the curve is evaluated at `samples` evenly spaced x once and read by
    // linear interpolation afterwards, as cpfg does; otherwise every call searches the curve.
    GraphicalFunction(std::string name, std::vector<Point> points, int samples);

    const std::string& name() const { return name_; }
    const std::vector<Point>& points() const { return points_; }
    int samples() const { return static_cast<int>(table_.size()); }

    // y at `x`, with x clamped to [0, 1]. cpfg's method: the curve parameter t is bisected
    // in [0, 1] from 0.5 until |x(t) - x| <= 0.001, and y(t) is returned.
    double value(double x) const;

    // The curve's point at parameter t in [0, 1) (t = 1 gives the origin, as in cpfg,
    // whose basis functions are zero there).
    Point at(double t) const;

  private:
    double search(double x) const;

    std::string name_;
    std::vector<Point> points_;
    std::vector<double> table_;  // precomputed values, empty when not sampled
};

// The functions of a `.func` file: `fver 1 1` with name:, samples:, flip:, points: and
// lines `x y [repeat]`, or the old format `range: lo hi`, points:, lines `x y`, whose
// number of samples comes from the view file's `function:` line (`oldFormatSamples`).
// Throws Error naming `fileName`:line on malformed text.
GraphicalFunction parseFunctionFile(std::string_view text, const std::string& fileName,
                                    int oldFormatSamples = 0);

// A `.fset` file: `funcgalleryver 1 1`, `items: k`, then k `fver 1 1` functions.
std::vector<GraphicalFunction> parseFunctionSet(std::string_view text, const std::string& fileName);

}  // namespace graftal
