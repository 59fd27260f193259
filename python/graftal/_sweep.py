"""graftal.sweep(): one derivation per point of a grid of #define values and seeds, run on a
dask.distributed client (or here, one after the other, without one), gathered into a pandas
DataFrame of the statistics `graftal stats` reports (Model.statistics, the pipeline's
measured()) and, on request, exported pictures or meshes.

Dask schedules the work: a LocalCluster on this machine, or a scheduler with workers on
other machines (dask-jobqueue, Kubernetes); docs/python.md shows both. A Model travels to
the workers as its source (it pickles as the file's path or the text, with its overrides),
and every worker reads it again with the point's constants.
"""
import itertools
import time

from . import _graftal

#: The statistics columns every row has, after the point's own values.
COLUMNS = ["steps", "modules", "segments", "polygons", "min_x", "min_y", "min_z", "max_x",
           "max_y", "max_z", "seconds"]
#: A map L-system's columns (graftal.MapModel.statistics()).
MAP_COLUMNS = ["steps", "cells", "edges", "vertices", "min_x", "min_y", "min_z", "max_x",
               "max_y", "max_z", "seconds"]


def grid_points(grid):
    """The points of a grid: a dict of name -> values (every combination, in order) or an
    iterable of dicts (the points themselves). A name 'seed' sets the derivation's seed;
    every other name is a #define."""
    if isinstance(grid, dict):
        names = list(grid)
        values = [[v] if isinstance(v, str) or not hasattr(v, "__iter__") else list(v)
                  for v in (grid[n] for n in names)]
        return [dict(zip(names, combination)) for combination in itertools.product(*values)]
    points = [dict(p) for p in grid]
    if not all(isinstance(p, dict) for p in points):
        raise TypeError("grid: expected a dict of name -> values, or a list of dicts")
    return points


def _plain(value):
    """A point's value as Python's own type (NumPy scalars print as numbers in defines)."""
    return value.item() if hasattr(value, "item") else value


def mesh_arrays(mesh):
    """A Mesh as a dict of NumPy arrays (what travels back from a worker): vertices,
    normals, indices, triangle_rgb (each triangle's colour, 0 to 1)."""
    return {"vertices": mesh.vertices, "normals": mesh.normals, "indices": mesh.indices,
            "triangle_rgb": mesh.palette[mesh.triangle_colors % max(len(mesh.palette), 1)]}


def _map_row(model, point, steps, export, size, threads, meshes):
    """A map L-system's row: what `graftal stats` counts of the map, and its picture."""
    if "seed" in point:
        raise ValueError("sweep: a map L-system draws no random numbers: 'seed' does not apply")
    if meshes:
        raise ValueError("sweep: a map L-system is drawn flat: meshes=True does not apply")
    stats = model.statistics(steps, threads=threads)
    row = dict(point)
    for name in ("steps", "cells", "edges", "vertices"):
        row[name] = stats[name]
    for axis, (lo, hi) in zip("xyz", zip(*stats["bounds"])):
        row["min_" + axis] = lo
        row["max_" + axis] = hi
    row["cell_sides"] = stats["cell_sides"]
    if export:
        options = {"format": export, "steps": steps, "threads": threads}
        if export in ("png", "svg", "pdf"):
            options["size"] = (size, size)
        row[export] = model.export(**options)
    return row


def run_point(model, point, steps=None, geometry=True, export=None, size=256, threads=1,
              memory_limit=None, meshes=False, tube_sides=8, _read=None):
    """One point of a sweep: the model read with the point's constants, derived with its
    seed, and measured (and exported when `export` names a format). Returns the row.
    A map L-system (graftal.MapModel) gives its cells, edges and vertices instead."""
    point = {k: _plain(v) for k, v in point.items()}
    defines = {k: v for k, v in point.items() if k != "seed"}
    seed = point.get("seed")
    start = time.perf_counter()
    m = (_read or _with_defines)(model, defines)
    if isinstance(m, _graftal.MapModel):
        row = _map_row(m, point, steps, export, size, threads, meshes)
        row["seconds"] = time.perf_counter() - start
        return row
    stats = m.statistics(steps, seed=seed, threads=threads, memory_limit=memory_limit,
                         geometry=geometry)
    row = dict(point)
    row["steps"] = stats["steps"]
    row["modules"] = stats["modules"]
    row["segments"] = stats.get("segments")
    row["polygons"] = stats.get("polygons")
    bounds = stats.get("bounds") or ((None,) * 3, (None,) * 3)
    for axis, (lo, hi) in zip("xyz", zip(*bounds)):
        row["min_" + axis] = lo
        row["max_" + axis] = hi
    row["symbols"] = stats["symbols"]
    if export:
        options = {"format": export, "steps": steps, "seed": seed, "threads": threads}
        if export in ("png", "svg", "pdf"):
            options["size"] = (size, size)
        row[export] = m.export(**options)
    if meshes:
        scene = m.derive(steps, seed=seed, threads=threads, memory_limit=memory_limit).scene()
        row["mesh"] = mesh_arrays(scene.mesh(tube_sides))
    row["seconds"] = time.perf_counter() - start
    return row


def _with_defines(model, defines):
    return model.with_defines(defines) if defines else model


def run_points(model, points, **options):
    """Several points of a sweep in one task (run_point for each): a derivation of a few
    tens of milliseconds is shorter than what Dask spends on a task. Points with the same
    constants (seeds of one plant) read the model once."""
    read = {}

    def with_defines(model, defines):
        key = _constants(defines)
        if key not in read:
            if len(read) >= 64:  # a long serial sweep keeps a few models, not every one
                read.clear()
            read[key] = _with_defines(model, defines)
        return read[key]

    return [run_point(model, p, _read=with_defines, **options) for p in points]


def _constants(point):
    """What decides which model a point reads: its #define values (not its seed)."""
    return tuple(sorted((k, repr(v)) for k, v in point.items() if k != "seed"))


def _batches(points, client):
    """The points' indices, one list per task: two tasks per worker thread, since on a busy
    machine a task costs Dask tens of milliseconds. The grid is cut into short runs of
    consecutive points with the same constants (read once per task) and the runs are dealt
    round the tasks, so that points whose cost grows along the grid are shared evenly."""
    threads = sum(client.nthreads().values()) or 1
    count = min(len(points), 2 * threads)
    if count == 0:
        return []
    longest = max(1, len(points) // (8 * count))
    runs = []
    for i, point in enumerate(points):
        key = _constants(point)
        if runs and runs[-1][0] == key and len(runs[-1][1]) < longest:
            runs[-1][1].append(i)
        else:
            runs.append((key, [i]))
    batches = [[] for _ in range(count)]
    for r, (_, indices) in enumerate(runs):
        batches[r % count].extend(indices)
    return [b for b in batches if b]


def sweep(model, grid, client=None, *, steps=None, geometry=True, export=None, size=256,
          meshes=False, tube_sides=8, threads=1, memory_limit=None):
    """Derives `model` once per point of `grid` and returns a pandas DataFrame, one row per
    point in grid order: the point's values, then steps, modules, segments, polygons, the
    drawing's box (min_x ... max_z), symbols (counts per module name) and seconds.

    model   a graftal.Model, or the path of a model file or folder
    grid    {'R2': [0.6, 0.7], 'seed': range(4)} (every combination) or a list of points;
            'seed' sets the seed, other names #define constants
    client  a dask.distributed.Client: the points are tasks on its workers, two batches of
            points a worker thread (threads=1 per task, as the workers run tasks side by side);
            None runs here, in order
    export  a format name ('png', 'glb', ...): a column of that name holds each point's file
            as bytes (pictures size x size pixels)
    meshes  a column 'mesh' holds each point's mesh as NumPy arrays (see mesh_arrays),
            stems as tubes of tube_sides sides
    """
    import pandas

    if not isinstance(model, (_graftal.Model, _graftal.MapModel)):
        model = _graftal.load(model)
    points = grid_points(grid)
    options = dict(steps=steps, geometry=geometry, export=export, size=size, threads=threads,
                   memory_limit=memory_limit, meshes=meshes, tube_sides=tube_sides)
    if client is None:
        rows = run_points(model, points, **options)
    else:
        # A model pickles as its source (a path, or its text with its overrides): it goes
        # with each task, which costs less than scattering it first, a round trip to every
        # worker before any work starts. One map() is one message to the scheduler.
        batches = _batches(points, client)
        futures = client.map(run_points, [model] * len(batches),
                             [[points[i] for i in batch] for batch in batches], pure=False,
                             **options)
        rows = [None] * len(points)
        for batch, done in zip(batches, client.gather(futures)):
            for i, row in zip(batch, done):
                rows[i] = row
    frame = pandas.DataFrame(rows)
    names = list(points[0]) if points else []
    columns = MAP_COLUMNS if isinstance(model, _graftal.MapModel) else COLUMNS
    extra = [c for c in frame.columns if c not in names and c not in columns]
    return frame[names + [c for c in columns if c in frame.columns] + extra]


__all__ = ["sweep", "grid_points", "run_point", "run_points", "mesh_arrays"]
