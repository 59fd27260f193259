// A placement as glTF's EXT_mesh_gpu_instancing stores it: translation, rotation
// (a unit quaternion) and a scale per axis, composed T * R * S. Not every Affine3f is one:
// a sheared linear part has no such form, and a mirror (negative determinant) would need a
// negative scale, which instanced renderers do not rewind triangles for. The writer gives a
// mirrored placement a mirrored copy of its prototype instead (mirroredPrototype), and
// copies a sheared one into the mesh.
#pragma once

#include <array>
#include <optional>

#include "graftal/geometry/mesh.hpp"
#include "graftal/geometry/mesh_scene.hpp"

namespace graftal::instance_transform {

struct Trs {
    std::array<float, 3> translation{0, 0, 0};
    std::array<float, 4> rotation{0, 0, 0, 1};  // x, y, z, w
    std::array<float, 3> scale{1, 1, 1};
};

// The TRS form of `a`, or nullopt when its linear part is not a rotation times a positive
// scale per axis: its columns must be orthogonal (to a relative 1e-4), non-zero and
// right-handed (a positive determinant).
std::optional<Trs> decompose(const Affine3f& a);

// T * R * S as an affine map (what a viewer draws).
Affine3f compose(const Trs& trs);

// The prototype reflected through its own z = 0 plane, triangles rewound and normals
// reflected, so that it still faces out; placed by withMirroredPrototype(a) it draws what
// the original placed by `a` draws.
Mesh mirroredPrototype(const Mesh& prototype);
Affine3f withMirroredPrototype(const Affine3f& a);

}  // namespace graftal::instance_transform
