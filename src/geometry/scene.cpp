#include "graftal/geometry/scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace graftal {

namespace {

Rgb hex(unsigned rgb) {
    return {static_cast<float>((rgb >> 16) & 0xff) / 255.0f,
            static_cast<float>((rgb >> 8) & 0xff) / 255.0f,
            static_cast<float>(rgb & 0xff) / 255.0f};
}

}  // namespace

void Bounds::extend(const Vec3& p) {
    min.x = std::min(min.x, p.x);
    min.y = std::min(min.y, p.y);
    min.z = std::min(min.z, p.z);
    max.x = std::max(max.x, p.x);
    max.y = std::max(max.y, p.y);
    max.z = std::max(max.z, p.z);
}

void Bounds::extend(const Bounds& b) {
    // An empty box has min = +inf and max = -inf; extending by those corners would be
    // harmless for min/max but reads as a bug, so skip it explicitly.
    if (b.empty()) return;
    extend(b.min);
    extend(b.max);
}

std::ostream& operator<<(std::ostream& os, const Bounds& b) {
    if (b.empty()) return os << "empty";
    return os << b.min << " .. " << b.max;
}

void Scene::addPolygon(std::span<const Vec3> vertices, std::uint16_t color) {
    // polygonStart is public; a caller who cleared it would otherwise make polygon(k)
    // read out of bounds.
    if (polygonStart.empty()) polygonStart.push_back(0);
    polygonVertices.insert(polygonVertices.end(), vertices.begin(), vertices.end());
    polygonStart.push_back(static_cast<std::uint32_t>(polygonVertices.size()));
    polygonColor.push_back(color);
}

Rgb Scene::colorOf(std::uint16_t index) const {
    if (palette.empty()) return Rgb{0, 0, 0};
    return palette[index % palette.size()];
}

Bounds discBounds(const Disc& d) {
    // A circle of radius r with unit normal n reaches r·sqrt(1 - n_i²) along axis i.
    Bounds b;
    if (!isFinite(d.centre) || !std::isfinite(d.radius)) return b;
    auto reach = [&](double n) { return d.radius * std::sqrt(std::max(0.0, 1 - n * n)); };
    Vec3 r{reach(d.normal.x), reach(d.normal.y), reach(d.normal.z)};
    b.extend(d.centre - r);
    b.extend(d.centre + r);
    return b;
}

Bounds sphereBounds(const Sphere& s) {
    Bounds b;
    if (!isFinite(s.centre) || !std::isfinite(s.radius)) return b;
    Vec3 r{s.radius, s.radius, s.radius};
    b.extend(s.centre - r);
    b.extend(s.centre + r);
    return b;
}

Bounds Scene::bounds() const {
    // Non-finite points (a turtle fed an infinite step, say) are left out: one of them would
    // make the box infinite and every writer would then fit the whole picture into a point.
    Bounds b;
    for (const Segment& s : segments) {
        if (isFinite(s.a)) b.extend(s.a);
        if (isFinite(s.b)) b.extend(s.b);
    }
    for (const Vec3& v : polygonVertices)
        if (isFinite(v)) b.extend(v);
    for (const Disc& d : discs) b.extend(discBounds(d));
    for (const Sphere& s : spheres) b.extend(sphereBounds(s));
    return b;
}

void Scene::print(std::ostream& os) const {
    const std::size_t polygons = polygonCount();
    os << "scene: " << segments.size() << (segments.size() == 1 ? " segment, " : " segments, ")
       << polygons << (polygons == 1 ? " polygon" : " polygons");
    if (!discs.empty()) os << ", " << discs.size() << (discs.size() == 1 ? " disc" : " discs");
    if (!spheres.empty())
        os << ", " << spheres.size() << (spheres.size() == 1 ? " sphere" : " spheres");
    os << ", bounds " << bounds();
}

std::ostream& operator<<(std::ostream& os, const Scene& s) {
    s.print(os);
    return os;
}

std::vector<Rgb> Scene::defaultPalette() {
    // Plants step through the palette with ', so the order matters more than the colours:
    // ink for stems, then leaf greens, then flower colours, then everything else.
    return {
        hex(0x1f2a1f),  //  0 dark ink: stems, curves
        hex(0x3a7d2c),  //  1 leaf green
        hex(0x8cbf3f),  //  2 light, yellowish green: young leaves
        hex(0xd9455f),  //  3 rose: petals
        hex(0xf2c230),  //  4 yellow: stamens, flower centres
        hex(0x7a4b2a),  //  5 bark brown
        hex(0x2f6db5),  //  6 blue
        hex(0xe0702a),  //  7 orange
        hex(0x1e5631),  //  8 dark green: old leaves, conifers
        hex(0xa15cc4),  //  9 violet
        hex(0xb5d99c),  // 10 pale green
        hex(0xc0392b),  // 11 deep red: berries
        hex(0xe8a0bf),  // 12 pink
        hex(0x5b3a29),  // 13 dark brown
        hex(0x4fb0c6),  // 14 sky cyan
        hex(0x7f7f7f),  // 15 grey
    };
}

}  // namespace graftal
