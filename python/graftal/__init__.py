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
from .display import Viewer, picture, show  # noqa: F401
from .sweep import sweep  # noqa: F401
from . import display as _display

_display.install()

__all__ = [
    "Derivation", "Diagnostic", "Error", "Map", "MapModel", "Mesh", "Model", "ModuleString",
    "ParseError", "Scene", "Viewer", "export_formats", "load", "parse", "picture", "show", "sweep",
]
