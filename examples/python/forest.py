"""A forest of stochastic plants placed on a ground, written as one instanced GLB.

A small stochastic tree (ABOP's ternary branching tree, its branches chosen and bent at
random) is grown once per seed by graftal.sweep(), on Dask when a scheduler is given; each
seed is another specimen. The forest places PLANTS copies of the SPECIMENS specimens on a
square of ground, each turned and scaled at random, and writes them as one glTF binary
whose meshes are placed by EXT_mesh_gpu_instancing (a specimen is stored once, however
often it stands in the forest; --specimens 1000 makes every plant its own).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/forest.py forest.glb
    ... forest.py forest.glb --scheduler tcp://scheduler:8786    (on a cluster)
"""
import argparse
import json
import struct

import numpy as np

import graftal

TREE = """/* A stochastic ternary tree: ABOP Fig 2.8 with branches that fork in two or three */
#define D1 94.74
#define D2 132.63
Lsystem: 1
derivation length: 4
tropism direction: 0, -1, 0
tropism elasticity: 0.22
axiom: !(1)F(200)/(45)A
A --> !(1.732)F(50)[&(15+ran(10))F(50)A]/(D1)[&(15+ran(10))F(50)A]/(D2)[&(15+ran(10))F(50)A] : 0.6
A --> !(1.732)F(50)[&(20+ran(15))F(50)A]/(D1+D2)[&(20+ran(15))F(50)A] : 0.4
F(l) --> F(l*(1.05+ran(0.1)))
!(w) --> !(w*1.732)
endlsystem
"""


def glb(meshes, placements, ground):
    """One glTF binary: each mesh (dict of arrays from graftal.sweep(meshes=True)) placed by
    EXT_mesh_gpu_instancing at its placements (translation, y rotation, scale), plus a
    ground quad of half-width `ground`."""
    blob = bytearray()
    views, accessors, gltf_meshes, nodes = [], [], [], []

    def add(array, target=None, minmax=False):
        array = np.ascontiguousarray(array)
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": array.nbytes}
        if target:
            view["target"] = target
        views.append(view)
        blob.extend(array.tobytes())
        kind = {1: "SCALAR", 3: "VEC3", 4: "VEC4"}[1 if array.ndim == 1 else array.shape[1]]
        accessor = {"bufferView": len(views) - 1, "count": len(array), "type": kind,
                    "componentType": 5125 if array.dtype == np.uint32 else 5126}
        if minmax:
            accessor["min"] = array.min(axis=0).tolist()
            accessor["max"] = array.max(axis=0).tolist()
        accessors.append(accessor)
        return len(accessors) - 1

    def add_mesh(vertices, normals, colours, indices):
        attributes = {"POSITION": add(vertices.astype(np.float32), 34962, True),
                      "NORMAL": add(normals.astype(np.float32), 34962),
                      "COLOR_0": add(colours.astype(np.float32), 34962)}
        gltf_meshes.append({"primitives": [{"attributes": attributes, "material": 0,
                                            "indices": add(indices.astype(np.uint32), 34963)}]})
        return len(gltf_meshes) - 1

    for k, mesh in enumerate(meshes):
        # Colours are per triangle: each triangle gets its own three corners.
        corners = mesh["indices"].reshape(-1)
        colours = np.repeat(mesh["triangle_rgb"], 3, axis=0)
        index = add_mesh(mesh["vertices"][corners], mesh["normals"][corners], colours,
                         np.arange(len(corners), dtype=np.uint32))
        mine = placements[placements[:, 0] == k]
        if not len(mine):
            continue
        half = mine[:, 4] / 2  # a turn about the up axis (y) as a quaternion
        rotation = np.stack([np.zeros_like(half), np.sin(half), np.zeros_like(half),
                             np.cos(half)], axis=1)
        nodes.append({"mesh": index, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {
            "TRANSLATION": add(mine[:, 1:4].astype(np.float32)),
            "ROTATION": add(rotation.astype(np.float32)),
            "SCALE": add(np.repeat(mine[:, 5:6], 3, axis=1).astype(np.float32))}}}})
    g = float(ground)
    quad = np.array([[-g, 0, -g], [g, 0, -g], [g, 0, g], [-g, 0, g]], dtype=np.float32)
    nodes.append({"mesh": add_mesh(quad, np.tile([0, 1, 0], (4, 1)),
                                   np.tile([0.35, 0.45, 0.2], (4, 1)),
                                   np.array([0, 2, 1, 0, 3, 2], dtype=np.uint32))})
    document = {
        "asset": {"version": "2.0", "generator": "graftal examples/python/forest.py"},
        "extensionsUsed": ["EXT_mesh_gpu_instancing"],
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
        "meshes": gltf_meshes, "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
        "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.9},
                       "doubleSided": True}]}
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    return b"".join([struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(blob)),
                     struct.pack("<II", len(text), 0x4E4F534A), text,
                     struct.pack("<II", len(blob), 0x004E4942), bytes(blob)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", help="the .glb file to write")
    parser.add_argument("--plants", type=int, default=1000)
    parser.add_argument("--specimens", type=int, default=24, help="distinct seeds grown")
    parser.add_argument("--scheduler", help="a Dask scheduler's address (default: here)")
    args = parser.parse_args()

    client = None
    if args.scheduler:
        from distributed import Client
        client = Client(args.scheduler)
    tree = graftal.parse(TREE, file="stochastic-tree.l")
    frame = graftal.sweep(tree, {"seed": range(1, args.specimens + 1)}, client, meshes=True,
                          tube_sides=5)
    rng = np.random.default_rng(0)
    side = 500 * np.sqrt(args.plants)  # about a crown's width between neighbours
    placements = np.column_stack([
        rng.integers(0, len(frame), args.plants),            # which specimen
        rng.uniform(-side / 2, side / 2, args.plants), np.zeros(args.plants),
        rng.uniform(-side / 2, side / 2, args.plants),       # where (x, 0, z)
        rng.uniform(0, 2 * np.pi, args.plants),              # turned about the up axis
        rng.uniform(0.7, 1.3, args.plants)])                  # and scaled
    data = glb(list(frame["mesh"]), placements, side / 2 + 1000)
    with open(args.output, "wb") as out:
        out.write(data)
    print(f"{args.plants} plants of {len(frame)} specimens "
          f"({frame['segments'].min()} to {frame['segments'].max()} segments each): "
          f"{args.output}, {len(data) / 1e6:.1f} MB")


if __name__ == "__main__":
    main()
