// A 3D scene as the 3D outputs consume it: the geometry that occurs once (stems, polygons)
// in one mesh, and repeated organs (a `~leaf` surface, an `@O` ball) stored once as a
// prototype and placed by transforms. A plant with 50,000 leaves then holds one leaf and
// 50,000 transforms: the ray tracer instances it, glTF writes EXT_mesh_gpu_instancing, and
// formats without instancing flatten it.
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "graftal/geometry/mesh.hpp"

namespace graftal {

// An affine map p -> linear * p + translation in single precision (as Embree and glTF
// store it). `columns[0..2]` are the images of the unit axes, `columns[3]` the
// translation. The linear part may mirror (negative determinant): a mirrored turtle frame
// mirrors its leaf.
struct Affine3f {
    Vec3f columns[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};

    Vec3f point(const Vec3f& p) const;
    // For normals: the inverse transpose of the linear part, renormalised.
    Vec3f normal(const Vec3f& n) const;
    float determinant() const;
    friend bool operator==(const Affine3f&, const Affine3f&) = default;
};

// One prototype placed once.
struct MeshPlacement {
    std::uint32_t prototype = 0;  // index into MeshScene::prototypes
    Affine3f transform;
};

// A stem segment thinner than a pixel, left as a round curve for the ray tracer instead of
// a tube (see MeshOptions::curveRadius). Formats without curves get it as a tube.
struct CurveSegment {
    Vec3f a, b;
    float radiusA = 0, radiusB = 0;
    std::uint16_t color = 0;
    // The curve this one continues along its axis (an index into MeshScene::curves, always
    // an earlier one; kNoSegment at the start of a run): its `b` is this one's `a` and its
    // radiusB this one's radiusA, so the joint is round and needs no cap of its own.
    std::uint32_t previous = kNoSegment;
};

struct MeshScene {
    Mesh mesh;                              // geometry that occurs once
    std::vector<Mesh> prototypes;           // each stored once, in its own coordinates
    std::vector<MeshPlacement> placements;  // where each copy goes
    std::vector<CurveSegment> curves;       // thin stems (empty unless asked for)

    // The palette every part indexes (mesh.palette; prototypes share it).
    const std::vector<Rgb>& palette() const { return mesh.palette; }
    // Counts as drawn: every placement counts its prototype's triangles again.
    std::size_t triangleCount() const;
    std::size_t vertexCount() const;
    // The box of everything drawn, placements applied (curves by their end points widened
    // by their radii).
    Bounds bounds() const;
    // One mesh with every placement copied in and its normals transformed (triangles of a
    // mirrored placement rewound so that they still face out). Curves are not included:
    // build with MeshOptions::curveRadius = 0 to get them as tubes.
    Mesh flattened() const;
    // One placement's copy appended to `out`, as flattened() copies it.
    void appendCopy(const MeshPlacement& placement, Mesh& out) const;
    void print(std::ostream& os) const;  // counts and bounds
};

std::ostream& operator<<(std::ostream& os, const MeshScene& s);

// Builds the scene's meshes with repeated organs instanced when `options.instancing` is
// set (otherwise everything lands in `mesh`). Surfaces named in the scene are looked up in
// `surfaces`; an unknown name throws Error, as buildMesh does.
MeshScene buildMeshScene(const Scene& scene, const MeshOptions& options = {},
                         const SurfaceLibrary* surfaces = nullptr);
// The same into `out`, whose arrays keep their storage: frames of an animation, or a
// program that meshes scene after scene, write into memory already mapped instead of
// faulting in hundreds of megabytes each time.
void buildMeshScene(const Scene& scene, const MeshOptions& options, const SurfaceLibrary* surfaces,
                    MeshScene& out);

}  // namespace graftal
