"""The quick-start notebook (examples/notebooks/quickstart.ipynb) runs from top to bottom in a
real Jupyter kernel (Debian's nbclient and ipykernel), and its pictures are there: the Koch
island as SVG, the 3D plant as a PNG, graftal.show()'s viewer with its GLB, the sweep."""
import os
import pathlib

import pytest

import graftal

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")


def test_quickstart_notebook_runs(root):
    path = root / "examples" / "notebooks" / "quickstart.ipynb"
    notebook = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=120, kernel_name="python3",
                                     resources={"metadata": {"path": str(path.parent)}})
    # The kernel imports the graftal this test imports, wherever it runs.
    env = dict(os.environ)
    package = pathlib.Path(os.path.abspath(graftal.__file__)).parent.parent
    env["PYTHONPATH"] = os.pathsep.join([str(package), env.get("PYTHONPATH", "")])
    client.execute(env=env)  # fails on the first cell that raises
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    kinds = [set(o.get("data", {})) for o in outputs]
    assert any("image/svg+xml" in k for k in kinds)  # the Koch island
    assert any("image/png" in k and "image/svg+xml" not in k for k in kinds)  # the 3D bush
    views = [o["data"]["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    assert any("graftalViewer.show(" in html for html in views)


def test_pictures_for_jupyter(root):
    koch = graftal.load(root / "examples/fig2.2-quadratic-koch-island.l")
    svg = koch._repr_svg_()
    assert svg.startswith("<?xml") or svg.startswith("<svg")
    assert koch._repr_png_() is None
    s = koch.derive(1)
    assert "<svg" in s._repr_svg_() and "<svg" in s.scene()._repr_svg_()
    bush = graftal.load(root / "examples/fig3.3-fibonacci-bush.l").derive(4)
    assert bush._repr_svg_() is None
    assert bush._repr_png_().startswith(b"\x89PNG")
    viewer = graftal.show(bush)
    assert viewer.glb.startswith(b"glTF")
    assert "graftalViewer.show(" in viewer._repr_html_()
