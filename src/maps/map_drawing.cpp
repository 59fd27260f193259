// A map to a Scene: walls, cell outlines as B-splines, cell fills.
#include <algorithm>
#include <cmath>
#include <functional>

#include "graftal/geometry/bspline.hpp"
#include "graftal/maps/map_drawing.hpp"

namespace graftal {

namespace {

// Ink, then fills: a ramp of greens for ages, then distinct pale colours for the rest.
constexpr int kAgeShades = 12;
constexpr int kFirstFill = 1;

std::vector<Rgb> mapPalette() {
    std::vector<Rgb> p;
    p.push_back({0.08, 0.1, 0.08});
    for (int i = 0; i < kAgeShades; ++i) {
        const float t = static_cast<float>(i) / (kAgeShades - 1);  // 0 oldest .. 1 newest
        p.push_back({0.35f + 0.55f * t, 0.6f + 0.35f * t, 0.3f + 0.5f * t});
    }
    const Rgb distinct[] = {{0.98, 0.85, 0.6}, {0.7, 0.85, 0.95}, {0.8, 0.95, 0.7},
                            {0.95, 0.75, 0.8}, {0.85, 0.8, 0.95}, {0.95, 0.95, 0.65},
                            {0.7, 0.95, 0.9},  {0.95, 0.8, 0.65}, {0.75, 0.75, 0.75},
                            {0.9, 0.7, 0.95}};
    for (const Rgb& c : distinct) p.push_back(c);
    return p;
}

constexpr int kDistinct = 10;

std::uint16_t fillColor(const PlaneMap& m, std::uint32_t r, const std::vector<std::uint32_t>& cycle,
                        MapFill fill) {
    switch (fill) {
        case MapFill::Age: {
            const int age = m.step - m.regionBorn[r];
            return static_cast<std::uint16_t>(kFirstFill + kAgeShades - 1 -
                                              std::min(age, kAgeShades - 1));
        }
        case MapFill::Sides:
            return static_cast<std::uint16_t>(kFirstFill + kAgeShades + (cycle.size() % kDistinct));
        case MapFill::Labels: {
            // The smallest rotation of the label cycle names the cell's state.
            std::string word;
            for (std::uint32_t h : cycle) {
                word += PlaneMap::forward(h) ? '+' : '-';
                word += m.label[PlaneMap::edgeOf(h)];
            }
            std::string best = word;
            for (std::size_t i = 2; i < word.size(); i += 2)
                best = std::min(best, word.substr(i) + word.substr(0, i));
            return static_cast<std::uint16_t>(kFirstFill + kAgeShades +
                                              std::hash<std::string>{}(best) % kDistinct);
        }
        case MapFill::None:
            break;
    }
    return 0;
}

}  // namespace

std::optional<MapFill> mapFillFromName(const std::string& name) {
    if (name == "none") return MapFill::None;
    if (name == "age") return MapFill::Age;
    if (name == "sides") return MapFill::Sides;
    if (name == "labels") return MapFill::Labels;
    return std::nullopt;
}

Scene mapScene(const PlaneMap& m, const MapDrawingOptions& o) {
    Scene scene;
    scene.palette = mapPalette();
    scene.baseWidth = 1;
    std::vector<Vec3> corners, curve;
    for (std::uint32_t r = 1; r < m.regionCount(); ++r) {
        const auto cycle = m.boundary(r);
        corners.clear();
        for (std::uint32_t h : cycle) corners.push_back(m.position[m.origin(h)]);
        const bool smooth = o.splines && corners.size() >= 3;
        if (smooth) curve = bsplineCurve(corners, std::max(1, o.splineSubdivisions), true);
        const std::vector<Vec3>& outline = smooth ? curve : corners;
        if (o.fill != MapFill::None) {
            std::span<const Vec3> pts(outline.data(), smooth ? outline.size() - 1 : outline.size());
            scene.addPolygon(pts, fillColor(m, r, cycle, o.fill));
        }
        if (smooth)
            for (std::size_t i = 0; i + 1 < curve.size(); ++i)
                scene.segments.push_back({curve[i], curve[i + 1], 1, 0, kNoSegment, {0, 0, 1}});
    }
    if (!o.splines) {
        for (std::size_t e = 0; e < m.edgeCount(); ++e) {
            const float w = o.widthByAge ? static_cast<float>(m.step - m.born[e] + 1) : 1.0f;
            scene.segments.push_back(
                {m.position[m.tail[e]], m.position[m.head[e]], w, 0, kNoSegment, {0, 0, 1}});
        }
    }
    return scene;
}

}  // namespace graftal
