"""Pictures of models, derived strings and scenes in Jupyter, and graftal.show().

Every picture is made by the library's export registry (Model.export), as `graftal render`
makes it: 2D models show as SVG line art, 3D ones as a ray-traced PNG. show() puts the
studio's three.js view (bundled into viewer.js when graftal is built; no network) in the
output cell, with the model's mesh as glTF binary.
"""
import base64
import json
import pathlib
import uuid

from . import _graftal

#: The size of the pictures notebooks show, in pixels.
PICTURE_SIZE = 400


def _settings(obj):
    """The model and the export keywords that remake what `obj` shows."""
    if isinstance(obj, (_graftal.Model, _graftal.MapModel)):
        return obj, {}
    if isinstance(obj, (_graftal.ModuleString, _graftal.Scene)):
        return obj.model, dict(obj.derive_keywords)
    raise TypeError(f"expected a graftal Model, ModuleString or Scene, not {type(obj).__name__}")


def _is_3d(obj):
    if isinstance(obj, _graftal.MapModel):
        return False
    if isinstance(obj, _graftal.Scene):
        return obj.is_3d
    if isinstance(obj, _graftal.ModuleString):
        return obj.scene().is_3d
    model, options = _settings(obj)
    return model.derive(**options).scene().is_3d


def picture(obj, format="svg", size=PICTURE_SIZE, **options):
    """The picture of a Model, ModuleString or Scene as bytes, exported as `graftal
    render` would write it (format 'svg', 'png' or 'pdf')."""
    model, keywords = _settings(obj)
    keywords.update(options)
    return model.export(format=format, size=(size, size), **keywords)


def repr_svg(obj):
    """Jupyter's SVG of a 2D model (None for a 3D one, which shows as a PNG)."""
    if _is_3d(obj):
        return None
    return picture(obj, "svg").decode()


def repr_png(obj):
    """Jupyter's PNG of a 3D model: ray traced with the file's camera (None for 2D)."""
    if not _is_3d(obj):
        return None
    return picture(obj, "png", samples_per_pixel=1)


def _viewer_script():
    path = pathlib.Path(__file__).with_name("viewer.js")
    if not path.exists():
        raise RuntimeError(
            "graftal.show() needs viewer.js, which the build bundles from the studio's npm "
            "packages; build graftal with npm installed")
    return path.read_text()


class Viewer:
    """An interactive 3D view of a model in a notebook's output cell (graftal.show()).

    Its HTML holds the studio's bundled three.js viewer and the model's mesh as GLB, so
    the notebook shows it offline and keeps showing it once saved. A map L-system, drawn
    flat, is its SVG picture instead (`svg`; `glb` is then None)."""

    def __init__(self, glb, height=480, svg=None):
        self.glb = glb
        self.height = height
        self.svg = svg

    def _repr_html_(self):
        element = "graftal-" + uuid.uuid4().hex
        if self.glb is None:
            # The SVG scaled into the cell, its proportions kept.
            return (f'<div id="{element}" style="width:100%;height:{int(self.height)}px">'
                    f'<img style="width:100%;height:100%;object-fit:contain" alt="map" '
                    f'src="data:image/svg+xml;base64,{base64.b64encode(self.svg).decode()}">'
                    "</div>")
        data = base64.b64encode(self.glb).decode()
        return (
            f'<div id="{element}" style="width:100%;height:{int(self.height)}px"></div>'
            f"<script>{_viewer_script()}\n"
            f"graftalViewer.show(document.getElementById({json.dumps(element)}), "
            f"{json.dumps(data)});</script>")

    def html(self):
        """The view as a self-contained HTML page."""
        return ("<!doctype html><meta charset=utf-8><title>graftal</title>"
                f"<body style=margin:0>{self._repr_html_()}</body>")

    def __repr__(self):
        if self.glb is None:
            return f"<graftal.Viewer {len(self.svg)} bytes of SVG>"
        return f"<graftal.Viewer {len(self.glb)} bytes of GLB>"


def show(obj, height=480, **options):
    """An interactive 3D view (orbit with the mouse) of a Model, ModuleString or Scene:
    its mesh as `graftal render -o x.glb` writes it, in the studio's three.js viewer.
    A MapModel, drawn flat, shows as its SVG picture scaled to the cell. Returns a Viewer,
    which Jupyter displays; options go to Model.export (MapModel.export for a map)."""
    model, keywords = _settings(obj)
    keywords.update(options)
    if isinstance(model, _graftal.MapModel):
        return Viewer(None, height, svg=model.export(format="svg", **keywords))
    keywords.setdefault("glb_compression", True)
    glb = model.export(format="glb", **keywords)
    return Viewer(glb, height)


__all__ = ["picture", "show", "Viewer", "PICTURE_SIZE"]
