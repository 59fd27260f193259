#!/usr/bin/python3
"""The Python module's benchmark (bench/run.sh runs it as the row `python`; not in the table).

  python_bench.py BUILD_DIR [--steps 20] [--points 100] [--sweep-steps 14]

1. Deriving Honda's tree n=STEPS: the whole /usr/bin/python3 process (import, load,
   derive) against the whole `graftal` process doing the same work (`stats --no-geometry`
   against Model.statistics(geometry=False), and `derive > /dev/null` against derive(),
   which is also timed with NumPy imported first, as the peak RSS runs do).
2. Reading the parameters as a NumPy array makes no copy: the peak RSS of a process that
   derives and sums model.derive().parameters against one that only derives.
3. A sweep of POINTS derivations on a LocalCluster of two worker processes against the same
   derivations one after the other in one process, divided by two; and, as the floor under
   it, the same derivations in two plain processes side by side, half each, and each core's
   own speed (a VM's two virtual CPUs need not run at the same speed). In RUNS rounds, the
   ratios taken within each round.

Prints one line per measure and writes them as JSON to BUILD_DIR/bench/results/python.json.
Each time is given as wall seconds and as CPU seconds (user + system, every thread): on a
shared, loaded machine the wall times measure the other users as much as graftal, while the
CPU times still compare the work done. The load average is printed with them.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
HONDA = ROOT / "examples" / "honda-monopodial-tree.l"


def timed(command, env=None):
    """Wall seconds, peak RSS (MiB) and CPU seconds of one process (its own, from wait4)."""
    start = time.perf_counter()
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(process.pid, 0)
    seconds = time.perf_counter() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode:
        raise subprocess.CalledProcessError(process.returncode, command)
    return seconds, usage.ru_maxrss / 1024, usage.ru_utime + usage.ru_stime


def best(command, runs, env=None):
    """The least wall and CPU seconds of `runs` runs, and the largest peak RSS."""
    results = [timed(command, env) for _ in range(runs)]
    return (min(r[0] for r in results), max(r[1] for r in results),
            min(r[2] for r in results))


def load():
    return "load average " + " ".join(f"{v:.1f}" for v in os.getloadavg())


def python(code):
    return [sys.executable, "-c", code]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build", type=pathlib.Path)
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--points", type=int, default=100)
    parser.add_argument("--sweep-steps", type=int, default=14)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    build = args.build.resolve()
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    graftal_exe = str(build / "graftal")
    n = str(args.steps)
    report = {}

    # 1. The same derivation from the command and from Python, whole processes.
    honda = repr(str(HONDA))
    cli_stats, _, cli_stats_cpu = best(
        [graftal_exe, "stats", str(HONDA), "-n", n, "--no-geometry", "-q"], args.runs)
    py_stats, _, py_stats_cpu = best(
        python(f"import graftal; graftal.load({honda}).statistics({n}, geometry=False)"),
        args.runs, env)
    cli_derive, _, cli_derive_cpu = best([graftal_exe, "derive", str(HONDA), "-n", n, "-q"],
                                         args.runs)
    # Deriving needs no NumPy (graftal imports it with the first array): the script imports
    # what a script that derives needs. The peak RSS below imports NumPy in both of its runs,
    # so that it compares the arrays alone; its derive-only run's time is printed too.
    py_derive, _, py_derive_cpu = best(
        python(f"import graftal; graftal.load({honda}).derive({n})"), args.runs, env)
    py_numpy, rss_derive, py_numpy_cpu = best(
        python(f"import numpy, graftal; graftal.load({honda}).derive({n})"), args.runs, env)
    report["stats_cli_s"], report["stats_python_s"] = cli_stats, py_stats
    report["derive_cli_s"], report["derive_python_s"] = cli_derive, py_derive
    report["derive_python_with_numpy_s"] = py_numpy
    cpu = {"stats_cli": cli_stats_cpu, "stats_python": py_stats_cpu,
           "derive_cli": cli_derive_cpu, "derive_python": py_derive_cpu,
           "derive_python_with_numpy": py_numpy_cpu}
    for k, v in cpu.items():
        report[k + "_cpu_s"] = v
    report["load"] = os.getloadavg()
    print(f"python bench ({load()}): Honda n={n} counted: graftal stats {cli_stats:.3f} s, "
          f"Python {py_stats:.3f} s ({py_stats / cli_stats:.2f}x); derived: graftal derive > "
          f"/dev/null {cli_derive:.3f} s, Python derive() {py_derive:.3f} s "
          f"({py_derive / cli_derive:.2f}x)")
    print(f"python bench: the same in CPU seconds: stats {cpu['stats_cli']:.3f} against "
          f"{cpu['stats_python']:.3f} ({cpu['stats_python'] / cpu['stats_cli']:.2f}x); derive "
          f"{cpu['derive_cli']:.3f} against {cpu['derive_python']:.3f} "
          f"({cpu['derive_python'] / cpu['derive_cli']:.2f}x)")
    print(f"python bench: derive() with NumPy imported too: {py_numpy:.3f} s "
          f"({py_numpy / cli_derive:.2f}x), {py_numpy_cpu:.3f} CPU s")

    # 2. No copy: summing the parameters through the NumPy view adds no memory.
    _, rss_view, _ = best(python(f"import numpy, graftal; s = graftal.load({honda})"
                                 f".derive({n}); p = s.parameters; print(float(p.sum()))"),
                          args.runs, env)
    report["rss_derive_mib"], report["rss_view_mib"] = rss_derive, rss_view
    print(f"python bench: peak RSS derive() {rss_derive:.0f} MiB, with the parameters read "
          f"as NumPy {rss_view:.0f} MiB ({rss_view / rss_derive:.3f}x)")

    # 3. A sweep on two worker processes against one process, one point after the other, in
    # rounds. Each round also runs, as the floor under the sweep, the same points in two
    # plain processes side by side (half each, both starting at one instant; the time is
    # until the later one ends), and measures each core's own speed (a plain loop pinned to
    # each CPU in turn). On a VM whose virtual CPUs share host cores with other guests, one
    # core can run at half the speed of the other for seconds at a time: two workers then
    # cannot finish in half the time of one. Ratios are taken within a round, whose runs
    # meet the same host, and their medians printed. CPU seconds: the serial run's own, and
    # the busier worker's (client.run asks them).
    sweep = (
        "import os, resource, statistics, subprocess, sys, time, graftal\n"
        "from distributed import Client, LocalCluster\n"
        "HALF, SPIN = sys.argv[1], sys.argv[2]\n"
        "def cpu():\n"
        "    r = resource.getrusage(resource.RUSAGE_SELF)\n"
        "    return r.ru_utime + r.ru_stime\n"
        "def pair():\n"
        "    start = time.time() + 1.0\n"
        "    both = [subprocess.Popen([sys.executable, '-c', HALF, str(k), repr(start)],\n"
        "                             stdout=subprocess.PIPE, text=True) for k in (0, 1)]\n"
        "    return max(float(p.communicate()[0].split()[-1]) for p in both)\n"
        "def share():\n"
        "    cores = sorted(os.sched_getaffinity(0))[:2]\n"
        "    if len(cores) < 2: return 1.0\n"
        "    t = [float(subprocess.run(['taskset', '-c', str(c), sys.executable, '-c', SPIN],\n"
        "         capture_output=True, text=True, check=True).stdout) for c in cores]\n"
        "    return min(t) / max(t)\n"
        "def main():\n"
        f"    model = graftal.load({str(HONDA)!r})\n"
        f"    grid = {{'R2': [0.5 + 0.4 * k / {args.points} for k in range({args.points})]}}\n"
        "    rounds = []\n"
        "    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as c, "
        "Client(c) as client:\n"
        f"        graftal.sweep(model, {{'R2': [0.6, 0.7]}}, client, steps=2)  # workers warm\n"
        f"        for _ in range({args.runs}):\n"
        "            c0 = cpu(); t = time.perf_counter()\n"
        f"            graftal.sweep(model, grid, steps={args.sweep_steps})\n"
        "            serial = time.perf_counter() - t; serial_cpu = cpu() - c0\n"
        "            w0 = client.run(cpu); t = time.perf_counter()\n"
        f"            graftal.sweep(model, grid, client, steps={args.sweep_steps})\n"
        "            parallel = time.perf_counter() - t; w1 = client.run(cpu)\n"
        "            busiest = max(w1[w] - w0[w] for w in w1)\n"
        "            rounds.append((serial, parallel, serial_cpu, busiest, pair(), share()))\n"
        "    for r in rounds: print(*r)\n"
        "if __name__ == '__main__':\n"
        "    main()\n")
    half = (
        "import sys, time, graftal\n"
        "from graftal import _sweep\n"
        f"model = graftal.load({str(HONDA)!r})\n"
        f"points = [{{'R2': 0.5 + 0.4 * k / {args.points}}} for k in range({args.points})]\n"
        f"_sweep.run_points(model, points[:1], steps={args.sweep_steps})  # warm\n"
        "start = float(sys.argv[2])\n"
        "while time.time() < start: time.sleep(0.001)\n"
        f"_sweep.run_points(model, points[int(sys.argv[1])::2], steps={args.sweep_steps})\n"
        "print(time.time() - start)\n")
    spin = ("import time\nt = time.perf_counter()\nx = 0\nfor i in range(2_000_000): x += i\n"
            "print(time.perf_counter() - t)\n")
    out = subprocess.run([sys.executable, "-c", sweep, half, spin], env=env, check=True,
                         capture_output=True, text=True).stdout.strip().splitlines()
    rounds = [tuple(map(float, line.split())) for line in out[-args.runs:]]
    m = statistics.median
    serial, parallel = m(r[0] for r in rounds), m(r[1] for r in rounds)
    serial_cpu, busiest = m(r[2] for r in rounds), m(r[3] for r in rounds)
    side, slower = m(r[4] for r in rounds), m(r[5] for r in rounds)
    ratio = m(r[1] / (r[0] / 2) for r in rounds)
    side_ratio = m(r[4] / (r[0] / 2) for r in rounds)
    over_side = m(r[1] / r[4] for r in rounds)
    # With the slower core at share s of the faster, two workers give 1 + s times one.
    ideal = m(2 / (1 + r[5]) for r in rounds)
    report["sweep_rounds"] = rounds
    report["sweep_serial_s"], report["sweep_two_workers_s"] = serial, parallel
    report["sweep_serial_cpu_s"], report["sweep_busiest_worker_cpu_s"] = serial_cpu, busiest
    report["sweep_ratio"], report["two_processes_side_by_side_s"] = ratio, side
    report["two_processes_ratio"], report["sweep_over_two_processes"] = side_ratio, over_side
    report["slower_core_share"], report["best_possible_sweep_ratio"] = slower, ideal
    print(f"python bench ({load()}): {args.points}-point sweep (n={args.sweep_steps}): one "
          f"process {serial:.2f} s, two workers {parallel:.2f} s ({ratio:.2f}x the serial time "
          f"halved; medians of {args.runs} rounds, the ratio taken within each round)")
    print(f"python bench: in CPU seconds: one process {serial_cpu:.2f}, the busier worker "
          f"{busiest:.2f} ({busiest / (serial_cpu / 2):.2f}x the serial CPU halved)")
    print(f"python bench: the same halves in two plain processes side by side: {side:.2f} s "
          f"({side_ratio:.2f}x the serial time halved); the sweep on Dask takes {over_side:.2f}x "
          f"that. The slower core ran at {slower:.2f} of the faster one's speed, so two workers "
          f"could at best take {ideal:.2f}x the serial time halved")

    results = build / "bench" / "results"
    results.mkdir(parents=True, exist_ok=True)
    (results / "python.json").write_text(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
