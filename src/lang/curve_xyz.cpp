// cpfg's curves (see graftal/curve_xyz.hpp). The parameterisations follow cpfg's curve code
// so that curveX/Y/Z give cpfg's numbers: a uniform cubic B-spline evaluated on the knot
// interval 3 + u (n - 3.000001), the end-point B-spline on clamped knots, and Bézier
// segments of four points each; t is turned into u through a table of sampled lengths.
#include "graftal/lang/curve_xyz.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

namespace {

constexpr int kMaxPoints = 100000;
constexpr int kMaxSamples = 1000000;
constexpr int kMaxMultiplicity = 1000;
constexpr int kMaxNesting = 20;  // cpfg keeps 20 levels of sub-curves

// The uniform cubic B-spline basis on knots i, i+1, ..., i+4, by Cox–de Boor from order 1
// (half-open intervals), as cpfg computes it.
double uniformBasis(int i, double t, int order) {
    if (order == 1) return i <= t && t < i + 1 ? 1.0 : 0.0;
    const int k = order - 1;
    return (t - i) / k * uniformBasis(i, t, order - 1) +
           (i + order - t) / k * uniformBasis(i + 1, t, order - 1);
}

// The cubic basis on cpfg's clamped knots for `size` points: 0 four times, 1, 2, ..., and
// size - 3 four times; zero-width intervals contribute nothing.
double clampedKnot(int k, int size) {
    if (k < 4) return 0.0;
    if (k > size - 1) return size - 3.0;
    return k - 3.0;
}

double clampedBasis(int k, double u, int order, int size) {
    if (order == 1) return clampedKnot(k, size) <= u && u < clampedKnot(k + 1, size) ? 1.0 : 0.0;
    double sum = 0;
    const double left = clampedKnot(k + order - 1, size) - clampedKnot(k, size);
    if (left != 0) sum += (u - clampedKnot(k, size)) / left * clampedBasis(k, u, order - 1, size);
    const double right = clampedKnot(k + order, size) - clampedKnot(k + 1, size);
    if (right != 0)
        sum += (clampedKnot(k + order, size) - u) / right * clampedBasis(k + 1, u, order - 1, size);
    return sum;
}

struct Line {
    std::string_view text;
    int number = 0;
};

[[noreturn]] void fail(const std::string& file, int line, int column, const std::string& msg) {
    throw Error(SourceLocation{file, std::max(line, 1), std::max(column, 1)}, msg);
}

// The white-space separated words of `s` with their 1-based columns.
std::vector<std::pair<std::string_view, int>> words(std::string_view s) {
    std::vector<std::pair<std::string_view, int>> out;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
        std::size_t b = i;
        while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != '\r') ++i;
        if (i > b) out.emplace_back(s.substr(b, i - b), static_cast<int>(b) + 1);
    }
    return out;
}

double parseNumber(const std::string& file, const Line& line, std::string_view word, int column,
                   const std::string& what) {
    std::string w(word);
    char* stop = nullptr;
    double d = std::strtod(w.c_str(), &stop);
    if (stop == w.c_str() || *stop || !std::isfinite(d))
        fail(file, line.number, column, "expected " + what + ", found '" + w + "'");
    return d;
}

int wholeNumber(const std::string& file, const Line& line, std::string_view word, int column,
                const std::string& what, int least, int most) {
    double d = parseNumber(file, line, word, column, what);
    if (d != std::floor(d) || d < least || d > most)
        fail(file, line.number, column,
             what + " must be a whole number from " + std::to_string(least) + " to " +
                 std::to_string(most) + ", not '" + std::string(word) + "'");
    return static_cast<int>(d);
}

CurveXYZ::Kind kindNamed(std::string_view word) {
    using K = CurveXYZ::Kind;
    if (word == "bezier-surface") return K::BezierSurface;
    if (word == "bezier") return K::Bezier;
    if (word == "bspline-phantom") return K::BSplinePhantom;
    if (word == "bspline-endpoint") return K::BSplineEndPoint;
    if (word == "bspline-closed") return K::BSplineClosed;
    return K::BSpline;  // cpfg: anything else
}

}  // namespace

CurveXYZ::CurveXYZ(std::string name, Kind kind, std::vector<Vec3> points, int samples)
    : name_(std::move(name)), kind_(kind) {
    // cpfg's evaluation points: the closed B-spline repeats its first three points, the
    // phantom one adds a point mirrored through each end, and a Bézier surface is read, for
    // curveX, along its first row of four points.
    if (kind == Kind::BSplineClosed && points.size() >= 3)
        for (int i = 0; i < 3; ++i) points.push_back(points[static_cast<std::size_t>(i)]);
    if (kind == Kind::BSplinePhantom && points.size() >= 2) {
        const std::size_t n = points.size();
        Vec3 first = 2.0 * points[0] - points[1];
        Vec3 last = 2.0 * points[n - 1] - points[n - 2];
        points.insert(points.begin(), first);
        points.push_back(last);
    }
    if (kind == Kind::BezierSurface) {
        if (points.size() >= 16)
            points.resize(4);
        else
            points.clear();
    }
    points_ = std::move(points);
    samples = std::max(samples, 2);
    std::vector<double> cumulative(static_cast<std::size_t>(samples), 0.0);
    Vec3 previous;
    for (int i = 0; i < samples; ++i) {
        Vec3 p = atParameter(static_cast<double>(i) / (samples - 1));
        if (i > 0) length_ += graftal::length(p - previous);
        cumulative[static_cast<std::size_t>(i)] = length_;
        previous = p;
    }
    shares_.resize(cumulative.size());
    for (std::size_t i = 0; i < cumulative.size(); ++i)
        // A curve of no length (cpfg divides by zero there) is read by its parameter.
        shares_[i] = length_ > 0 ? cumulative[i] / length_
                                 : static_cast<double>(i) / static_cast<double>(samples - 1);
}

Vec3 CurveXYZ::atParameter(double u) const {
    const int n = static_cast<int>(points_.size());
    Vec3 p;
    if (n <= 3) return p;  // cpfg draws nothing from fewer than four points
    switch (kind_) {
        case Kind::Bezier:
        case Kind::BezierSurface: {
            const int segments = 1 + (n - 4) / 3;
            const int c = static_cast<int>(u / (1.000001 / segments));
            const double t = (u - c * (1.0 / segments)) * segments / 1.000001;
            for (int j = 0; j < 4; ++j)
                p = p + points_[static_cast<std::size_t>(3 * c + j)] * clampedBasis(j, t, 4, 4);
            return p;
        }
        case Kind::BSplineEndPoint: {
            const double t = u * (n - 3.000001);
            for (int k = 0; k < n; ++k)
                p = p + points_[static_cast<std::size_t>(k)] * clampedBasis(k, t, 4, n);
            return p;
        }
        default: {
            const int i = 3 + static_cast<int>(u * (n - 3.000001));
            const double t = 3.0 + u * (n - 3.000001);
            for (int k = i - 3; k <= i; ++k)
                p = p + points_[static_cast<std::size_t>(k)] * uniformBasis(k, t, 4);
            return p;
        }
    }
}

Vec3 CurveXYZ::atLength(double t) const {
    if (!(t >= 0)) t = 0;  // also NaN
    if (t > 1) t = 1;
    const int samples = static_cast<int>(shares_.size());
    int low = 0, high = samples - 1;
    while (high - low > 1) {
        int mid = (low + high) / 2;
        if (shares_[static_cast<std::size_t>(mid)] > t)
            high = mid;
        else
            low = mid;
    }
    const double a = shares_[static_cast<std::size_t>(low)];
    const double b = shares_[static_cast<std::size_t>(high)];
    const double within = b > a ? (t - a) / (b - a) : 0.0;
    return atParameter((low + within) / (samples - 1));
}

CurveXYZ parseCurveFile(std::string_view text, const std::string& file, int samples) {
    if (samples < 2 || samples > kMaxSamples)
        throw Error(SourceLocation{file, 0, 0},
                    "a curve needs at least 2 samples (cpfg takes 100 when the view file "
                    "gives none), not " +
                        std::to_string(samples));
    struct Level {
        int size = 0, filled = 0, dimension = 2;
        CurveXYZ::Kind kind = CurveXYZ::Kind::BSpline;
    };
    std::vector<Level> levels;
    std::vector<Vec3> points;
    int lastLine = 0;
    std::size_t start = 0;
    for (int number = 1; start < text.size(); ++number) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        Line line{text.substr(start, end - start), number};
        start = end + 1;
        auto w = words(line.text);
        if (w.empty()) continue;
        lastLine = number;
        const std::string_view key = w[0].first;
        auto needs = [&](std::size_t count, const char* what) {
            if (w.size() < count + 1)
                fail(file, number, static_cast<int>(line.text.size()) + 1,
                     "expected " + std::string(what) + " after '" + std::string(key) + "'");
        };
        if (key.starts_with("//")) continue;
        if (key == "version:" || key == "range:") continue;
        if (key == "contact:" || key == "end:" || key == "heading:" || key == "up:" ||
            key == "size:") {
            // The curve's own turtle (where it attaches), which curveX does not use.
            std::size_t count = key == "size:" ? 1 : 3;
            needs(count, count == 1 ? "a number" : "three numbers 'x y z'");
            for (std::size_t i = 1; i <= count; ++i)
                parseNumber(file, line, w[i].first, w[i].second, "a number");
            continue;
        }
        if (key == "points:") {
            needs(1, "the number of points");
            if (!levels.empty() && levels.back().filled == 0)
                fail(file, number, w[0].second,
                     "a 'points:' line inside the points opens the sub-curve of the point "
                     "before it; there is none yet");
            if (levels.size() >= kMaxNesting)
                fail(file, number, w[0].second, "sub-curves nest at most 20 deep");
            Level l;
            l.size = wholeNumber(file, line, w[1].first, w[1].second, "the number of points", 1,
                                 kMaxPoints);
            levels.push_back(l);
            continue;
        }
        if (key == "dim:" || key == "dimension:" || key == "type:") {
            if (levels.empty())
                fail(file, number, w[0].second,
                     "'" + std::string(key) + "' comes after the 'points:' line it belongs to");
            if (key == "type:") {
                needs(1, "a curve type");
                levels.back().kind = kindNamed(w[1].first);
            } else {
                needs(1, "the dimension");
                levels.back().dimension =
                    wholeNumber(file, line, w[1].first, w[1].second, "the dimension", 2, 4);
            }
            continue;
        }
        // cpfg skips other labelled lines and lines of one or two characters.
        if (line.text.find(':') != std::string_view::npos) continue;
        std::string_view trimmed = line.text;
        while (!trimmed.empty() && (trimmed.back() == '\r' || trimmed.back() == ' '))
            trimmed.remove_suffix(1);
        if (trimmed.size() <= 2) continue;
        if (levels.empty())
            fail(file, number, w[0].second, "expected 'points: n' before the first point");
        // The point belongs to the innermost curve that still has room.
        while (levels.size() > 1 && levels.back().filled >= levels.back().size) levels.pop_back();
        Level& level = levels.back();
        if (level.filled >= level.size)
            fail(file, number, w[0].second,
                 "more points than the " + std::to_string(level.size) +
                     " the 'points:' line announces");
        if (static_cast<int>(w.size()) != level.dimension)
            fail(file, number, w[0].second,
                 "expected a point of " + std::to_string(level.dimension) +
                     " numbers (the dimension), found " + std::to_string(w.size()) + " words");
        ++level.filled;
        double v[4] = {0, 0, 0, 1};
        for (std::size_t i = 0; i < w.size(); ++i)
            v[i] = parseNumber(file, line, w[i].first, w[i].second, "a coordinate");
        if (levels.size() > 1) continue;  // a sub-curve's point: curveX never reads it
        int m = 1;
        if (level.dimension == 4)
            m = wholeNumber(file, line, w[3].first, w[3].second, "the multiplicity", 0,
                            kMaxMultiplicity);
        for (int k = 0; k < m; ++k) points.push_back({v[0], v[1], v[2]});
    }
    if (levels.empty()) fail(file, lastLine, 1, "expected 'points: n', found none");
    const Level& top = levels.front();
    if (top.filled < top.size || (levels.size() > 1 && levels.back().filled < levels.back().size))
        fail(file, lastLine, 1, "the file ends before all the points its 'points:' lines announce");
    std::size_t evaluated = points.size() + (top.kind == CurveXYZ::Kind::BSplineClosed ? 3 : 0) +
                            (top.kind == CurveXYZ::Kind::BSplinePhantom ? 2 : 0);
    if (top.kind == CurveXYZ::Kind::BezierSurface ? points.size() < 16 : evaluated < 4)
        fail(file, lastLine, 1,
             top.kind == CurveXYZ::Kind::BezierSurface
                 ? "a bezier-surface curve needs 16 points"
                 : "a curve needs at least 4 points (with their multiplicities)");
    std::string name = file;
    std::size_t slash = name.find_last_of('/');
    if (slash != std::string::npos) name = name.substr(slash + 1);
    return CurveXYZ(std::move(name), top.kind, std::move(points), samples);
}

}  // namespace graftal
