"""Type stubs of graftal's Python module, for editors and type checkers (docs/python.md)."""
import os
from typing import Any, Callable, Iterator, Mapping, Protocol, Sequence, Union, overload

import numpy as np
import numpy.typing as npt
import pandas

PathLike = Union[str, os.PathLike[str]]
Size = Union[int, str]  # bytes, or '2G', '512M'
Colour = Union[str, tuple[float, float, float]]  # '#rrggbb' or (r, g, b) from 0 to 1
Vector = tuple[float, float, float]
Define = Union[int, float, str]

class Error(Exception):
    """An error of graftal's; str() is every diagnostic as the graftal command prints it."""
    diagnostics: list[Diagnostic]

class ParseError(Error):
    """A model that does not parse: .diagnostics holds every error found."""

class Diagnostic:
    """A problem, warning or note at a place in a file."""
    severity: str  # 'error', 'warning' or 'note'
    file: str
    line: int  # 1-based; 0 for the file as a whole
    column: int  # 1-based, in bytes
    end_line: int
    end_column: int
    message: str

class Queries(Protocol):
    """What an environment is asked after every step: one row per ?E module, in string
    order. Write the answers into `parameters` (or return them)."""
    step: int
    index: npt.NDArray[np.int64]  # the module's position in the string
    position: npt.NDArray[np.float64]  # (n, 3): the turtle's position at the module
    heading: npt.NDArray[np.float64]  # (n, 3): H
    left: npt.NDArray[np.float64]  # (n, 3): L
    up: npt.NDArray[np.float64]  # (n, 3): U
    parameters: Union[npt.NDArray[np.float64], list[npt.NDArray[np.float64]]]

class EnvironmentObject(Protocol):
    def respond(self, step: int, queries: Queries) -> Any: ...

Environment = Union[EnvironmentObject, Callable[[int, Queries], Any]]
# func(id, x) answered by Python: keyed by the id or a name the model gives it.
Functions = Mapping[Union[int, str], Callable[[float], float]]
Random = str  # 'graftal' or 'cpfg'

class Model:
    """A parsed model (graftal.load, graftal.parse)."""
    name: str
    file: str
    derivation_length: int
    defines: dict[str, str]
    overrides: dict[str, str]
    symbols: list[str]  # module names by symbol id
    warnings: list[Diagnostic]
    def derive(self, steps: int | None = None, *, seed: int | None = None, threads: int = 0,
               memory_limit: Size | None = None, precision: str = "single",
               environment: Environment | None = None,
               random: Random | None = None) -> ModuleString: ...
    def derivation(self, steps: int | None = None, *, seed: int | None = None,
                   threads: int = 0, memory_limit: Size | None = None,
                   precision: str = "single", environment: Environment | None = None,
                   random: Random | None = None) -> Derivation: ...
    def statistics(self, steps: int | None = None, *, seed: int | None = None,
                   threads: int = 0, memory_limit: Size | None = None, geometry: bool = True,
                   stream: bool = False, environment: Environment | None = None,
                   random: Random | None = None) -> dict[str, Any]: ...
    def predict(self, steps: int | None = None) -> dict[str, Any]: ...
    @overload
    def export(self, path: None = None, *, format: str, steps: int | None = None,
               seed: int | None = None, threads: int = 0, memory_limit: Size | None = None,
               environment: Environment | None = None, random: Random | None = None,
               notes: list[Diagnostic] | None = None, size: int | tuple[int, int] | None = None, width: int | None = None,
               height: int | None = None, line_width: float | None = None,
               margin: float | None = None, background: Colour | None = None,
               line_color: Colour | None = None, fill_color: Colour | None = None,
               view: str | None = None, viewpoint: Vector | None = None,
               target: Vector | None = None, up: Vector | None = None,
               light: Vector | None = None, field_of_view: float | None = None,
               samples_per_pixel: int | None = None, ground: bool | None = None,
               quality: str | int | None = None, tube_sides: int | None = None,
               surface_divisions: int | None = None, spline: int | None = None,
               spline_path: bool | None = None, kolam_dots: bool | None = None,
               derivation_diagram: bool | None = None, glb_instancing: bool | None = None,
               glb_compression: bool | None = None, first: int | None = None,
               last: int | None = None, frames_per_step: int | None = None,
               fps: float | None = None, hold_seconds: float | None = None,
               turntable_degrees: float | None = None, stream: bool | None = None,
               stream_limit: int | None = None, source_file: str | None = None) -> bytes: ...
    @overload
    def export(self, path: PathLike, *, format: str | None = None, **options: Any) -> None: ...
    def with_defines(self, defines: Mapping[str, Define]) -> Model: ...
    def _repr_svg_(self) -> str | None: ...
    def _repr_png_(self) -> bytes | None: ...

class ModuleString:
    """A derived string: str() as `graftal derive` prints it; NumPy views, no copy."""
    steps: int
    symbols: npt.NDArray[np.uint8]
    parameter_offsets: npt.NDArray[np.uint32]
    parameters: Union[npt.NDArray[np.float32], npt.NDArray[np.float64]]
    model: Model
    derive_keywords: dict[str, Any]
    def __len__(self) -> int: ...
    def __getitem__(self, index: int) -> tuple[str, tuple[float, ...]]: ...
    def __buffer__(self, flags: int) -> memoryview: ...
    def symbol_counts(self) -> dict[str, int]: ...
    def scene(self) -> Scene: ...
    def _repr_svg_(self) -> str | None: ...
    def _repr_png_(self) -> bytes | None: ...

class Derivation(Iterator[ModuleString]):
    """A derivation step by step: yields the strings of steps 0 (the axiom) to `steps`."""
    current: ModuleString
    steps_done: int
    steps: int
    def __next__(self) -> ModuleString: ...
    def step(self) -> None: ...

class Scene:
    """What the turtle drew, in model units."""
    segments: npt.NDArray[np.float64]  # (n, 2, 3)
    widths: npt.NDArray[np.float32]
    colors: npt.NDArray[np.uint16]
    segment_rgb: npt.NDArray[np.float32]  # (n, 3)
    polygon_vertices: npt.NDArray[np.float64]  # (m, 3)
    polygon_offsets: npt.NDArray[np.uint32]
    polygon_colors: npt.NDArray[np.uint16]
    palette: npt.NDArray[np.float32]  # (c, 3)
    is_3d: bool
    bounds: tuple[Vector, Vector] | None
    steps: int
    surfaces: int
    model: Model
    derive_keywords: dict[str, Any]
    def mesh(self, tube_sides: int = 8) -> Mesh: ...
    def _repr_svg_(self) -> str | None: ...
    def _repr_png_(self) -> bytes | None: ...

class Mesh:
    """One triangle mesh."""
    vertices: npt.NDArray[np.float32]  # (v, 3)
    normals: npt.NDArray[np.float32]  # (v, 3)
    indices: npt.NDArray[np.uint32]  # (t, 3)
    triangles: npt.NDArray[np.float32]  # (t, 3, 3)
    triangle_colors: npt.NDArray[np.uint16]
    palette: npt.NDArray[np.float32]

class Viewer:
    """graftal.show()'s 3D view (a map's flat SVG), displayed by Jupyter."""
    glb: bytes | None
    svg: bytes | None
    height: int
    def html(self) -> str: ...
    def _repr_html_(self) -> str: ...

class Map:
    """A derived map L-system: str() is the cells as `graftal derive` prints them."""
    steps: int
    vertices: int
    edges: int
    cells: int
    positions: npt.NDArray[np.float64]  # (vertices, 3)
    def statistics(self) -> dict[str, Any]: ...

class MapModel:
    """A map L-system (the book's chapter 5), read by graftal.load or graftal.parse."""
    file: str
    derivation_length: int
    overrides: dict[str, str]
    warnings: list[Diagnostic]
    def derive(self, steps: int | None = None, *, threads: int = 0, geometry: str = "siero",
               outline: str = "growing") -> Map: ...
    def statistics(self, steps: int | None = None, *, threads: int = 0,
                   geometry: str = "siero", outline: str = "growing") -> dict[str, Any]: ...
    def export(self, path: PathLike | None = None, *, format: str | None = None,
               steps: int | None = None, threads: int = 0, geometry: str = "siero",
               outline: str = "growing", fill: str = "none", uniform_width: bool = False,
               **options: Any) -> bytes | None: ...
    def with_defines(self, defines: Mapping[str, Define]) -> MapModel: ...

def load(path: PathLike, *, defines: Mapping[str, Define] | None = None,
         view: PathLike | None = None, functions: Functions | None = None,
         random: Random | None = None) -> Model | MapModel: ...
def parse(text: str, *, file: str = "", defines: Mapping[str, Define] | None = None,
          view_text: str | None = None, view_file: str = "", functions: Functions | None = None,
          random: Random | None = None) -> Model | MapModel: ...
def export_formats() -> list[dict[str, Any]]: ...
def picture(obj: Model | ModuleString | Scene, format: str = "svg", size: int = 400,
            **options: Any) -> bytes: ...
def show(obj: Model | MapModel | ModuleString | Scene, height: int = 480,
         **options: Any) -> Viewer: ...
def sweep(model: Model | MapModel | PathLike, grid: Mapping[str, Any] | Sequence[Mapping[str, Any]],
          client: Any = None, *, steps: int | None = None, geometry: bool = True,
          export: str | None = None, size: int = 256, meshes: bool = False,
          tube_sides: int = 8, threads: int = 1,
          memory_limit: Size | None = None) -> pandas.DataFrame: ...
