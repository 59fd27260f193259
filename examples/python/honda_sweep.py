"""A parameter sweep of Honda's tree (ABOP Fig 2.6, examples/honda-monopodial-tree.l),
plotted with matplotlib: the crown's width (x) and depth (z) for every pair of the branches'
contraction ratio R2 and branching angle A0 (the trunk, and so the height, does not change).

graftal.sweep() derives one tree per point; with --workers N it starts a Dask LocalCluster
of N worker processes, with --scheduler ADDRESS it uses a running cluster (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/honda_sweep.py honda.png
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # a file, no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import graftal  # noqa: E402

HONDA = pathlib.Path(__file__).resolve().parents[1] / "honda-monopodial-tree.l"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", help="the plot's file (.png, .svg, .pdf)")
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--workers", type=int, default=0, help="a LocalCluster of N workers")
    parser.add_argument("--scheduler", help="a running Dask scheduler's address")
    args = parser.parse_args()

    client = cluster = None
    if args.scheduler or args.workers:
        from distributed import Client, LocalCluster
        if not args.scheduler:
            cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                   dashboard_address=None)
        client = Client(args.scheduler or cluster)
    grid = {"R2": np.round(np.linspace(0.5, 0.9, 5), 2), "A0": [20, 30, 45, 60]}
    frame = graftal.sweep(HONDA, grid, client, steps=args.steps)
    if client:
        client.close()
    if cluster:
        cluster.close()

    frame["width"] = frame["max_x"] - frame["min_x"]
    frame["depth"] = frame["max_z"] - frame["min_z"]
    figure, (left, right) = plt.subplots(1, 2, figsize=(9, 3.6))
    for a0, rows in frame.groupby("A0"):
        left.plot(rows["R2"], rows["width"], marker="o", label=f"A0 = {a0}°")
        right.plot(rows["R2"], rows["depth"], marker="o", label=f"A0 = {a0}°")
    left.set(xlabel="R2 (branch contraction)", ylabel="crown width", title="Width")
    right.set(xlabel="R2 (branch contraction)", ylabel="crown depth", title="Depth")
    left.legend(fontsize=8)
    figure.suptitle(f"Honda's tree, {args.steps} steps: {len(frame)} trees, "
                    f"{frame['modules'].iloc[0]} modules each")
    figure.tight_layout()
    figure.savefig(args.output, dpi=100)
    print(frame[["R2", "A0", "modules", "width", "depth", "seconds"]].to_string(index=False))


if __name__ == "__main__":
    main()
