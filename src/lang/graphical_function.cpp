// cpfg's graphical functions (see the header). The curve, the search and the sampling
// follow cpfg's definitions so that func() gives cpfg's numbers, not just a close curve.
#include "graftal/lang/graphical_function.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

namespace {

constexpr int kOrder = 4;                   // cubic
constexpr double kSearchTolerance = 0.001;  // cpfg's bisection stops within this in x
constexpr int kMaxSearchSteps = 200;        // a curve whose x is not monotone may never get there

// The clamped uniform knots of cpfg's curves over n + 1 control points: four zeros, then
// 1, 2, ..., and four times n - 2 at the end.
int knot(int j, int n) {
    if (j < kOrder) return 0;
    if (j > n) return n - kOrder + 2;
    return j - kOrder + 1;
}

// Reads a function file line by line, keeping the line number for messages.
class LineReader {
  public:
    LineReader(std::string_view text, const std::string& file) : text_(text), file_(file) {}

    bool atEnd() const { return pos_ >= text_.size(); }
    int lineNumber() const { return number_; }

    std::string_view peek() const {
        std::size_t end = text_.find('\n', pos_);
        if (end == std::string_view::npos) end = text_.size();
        std::string_view l = text_.substr(pos_, end - pos_);
        if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
        return l;
    }

    std::string_view next(const char* expected) {
        if (atEnd()) fail(std::string("expected ") + expected + ", found the end of the file", 1);
        std::string_view l = peek();
        std::size_t end = text_.find('\n', pos_);
        pos_ = end == std::string_view::npos ? text_.size() : end + 1;
        ++number_;
        return l;
    }

    // The number after `key` on the next line ("samples: 5").
    double keyed(std::string_view key) {
        std::string_view l = next((std::string("'") + std::string(key) + " n'").c_str());
        std::size_t a = l.find_first_not_of(" \t");
        if (a == std::string_view::npos || l.substr(a, key.size()) != key)
            fail("expected '" + std::string(key) + "', found '" + std::string(l) + "'", 1);
        std::vector<double> v = numbers(l.substr(a + key.size()), 1);
        return v[0];
    }

    // The numbers of `s`: between `least` and `least + extra` of them.
    std::vector<double> numbers(std::string_view s, std::size_t least, std::size_t extra = 0) {
        std::vector<double> out;
        std::string copy(s);
        const char* p = copy.c_str();
        while (true) {
            while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
            if (!*p) break;
            char* stop = nullptr;
            double d = std::strtod(p, &stop);
            if (stop == p || !std::isfinite(d))
                fail("expected a number, found '" + std::string(p) + "'", 1);
            out.push_back(d);
            p = stop;
        }
        if (out.size() < least || out.size() > least + extra)
            fail("expected " + std::to_string(least) +
                     (extra ? " or " + std::to_string(least + extra) : std::string()) +
                     " numbers, found " + std::to_string(out.size()),
                 1);
        return out;
    }

    [[noreturn]] void fail(const std::string& message, int column) const {
        throw Error(SourceLocation{file_, std::max(number_, 1), column}, message);
    }

  private:
    std::string_view text_;
    std::string file_;
    std::size_t pos_ = 0;
    int number_ = 0;
};

bool startsWith(std::string_view line, std::string_view word) {
    std::size_t a = line.find_first_not_of(" \t");
    return a != std::string_view::npos && line.substr(a, word.size()) == word;
}

// cpfg stores the points as single-precision numbers.
double asFloat(double d) {
    return static_cast<double>(static_cast<float>(d));
}

int countOf(LineReader& in, std::string_view key, int least) {
    double d = in.keyed(key);
    if (d != std::floor(d) || d < least || d > 1e6)
        in.fail("'" + std::string(key) + "' must be a whole number of at least " +
                    std::to_string(least),
                1);
    return static_cast<int>(d);
}

// The body after `fver 1 1`.
GraphicalFunction readVersion101(LineReader& in) {
    std::string_view nameLine = in.next("'name: NAME'");
    if (!startsWith(nameLine, "name:")) in.fail("expected 'name: NAME'", 1);
    std::string name(nameLine.substr(nameLine.find(':') + 1));
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t\r") + 1);
    int samples = countOf(in, "samples:", 0);
    // Lines vlab's editor may add before flip: (a background image, markers) are skipped.
    if (startsWith(in.peek(), "b")) {
        in.next("a background line");
        in.next("a background line");
    }
    if (startsWith(in.peek(), "markers:")) {
        int markers = countOf(in, "markers:", 0);
        for (int i = 0; i < markers; ++i) in.next("a marker line");
    }
    if (!startsWith(in.next("'flip: on|off'"), "flip:")) in.fail("expected 'flip: on|off'", 1);
    int count = countOf(in, "points:", 4);
    std::vector<GraphicalFunction::Point> points;
    for (int i = 0; i < count; ++i) {
        std::vector<double> v = in.numbers(in.next("a point line 'x y'"), 2, 1);
        // A third number repeats the point (a sharper corner in the B-spline).
        double repeat = v.size() == 3 ? v[2] : 1;
        if (repeat < 1 || repeat > 64) in.fail("a point's repeat count must be 1 to 64", 1);
        for (int k = 0; k < static_cast<int>(repeat); ++k)
            points.push_back({asFloat(v[0]), asFloat(v[1])});
    }
    return GraphicalFunction(std::move(name), std::move(points), samples);
}

GraphicalFunction readOldFormat(LineReader& in, const std::string& name, int samples) {
    int count = countOf(in, "points:", 4);
    std::vector<GraphicalFunction::Point> points;
    for (int i = 0; i < count; ++i) {
        std::vector<double> v = in.numbers(in.next("a point line 'x y'"), 2);
        points.push_back({asFloat(v[0]), asFloat(v[1])});
    }
    return GraphicalFunction(name, std::move(points), samples);
}

GraphicalFunction readFunction(LineReader& in, const std::string& fileName, int samples) {
    std::string_view first = in.next("'fver 1 1' or 'range: lo hi'");
    if (startsWith(first, "range:")) return readOldFormat(in, fileName, samples);
    if (!startsWith(first, "fver")) in.fail("expected 'fver 1 1' or 'range: lo hi'", 1);
    std::vector<double> v = in.numbers(first.substr(first.find("fver") + 4), 2);
    if (v[0] != 1 || v[1] != 1)
        in.fail("function format version " + std::string(first) + " is not supported (1 1 is)", 1);
    return readVersion101(in);
}

}  // namespace

GraphicalFunction::GraphicalFunction(std::string name, std::vector<Point> points, int samples)
    : name_(std::move(name)), points_(std::move(points)) {
    if (samples > 2) {
        std::vector<double> table(static_cast<std::size_t>(samples));
        for (int i = 0; i < samples; ++i)
            table[static_cast<std::size_t>(i)] = search(double(i) / double(samples - 1));
        table_ = std::move(table);
    }
}

GraphicalFunction::Point GraphicalFunction::at(double t) const {
    const int n = static_cast<int>(points_.size()) - 1;
    if (n < kOrder - 1) return {};
    const double u = t * (n - kOrder + 2);
    // Cox–de Boor from order 1 up: basis[k] is N(k, order) at u; intervals are half-open.
    std::vector<double> basis(static_cast<std::size_t>(n + kOrder), 0.0);
    for (int k = 0; k <= n + kOrder - 1; ++k)
        basis[static_cast<std::size_t>(k)] = knot(k, n) <= u && u < knot(k + 1, n) ? 1.0 : 0.0;
    for (int order = 2; order <= kOrder; ++order) {
        for (int k = 0; k + order <= n + kOrder; ++k) {
            double sum = 0;
            int left = knot(k + order - 1, n) - knot(k, n);
            if (left != 0) sum = (u - knot(k, n)) / left * basis[static_cast<std::size_t>(k)];
            int right = knot(k + order, n) - knot(k + 1, n);
            if (right != 0)
                sum += (knot(k + order, n) - u) / right * basis[static_cast<std::size_t>(k + 1)];
            basis[static_cast<std::size_t>(k)] = sum;
        }
    }
    Point p;
    for (int k = 0; k <= n; ++k) {
        p.x += points_[static_cast<std::size_t>(k)].x * basis[static_cast<std::size_t>(k)];
        p.y += points_[static_cast<std::size_t>(k)].y * basis[static_cast<std::size_t>(k)];
    }
    return p;
}

double GraphicalFunction::search(double x) const {
    double low = 0, high = 1;
    Point p;
    for (int step = 0; step < kMaxSearchSteps; ++step) {
        double t = (low + high) / 2;
        p = at(t);
        if (p.x > x)
            high = t;
        else
            low = t;
        if (std::fabs(p.x - x) <= kSearchTolerance) break;
    }
    return p.y;
}

double GraphicalFunction::value(double x) const {
    if (!(x >= 0)) x = 0;  // also NaN
    if (x > 1) x = 1;
    if (table_.empty()) return search(x);
    double index = x * static_cast<double>(table_.size() - 1);
    auto i = static_cast<std::size_t>(std::floor(index));
    if (i + 1 >= table_.size()) return table_.back();
    double w = index - static_cast<double>(i);
    return (1 - w) * table_[i] + w * table_[i + 1];
}

GraphicalFunction parseFunctionFile(std::string_view text, const std::string& fileName,
                                    int oldFormatSamples) {
    LineReader in(text, fileName);
    return readFunction(in, fileName, oldFormatSamples);
}

std::vector<GraphicalFunction> parseFunctionSet(std::string_view text,
                                                const std::string& fileName) {
    LineReader in(text, fileName);
    std::string_view first = in.next("'funcgalleryver 1 1'");
    if (!startsWith(first, "funcgalleryver"))
        in.fail("expected 'funcgalleryver 1 1' (a function set)", 1);
    std::vector<double> v = in.numbers(first.substr(first.find("ver") + 3), 2);
    if (v[0] != 1 || v[1] != 1)
        in.fail("function set version " + std::string(first) + " is not supported (1 1 is)", 1);
    int items = countOf(in, "items:", 0);
    std::vector<GraphicalFunction> out;
    for (int i = 0; i < items; ++i) {
        // cpfg reads each item as it reads a .func file: `fver 1 1`, or the old `range:`
        // layout (whose functions are not sampled).
        std::string_view head = in.next("'fver 1 1' or 'range: lo hi'");
        if (startsWith(head, "range:")) {
            out.push_back(readOldFormat(in, "function " + std::to_string(i + 1), 0));
            continue;
        }
        if (!startsWith(head, "fver"))
            in.fail("expected 'fver 1 1' or 'range: lo hi' (function " + std::to_string(i + 1) +
                        " of the set's " + std::to_string(items) + ")",
                    1);
        std::vector<double> version = in.numbers(head.substr(head.find("fver") + 4), 2);
        if (version[0] != 1 || version[1] != 1)
            in.fail("function format version " + std::string(head) + " is not supported (1 1 is)",
                    1);
        out.push_back(readVersion101(in));
    }
    return out;
}

}  // namespace graftal
