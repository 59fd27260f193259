"""graftal in Python: derive and draw Lindenmayer systems with graftal's library.

    import graftal
    koch = graftal.load("examples/fig2.2-quadratic-koch-island.l")
    s = koch.derive(steps=2)
    print(s)                      # the module string, as `graftal derive` prints it
    s.symbols                     # NumPy uint8 array over the library's storage (no copy)
    koch.export("koch.svg")       # any format of graftal.export_formats()

In Jupyter, models, strings and scenes show as pictures; graftal.show() gives a 3D view.
graftal.sweep() derives a model over a grid of constants and seeds, on Dask when given a
client. See docs/python.md.
"""
from ._graftal import (  # noqa: F401
    Derivation,
    Diagnostic,
    Error,
    Map,
    MapModel,
    Mesh,
    Model,
    ModuleString,
    ParseError,
    Scene,
    export_formats,
    load,
    parse,
)

# Importing graftal costs little more than loading the library: the pictures' helpers
# (graftal.display) and the sweeps' (graftal._sweep, which imports pandas) are imported when
# first used, and NumPy when an array is first asked for.
_LAZY = {"Viewer": "display", "picture": "display", "show": "display", "sweep": "_sweep"}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module("." + _LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'graftal' has no attribute '{name}'")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


def _repr_svg_(obj):
    from . import display

    return display.repr_svg(obj)


def _repr_png_(obj):
    from . import display

    return display.repr_png(obj)


# Jupyter's pictures of models, strings and scenes (a map L-system is drawn flat: SVG only).
for _cls in (Model, ModuleString, Scene):
    _cls._repr_svg_ = _repr_svg_
    _cls._repr_png_ = _repr_png_
MapModel._repr_svg_ = _repr_svg_
del _cls

__all__ = [
    "Derivation", "Diagnostic", "Error", "Map", "MapModel", "Mesh", "Model", "ModuleString",
    "ParseError", "Scene", "Viewer", "export_formats", "load", "parse", "picture", "show", "sweep",
]
