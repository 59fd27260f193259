// The cross-section points of a contour (see graftal/contour.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "graftal/geometry/contour_points.hpp"

namespace graftal {

namespace {

constexpr int kSamplesPerSpan = 10;  // cpfg measures a contour's length at 10 points per span

// The uniform cubic B-spline over `p` at parameter t in [0, spans]: span i is shaped by
// points i .. i + 3, wrapped around the end (only closed contours reach past it).
Vec3 splinePoint(const std::vector<Vec3>& p, double t) {
    const int n = static_cast<int>(p.size());
    int i = static_cast<int>(std::floor(t));
    double u = t - i;
    const double u2 = u * u, u3 = u2 * u;
    const double w[4] = {(1 - 3 * u + 3 * u2 - u3) / 6, (3 * u3 - 6 * u2 + 4) / 6,
                         (-3 * u3 + 3 * u2 + 3 * u + 1) / 6, u3 / 6};
    Vec3 out{0, 0, 0};
    for (int k = 0; k < 4; ++k) out = out + p[((i + k) % n + n) % n] * w[k];
    return out;
}

}  // namespace

std::vector<Vec3> circleContourPoints(int sides) {
    std::vector<Vec3> out;
    out.reserve(sides + 1);
    for (int i = 0; i < sides; ++i) {
        double a = 2 * std::numbers::pi * i / sides;
        out.push_back({std::cos(a), std::sin(a), 0});
    }
    out.push_back(out.front());
    return out;
}

std::vector<Vec3> contourPoints(const Contour& contour, int sides) {
    const std::vector<Vec3>& p = contour.controlPoints;
    const int spans = contour.closed ? static_cast<int>(p.size()) : static_cast<int>(p.size()) - 3;
    if (sides < 1 || spans < 1) return circleContourPoints(std::max(sides, 3));
    // The curve sampled evenly in t, with the length along it (in x and y, as cpfg).
    const int samples = spans * kSamplesPerSpan;
    std::vector<Vec3> at(samples + 1);
    std::vector<double> length(samples + 1, 0.0);
    for (int k = 0; k <= samples; ++k) {
        at[k] = splinePoint(p, static_cast<double>(k) / kSamplesPerSpan);
        if (k > 0)
            length[k] = length[k - 1] + std::hypot(at[k].x - at[k - 1].x, at[k].y - at[k - 1].y);
    }
    // cpfg turns a closed contour so that its start lies on +x; open ones stay as drawn.
    double c = 1, s = 0;
    if (contour.closed) {
        double r = std::hypot(at[0].x, at[0].y);
        if (r > 1e-9) c = at[0].x / r, s = at[0].y / r;
    }
    auto turned = [&](const Vec3& v) { return Vec3{v.x * c + v.y * s, v.y * c - v.x * s, v.z}; };
    std::vector<Vec3> out;
    out.reserve(sides + 1);
    const double total = length[samples];
    int k = 1;
    for (int i = 0; i <= sides; ++i) {
        if (contour.closed && i == sides) {
            out.push_back(out.front());
            break;
        }
        double want = total * i / sides;
        while (k < samples && length[k] < want) ++k;
        double span = length[k] - length[k - 1];
        double f = span > 0 ? std::clamp((want - length[k - 1]) / span, 0.0, 1.0) : 0.0;
        double t = (k - 1 + f) / kSamplesPerSpan;
        out.push_back(turned(splinePoint(p, t)));
    }
    return out;
}

}  // namespace graftal
