// The pulli of a kolam: the centres of the loops of the turtle's path (see kolam.hpp).
#include <cmath>
#include <numbers>

#include "graftal/geometry/kolam.hpp"

namespace graftal {

namespace {

// The signed turn (radians, left positive) from the direction of u to the direction of v,
// in the xy plane.
double turn(const Vec3& u, const Vec3& v) {
    return std::atan2(u.x * v.y - u.y * v.x, u.x * v.x + u.y * v.y);
}

struct DotSet {
    std::vector<Vec3> dots;
    double minDistance;
    void add(const Vec3& p) {
        for (const Vec3& d : dots)
            if (std::hypot(d.x - p.x, d.y - p.y) < minDistance) return;
        dots.push_back(p);
    }
};

// The loops of one run of consecutive segments [first, last].
void loopsOfRun(const std::vector<Segment>& segs, std::size_t first, std::size_t last,
                DotSet& out) {
    const double eps = 1e-9;
    std::size_t start = first;  // first segment of the current same-side stretch
    double total = 0;
    int side = 0;
    auto finish = [&](std::size_t end) {  // the stretch is segments start..end
        if (std::abs(total) < std::numbers::pi - 1e-6) return;
        std::vector<Vec3> corners;
        corners.push_back(segs[start].a);
        for (std::size_t s = start; s <= end; ++s) {
            const Vec3& p = segs[s].b;
            bool seen = false;
            for (const Vec3& c : corners)
                seen = seen || std::hypot(c.x - p.x, c.y - p.y) < 1e-6 * out.minDistance;
            if (!seen) corners.push_back(p);
        }
        Vec3 c{0, 0, 0};
        for (const Vec3& p : corners) c = c + p;
        out.add(c * (1.0 / static_cast<double>(corners.size())));
    };
    for (std::size_t s = first; s < last; ++s) {
        double t = turn(segs[s].b - segs[s].a, segs[s + 1].b - segs[s + 1].a);
        int sideHere = t > eps ? 1 : t < -eps ? -1 : 0;
        if (sideHere != 0 && sideHere == side) {
            total += t;
            continue;
        }
        finish(s);
        side = sideHere;
        start = s;
        total = t;
        if (sideHere == 0) start = s + 1;
    }
    finish(last);
}

}  // namespace

std::vector<Vec3> kolamDots(const Scene& scene, double stepLength) {
    DotSet out{{}, 0.25 * stepLength};
    const std::vector<Segment>& segs = scene.segments;
    std::size_t first = 0;
    for (std::size_t s = 0; s < segs.size(); ++s) {
        bool continues = s + 1 < segs.size() && segs[s + 1].a == segs[s].b;
        if (!continues) {
            loopsOfRun(segs, first, s, out);
            first = s + 1;
        }
    }
    return out.dots;
}

void addKolamDots(Scene& scene, double stepLength, double radius, std::uint16_t color) {
    for (const Vec3& p : kolamDots(scene, stepLength))
        scene.discs.push_back(Disc{p, {0, 0, 1}, radius, color});
}

}  // namespace graftal
