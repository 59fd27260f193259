#!/usr/bin/python3
"""The Python module's benchmark (bench/run.sh runs it as the row `python`; not in the table).

  python_bench.py BUILD_DIR [--steps 20] [--points 100] [--sweep-steps 14]

1. Deriving Honda's tree n=STEPS: the whole /usr/bin/python3 process (import, load,
   derive) against the whole `graftal` process doing the same work (`stats --no-geometry`
   against Model.statistics(geometry=False), and `derive > /dev/null` against derive()).
2. Reading the parameters as a NumPy array makes no copy: the peak RSS of a process that
   derives and sums model.derive().parameters against one that only derives.
3. A sweep of POINTS derivations on a LocalCluster of two worker processes against the same
   derivations one after the other in one process, divided by two.

Prints one line per measure and writes them as JSON to BUILD_DIR/bench/results/python.json.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
HONDA = ROOT / "examples" / "honda-monopodial-tree.l"


def timed(command, env=None):
    """Wall seconds and peak RSS (MiB) of one process (its own, from wait4)."""
    start = time.perf_counter()
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(process.pid, 0)
    seconds = time.perf_counter() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode:
        raise subprocess.CalledProcessError(process.returncode, command)
    return seconds, usage.ru_maxrss / 1024


def best(command, runs, env=None):
    results = [timed(command, env) for _ in range(runs)]
    return min(r[0] for r in results), max(r[1] for r in results)


def python(code):
    return [sys.executable, "-c", code]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build", type=pathlib.Path)
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--points", type=int, default=100)
    parser.add_argument("--sweep-steps", type=int, default=14)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    build = args.build.resolve()
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    graftal_exe = str(build / "graftal")
    n = str(args.steps)
    report = {}

    # 1. The same derivation from the command and from Python, whole processes.
    cli_stats, _ = best([graftal_exe, "stats", str(HONDA), "-n", n, "--no-geometry", "-q"],
                        args.runs)
    py_stats, _ = best(python(f"import graftal; graftal.load({str(HONDA)!r})"
                              f".statistics({n}, geometry=False)"), args.runs, env)
    cli_derive, _ = best([graftal_exe, "derive", str(HONDA), "-n", n, "-q"], args.runs)
    # NumPy is imported in both, so that the peak RSS below compares the arrays alone.
    py_derive, rss_derive = best(python(f"import numpy, graftal; graftal.load({str(HONDA)!r})"
                                        f".derive({n})"), args.runs, env)
    report["stats_cli_s"], report["stats_python_s"] = cli_stats, py_stats
    report["derive_cli_s"], report["derive_python_s"] = cli_derive, py_derive
    print(f"python bench: Honda n={n} counted: graftal stats {cli_stats:.3f} s, Python "
          f"{py_stats:.3f} s ({py_stats / cli_stats:.2f}x); derived: graftal derive > /dev/null "
          f"{cli_derive:.3f} s, Python derive() {py_derive:.3f} s ({py_derive / cli_derive:.2f}x)")

    # 2. No copy: summing the parameters through the NumPy view adds no memory.
    _, rss_view = best(python(f"import numpy, graftal; s = graftal.load({str(HONDA)!r})"
                              f".derive({n}); p = s.parameters; print(float(p.sum()))"),
                       args.runs, env)
    report["rss_derive_mib"], report["rss_view_mib"] = rss_derive, rss_view
    print(f"python bench: peak RSS derive() {rss_derive:.0f} MiB, with the parameters read "
          f"as NumPy {rss_view:.0f} MiB ({rss_view / rss_derive:.3f}x)")

    # 3. A sweep on two worker processes against one process, one point after the other.
    sweep = (
        "import sys, time, graftal\n"
        "from distributed import Client, LocalCluster\n"
        f"model = graftal.load({str(HONDA)!r})\n"
        f"grid = {{'R2': [0.5 + 0.4 * k / {args.points} for k in range({args.points})]}}\n"
        f"t = time.perf_counter(); graftal.sweep(model, grid, steps={args.sweep_steps})\n"
        "serial = time.perf_counter() - t\n"
        "with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as c, "
        "Client(c) as client:\n"
        f"    graftal.sweep(model, {{'R2': [0.6, 0.7]}}, client, steps=2)  # workers warm\n"
        "    t = time.perf_counter()\n"
        f"    graftal.sweep(model, grid, client, steps={args.sweep_steps})\n"
        "    parallel = time.perf_counter() - t\n"
        "print(serial, parallel)\n")
    out = subprocess.run([sys.executable, "-c", sweep], env=env, check=True,
                         capture_output=True, text=True).stdout.split()
    serial, parallel = float(out[-2]), float(out[-1])
    report["sweep_serial_s"], report["sweep_two_workers_s"] = serial, parallel
    print(f"python bench: {args.points}-point sweep (n={args.sweep_steps}): one process "
          f"{serial:.2f} s, two workers {parallel:.2f} s ({parallel / (serial / 2):.2f}x "
          f"the serial time halved)")

    results = build / "bench" / "results"
    results.mkdir(parents=True, exist_ok=True)
    (results / "python.json").write_text(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
