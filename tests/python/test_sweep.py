"""graftal.sweep(): a grid of #define values and seeds, one derivation per point, gathered
into a pandas DataFrame; here and on a real dask.distributed LocalCluster of two worker
processes, with the same rows."""
import pandas
import pytest

import graftal

HONDA = "examples/honda-monopodial-tree.l"


def test_sweep_here(root, cli):
    honda = graftal.load(root / HONDA)
    frame = graftal.sweep(honda, {"R2": [0.6, 0.8], "A0": [30, 45]}, steps=5)
    assert isinstance(frame, pandas.DataFrame) and len(frame) == 4
    assert list(frame.columns[:2]) == ["R2", "A0"]
    assert frame[["R2", "A0"]].values.tolist() == [[0.6, 30], [0.6, 45], [0.8, 30], [0.8, 45]]
    # Each row is what `graftal stats` says of that point.
    import json
    stats = json.loads(cli("stats", HONDA, "-n", 5, "-D", "R2=0.8", "-D", "A0=45"))
    row = frame.iloc[3]
    assert row["modules"] == stats["modules"] and row["segments"] == stats["segments"]
    assert row["max_y"] == pytest.approx(stats["bbox"]["max"][1])
    assert frame["segments"].nunique() == 1  # the constants change shapes, not counts


def test_sweep_on_a_local_cluster(root):
    distributed = pytest.importorskip("distributed")
    bush = graftal.load(root / "examples/fig3.16-stochastic-bush.l")
    grid = {"seed": range(6)}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        remote = graftal.sweep(bush, grid, client, steps=4, export="png", size=32)
    here = graftal.sweep(bush, grid, steps=4)
    assert remote["seed"].tolist() == list(range(6))
    assert remote["modules"].tolist() == here["modules"].tolist()
    assert remote["modules"].nunique() > 1  # stochastic: the seeds grow different bushes
    assert all(png.startswith(b"\x89PNG") for png in remote["png"])


def test_batches_deal_runs_of_shared_constants_round_the_tasks():
    from graftal import _sweep

    class TwoThreads:
        def nthreads(self):
            return {"w1": 1, "w2": 1}

    points = _sweep.grid_points({"R2": [0.5 + k / 100 for k in range(40)], "seed": range(3)})
    batches = _sweep._batches(points, TwoThreads())
    assert len(batches) == 4  # two a worker thread
    assert sorted(i for b in batches for i in b) == list(range(len(points)))
    # The seeds of one plant stay in one task: each task reads each of its models once.
    for batch in batches:
        keys = [_sweep._constants(points[i]) for i in batch]
        assert len(set(keys)) == len(keys) // 3
    # The grid's last (say, most expensive) quarter is shared by every task.
    last = set(range(len(points) * 3 // 4, len(points)))
    assert all(len(last.intersection(b)) >= 6 for b in batches)
