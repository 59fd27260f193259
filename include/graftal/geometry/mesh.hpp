// Triangle meshes: what 3D files and the ray tracer consume. Built from a Scene by the
// mesher (src/geometry/), which turns segments into generalized cylinders, polygons into
// triangles and placed surfaces into tessellated patches.
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "graftal/geometry/scene.hpp"

namespace graftal {

class SurfaceLibrary;

struct Vec3f {
    float x = 0, y = 0, z = 0;

    friend bool operator==(const Vec3f&, const Vec3f&) = default;
};

// The single-precision copy a mesh stores (and Embree reads) of a computed point.
inline Vec3f toVec3f(const Vec3& v) {
    return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}
inline Vec3 toVec3(const Vec3f& v) {
    return {v.x, v.y, v.z};
}

// Indexed triangles with per-vertex normals; every triangle has a colour index into
// `palette` (writers group triangles by colour into materials).
struct Mesh {
    std::vector<Vec3f> positions;
    std::vector<Vec3f> normals;                // one per position, unit length
    std::vector<std::uint32_t> indices;        // 3 per triangle, counter-clockwise = front
    std::vector<std::uint16_t> triangleColor;  // one per triangle
    std::vector<Rgb> palette;

    std::size_t triangleCount() const { return triangleColor.size(); }
    Bounds bounds() const;
    void append(const Mesh& other);      // palettes must agree (the scene's)
    void print(std::ostream& os) const;  // counts and bounds
};

std::ostream& operator<<(std::ostream& os, const Mesh& m);

struct MeshOptions {
    int tubeSides = 8;         // cross-section vertices of a cylinder
    double minimumRadius = 0;  // thinner stems are widened to this (model units)
    double widthScale = 1;     // cylinder diameter = segment width * widthScale
    int surfaceDivisions = 8;  // per patch side when tessellating bicubic patches
    bool cylinders = true;     // false: segments are left out (polygons and surfaces only)
    // buildMeshScene: repeated organs (placed surfaces, discs, spheres, and polygons of a
    // shape drawn more than once, e.g. the same leaf at every node) become prototypes
    // placed by transforms instead of copies. Organs scaled to nothing are left out.
    bool instancing = true;
    // buildMeshScene: segments whose drawn radius (width * widthScale / 2, at least
    // minimumRadius) is below this (model units) become CurveSegments instead of tubes; 0
    // keeps every segment a tube. buildMesh ignores it.
    double curveRadius = 0;
    // Threads that build the tubes (0: one per core); the mesh is the same for any number.
    unsigned threads = 0;
};

// Builds the mesh of a scene. Surfaces named in the scene are looked up in `surfaces`
// (may be null when the scene places none); an unknown name throws Error.
Mesh buildMesh(const Scene& scene, const MeshOptions& options = {},
               const SurfaceLibrary* surfaces = nullptr);

// Splits a simple polygon (possibly concave, roughly planar, in 3D) into triangles by ear
// clipping in its best-fit plane. Returns vertex indices, 3 per triangle; degenerate
// input (fewer than 3 distinct vertices) gives none.
std::vector<std::uint32_t> triangulatePolygon(const std::vector<Vec3>& outline);

}  // namespace graftal
