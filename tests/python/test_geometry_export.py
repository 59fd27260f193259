"""Scenes and meshes as NumPy arrays (the pipeline's drawn() and meshed()), and export() in
every format of the registry, to a path and to bytes, equal to the command's files."""
import struct

import numpy as np
import pytest

import graftal

KOCH = "examples/fig2.2-quadratic-koch-island.l"
BUSH = "examples/fig3.3-fibonacci-bush.l"


def test_scene_arrays(root):
    scene = graftal.load(root / KOCH).derive(1).scene()
    assert not scene.is_3d
    seg = scene.segments
    assert seg.shape == (32, 2, 3) and seg.dtype == np.float64
    # The turtle starts at the origin heading +y, one unit a step.
    assert seg[0].tolist() == [[0, 0, 0], [0, 1, 0]]
    # Consecutive segments join; the island closes.
    assert np.allclose(seg[1:, 0], seg[:-1, 1])
    assert np.allclose(seg[-1, 1], seg[0, 0])
    assert scene.widths.shape == (32,) and scene.colors.dtype == np.uint16
    assert scene.segment_rgb.shape == (32, 3)
    assert np.allclose(scene.segment_rgb[0], scene.palette[scene.colors[0]])
    (lo, hi) = scene.bounds
    assert np.allclose(lo, seg.reshape(-1, 3).min(axis=0))
    assert np.allclose(hi, seg.reshape(-1, 3).max(axis=0))


def test_polygons(root):
    scene = graftal.load(root / "examples/fig2.9-filled-polygon-fractal.l").derive(1).scene()
    offsets = scene.polygon_offsets
    assert len(offsets) == len(scene.polygon_colors) + 1 > 1
    assert offsets[-1] == len(scene.polygon_vertices)


def test_mesh_of_a_3d_plant(root):
    scene = graftal.load(root / BUSH).derive(4).scene()
    assert scene.is_3d
    mesh = scene.mesh(tube_sides=6)
    v, i = mesh.vertices, mesh.indices
    assert v.dtype == np.float32 and v.shape[1] == 3 and len(v) > 0
    assert i.shape[1] == 3 and i.max() < len(v)
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1, atol=1e-3)
    assert mesh.triangles.shape == (len(i), 3, 3)
    assert np.array_equal(mesh.triangles[5], v[i[5]])
    assert len(mesh.triangle_colors) == len(i)


def test_export_to_bytes_equals_the_commands_file(root, cli, tmp_path):
    koch = graftal.load(root / KOCH)
    svg = koch.export(format="svg", steps=2)
    cli("render", KOCH, "-n", 2, "-o", tmp_path / "koch.svg")
    assert svg == (tmp_path / "koch.svg").read_bytes()
    assert svg.startswith(b"<?xml") or svg.startswith(b"<svg")
    png = koch.export(format="png", steps=2, size=(120, 80))
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", png[16:24]) == (120, 80)


@pytest.mark.parametrize("example, name, flags, options", [
    ("examples/fig2.7b-hilbert.l", "hilbert.png", ["--size", "160x120"], dict(size=(160, 120))),
    ("examples/fig3.4-plant.l", "plant.svg", [], {}),  # (a PDF holds its date)
    (BUSH, "bush.png", ["--size", "96x96", "--spp", "1"], dict(size=96, samples_per_pixel=1)),
    ("examples/fig6.2-snake-kolam.l", "kolam.svg", ["--dots"], dict(kolam_dots=True)),
])
def test_gallery_pictures_equal_the_commands(root, cli, tmp_path, example, name, flags, options):
    cli("render", example, "-o", tmp_path / name, *flags)
    model = graftal.load(root / example)
    assert model.export(format=name.split(".")[1], **options) == (tmp_path / name).read_bytes()


def test_export_to_a_path_and_read_back(root, tmp_path):
    bush = graftal.load(root / BUSH)
    notes = []
    assert bush.export(tmp_path / "bush.glb", steps=3, notes=notes) is None
    glb = (tmp_path / "bush.glb").read_bytes()
    assert glb[:4] == b"glTF" and struct.unpack("<I", glb[8:12])[0] == len(glb)
    obj = tmp_path / "bush.obj"
    bush.export(obj, steps=2)
    vertices = [l for l in obj.read_text().splitlines() if l.startswith("v ")]
    mesh = bush.derive(2).scene().mesh()
    assert len(vertices) == len(mesh.vertices)
    assert (tmp_path / "bush.mtl").exists()


# Every format of the registry, written to a file or to bytes. The engraved scores need
# LilyPond, which takes seconds each: the C++ suite engraves them (Music.*).
FAST = [f for f in graftal.export_formats() if not f["name"].startswith("score-")]


@pytest.mark.parametrize("fmt", FAST, ids=[f["name"] for f in FAST])
def test_every_registry_format(root, tmp_path, fmt):
    model = graftal.load(root / "examples/fig2.7b-hilbert.l")
    options = dict(steps=2)
    if fmt["kind"] == "animation":
        options.update(size=(64, 64), fps=4)
    if fmt["file_only"]:
        target = tmp_path / ("out" + fmt["extension"])
        assert model.export(target, format=fmt["name"], **options) is None
        assert target.exists()
        return
    data = model.export(format=fmt["name"], **options)
    assert isinstance(data, bytes) and len(data) > 0
    magic = {"png": b"\x89PNG", "pdf": b"%PDF", "glb": b"glTF", "gif": b"GIF8", "webp": b"RIFF",
             "mid": b"MThd", "wav": b"RIFF", "score-pdf": b"%PDF", "ply": b"ply\n"}
    if fmt["name"] in magic:
        assert data.startswith(magic[fmt["name"]])
