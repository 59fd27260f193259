"""The Python examples (examples/python/) run, on small settings, and make what they say:
a forest GLB, a sweep's plot, recovered constants, a tree grown in a Python light model."""
import contextlib
import io
import json
import runpy
import struct
import sys

import pytest


def run(root, script, *args):
    """Runs examples/python/SCRIPT ARGS... as `python3 SCRIPT ARGS...` would (as __main__,
    with its arguments in sys.argv) and returns what it printed. It runs in this process,
    which has imported NumPy, pandas and the module already: a process of its own would
    import them again for each example."""
    path = str(root / "examples" / "python" / script)
    out = io.StringIO()
    argv = sys.argv
    sys.argv = [path, *map(str, args)]
    try:
        with contextlib.redirect_stdout(out):
            runpy.run_path(path, run_name="__main__")
    except SystemExit as exit:
        if exit.code not in (None, 0):
            pytest.fail(f"{script} exited with {exit.code}")
    finally:
        sys.argv = argv
    return out.getvalue()


def test_forest(root, tmp_path):
    out = tmp_path / "forest.glb"
    assert "60 plants of 3 specimens" in run(root, "forest.py", out, "--plants", 60,
                                              "--specimens", 3)
    data = out.read_bytes()
    magic, version, length = struct.unpack("<III", data[:12])
    assert (magic, version, length) == (0x46546C67, 2, len(data))
    size, kind = struct.unpack("<II", data[12:20])
    document = json.loads(data[20:20 + size])
    placed = [n for n in document["nodes"] if "extensions" in n]
    counts = [document["accessors"][n["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]
                                    ["TRANSLATION"]]["count"] for n in placed]
    assert sum(counts) == 60 and len(document["meshes"]) == 4  # 3 specimens and the ground


def test_honda_sweep_plot(root, tmp_path):
    out = tmp_path / "honda.png"
    table = run(root, "honda_sweep.py", out, "--steps", 5)
    assert out.read_bytes()[:4] == b"\x89PNG"
    assert len(table.splitlines()) == 1 + 20  # a header and the 5 x 4 trees


def test_inverse_modelling(root):
    assert "recovered: R2 = " in run(root, "inverse_modelling.py", "--generations", 1,
                                     "--steps", 5)


def test_light_environment(root, tmp_path):
    out = tmp_path / "tree.svg"
    text = run(root, "light_environment.py", out, "--steps", 7)
    assert "step 7:" in text and out.read_text().startswith("<?xml")
