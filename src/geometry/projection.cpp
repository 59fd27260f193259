#include "graftal/geometry/projection.hpp"

namespace graftal {

std::optional<ViewDirection> viewDirectionFromName(const std::string& name) {
    if (name == "front") return ViewDirection::Front;
    if (name == "back") return ViewDirection::Back;
    if (name == "side") return ViewDirection::Side;
    if (name == "top") return ViewDirection::Top;
    return std::nullopt;
}

static Vec3 project(const Vec3& p, ViewDirection v) {
    switch (v) {
        case ViewDirection::Front:
            return {p.x, p.y, 0};
        case ViewDirection::Back:
            return {-p.x, p.y, 0};
        case ViewDirection::Side:
            return {-p.z, p.y, 0};
        case ViewDirection::Top:
            return {p.x, -p.z, 0};
    }
    return p;
}

Scene projectScene(const Scene& scene, ViewDirection view) {
    Scene out = scene;
    for (auto& s : out.segments) {
        s.a = project(s.a, view);
        s.b = project(s.b, view);
    }
    for (auto& p : out.polygonVertices) p = project(p, view);
    for (auto& s : out.surfaces) s.origin = project(s.origin, view);
    // Line art fills outlines: a disc becomes its projected outline (an ellipse unless it
    // faces the viewer), a sphere the circle it looks like from any side.
    constexpr int kSides = 48;
    for (const Disc& d : scene.discs) {
        std::vector<Vec3> outline = discOutline(d, kSides);
        for (Vec3& p : outline) p = project(p, view);
        out.addPolygon(outline, d.color);
    }
    for (const Sphere& s : scene.spheres)
        out.addPolygon(
            discOutline(Disc{project(s.centre, view), {0, 0, 1}, s.radius, s.color}, kSides),
            s.color);
    out.discs.clear();
    out.spheres.clear();
    out.is3D = false;
    return out;
}

}  // namespace graftal
