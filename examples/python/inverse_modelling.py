"""Inverse modelling: recover two #define constants of a model from the statistics of a
plant it grew, with scipy.optimize evaluating the candidates through graftal.sweep().

A Honda tree (examples/honda-monopodial-tree.l) is grown with hidden values of R2 (the
branches' contraction) and A0 (the branching angle); only its measurements are kept: the
crown's extent along x and z and its box's corners, as `graftal stats` reports them. SciPy's
differential evolution then searches R2 and A0: each generation's candidates are one sweep,
which runs them side by side on Dask's workers when a scheduler is given.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/inverse_modelling.py
"""
import argparse
import pathlib

import numpy as np
from scipy.optimize import differential_evolution

import graftal

HONDA = pathlib.Path(__file__).resolve().parents[1] / "honda-monopodial-tree.l"
MEASURED = ["min_x", "max_x", "min_z", "max_z"]


def measurements(frame):
    return frame[MEASURED].to_numpy(dtype=float)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--r2", type=float, default=0.72, help="the hidden R2")
    parser.add_argument("--a0", type=float, default=38, help="the hidden A0")
    parser.add_argument("--steps", type=int, default=7)
    parser.add_argument("--generations", type=int, default=12)
    parser.add_argument("--scheduler", help="a running Dask scheduler's address")
    parser.add_argument("--check", action="store_true",
                        help="exit with status 1 unless both values are found")
    args = parser.parse_args()
    client = None
    if args.scheduler:
        from distributed import Client
        client = Client(args.scheduler)

    honda = graftal.load(HONDA)
    target = measurements(graftal.sweep(honda, [{"R2": args.r2, "A0": args.a0}],
                                        steps=args.steps))[0]
    evaluated = []

    def cost(rows):
        return np.sqrt((((rows - target) / np.abs(target).clip(1e-9)) ** 2).mean(axis=1))

    def generation(_, candidates):
        # SciPy hands over a whole generation; the sweep derives it at once.
        candidates = [list(c) for c in candidates]
        frame = graftal.sweep(honda, [{"R2": r2, "A0": a0} for r2, a0 in candidates], client,
                              steps=args.steps)
        costs = cost(measurements(frame))
        evaluated.extend(zip(candidates, costs))
        return costs

    result = differential_evolution(
        lambda x: 0.0, bounds=[(0.5, 0.9), (20, 60)], workers=generation,
        updating="deferred", popsize=8, maxiter=args.generations, tol=1e-8, seed=1,
        polish=False)
    r2, a0 = result.x
    print(f"hidden:    R2 = {args.r2:.3f}, A0 = {args.a0:.1f}")
    print(f"recovered: R2 = {r2:.3f}, A0 = {a0:.1f}  (relative error of the measurements "
          f"{result.fun:.2e}, {len(evaluated)} trees derived)")
    return not args.check or (abs(r2 - args.r2) < 0.02 and abs(a0 - args.a0) < 2)


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
