#!/usr/bin/env python3
"""Start-up: every command on small models, graftal and cpfg interleaved.

    bench/startup_versus_cpfg.py --graftal BUILD/graftal --cpfg DEST/bin/cpfg --results DIR
                                 [--runs 15] [--doc docs/performance.md]

Called by bench/run.sh when CPFG is set (row key `startup`). The models: the book's
Fibonacci words (examples/fig1.3-fibonacci.l) and the bench's Koch island at n = 3 (a copy
of bench/cpfg/koch-island.l with its derivation length set to 3, and its view file). Each
command runs RUNS times, the commands interleaved (one run of each, then the next round),
each run a whole process. Wall and CPU time come from wait4(); the peak RSS from
/usr/bin/time, whose small process forks the command: a child of this Python process would
report the interpreter's own pages as its peak, since the kernel keeps the larger peak
across exec.

Targets (issue "every command at memory speed"): each command ≤ 15 ms and ≤ 12 MiB, and
graftal at least 3× faster than cpfg on the same model (graftal's slowest command on
Koch n = 3 but the PNG against cpfg's faster mode). The table goes to DIR/startup.md and,
with --doc, between <!-- startup:begin --> and <!-- startup:end --> in the doc.
"""

from __future__ import annotations

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from report import fmt_time, loadavg, replace_between_markers  # noqa: E402
from versus_cpfg import cpfg_missing, side_by_side_arguments  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
WALL_TARGET = 0.015
RSS_TARGET_MIB = 12
SPEEDUP_TARGET = 3


def run_once(argv: list[str], env: dict) -> tuple[float, float, float]:
    """Wall s, CPU s (wait4 of /usr/bin/time: its child's time is in it) and peak RSS MiB."""
    with tempfile.NamedTemporaryFile("r", suffix=".rss") as rss:
        t0 = time.perf_counter()
        proc = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", rss.name] + argv,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        if os.waitstatus_to_exitcode(status) != 0:
            raise RuntimeError(f"{' '.join(argv)} failed")
        peak = int(rss.read().split()[-1]) / 1024
    # /usr/bin/time's own start is in both times: taken off below.
    return wall, usage.ru_utime + usage.ru_stime, peak


def commands(graftal: str, cpfg: str, work: Path) -> list[tuple[str, str, list[str]]]:
    """(side, what, argv) for every command."""
    fib = str(ROOT / "examples" / "fig1.3-fibonacci.l")
    source = (HERE / "cpfg" / "koch-island.l").read_text()
    koch = work / "koch3.l"
    koch.write_text(re.sub(r"(?im)^(derivation length:\s*)\d+", r"\g<1>3", source))
    view = work / "koch3.v"
    view.write_text((HERE / "cpfg" / "koch-island.v").read_text())
    grey = work / "grey.map"
    grey.write_bytes(bytes(b for i in range(256) for b in (i, i, i)))
    k, v = str(koch), str(view)
    return [
        ("graftal", "`graftal --version`", [graftal, "--version"]),
        ("graftal", "`graftal derive fig1.3-fibonacci.l`", [graftal, "derive", fib]),
        ("graftal", "`graftal stats fig1.3-fibonacci.l`", [graftal, "stats", fib]),
        ("graftal", "`graftal derive koch3.l koch3.v`", [graftal, "derive", k, v]),
        ("graftal", "`graftal stats koch3.l koch3.v`", [graftal, "stats", k, v]),
        ("graftal", "`graftal render koch3.l koch3.v -o k3.svg`",
         [graftal, "render", k, v, "-o", str(work / "k3.svg"), "--quiet"]),
        ("png", "`graftal render koch3.l koch3.v -o k3.png` (800 × 800)",
         [graftal, "render", k, v, "-o", str(work / "k3.png"), "--quiet"]),
        ("cpfg", "`cpfg -g -m grey.map -str k3.str koch3.l koch3.v`",
         [cpfg, "-g", "-m", str(grey), "-str", str(work / "k3.str"), k, v]),
        ("cpfg", "`cpfg -g -m grey.map koch3.l koch3.v`", [cpfg, "-g", "-m", str(grey), k, v]),
    ]


def main() -> int:
    args = side_by_side_arguments(__doc__, 15).parse_args()
    if cpfg_missing(args.cpfg):
        return 2
    results = Path(args.results)
    results.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ)
    env["PATH"] = str(Path(args.cpfg).resolve().parent) + os.pathsep + env.get("PATH", "")
    env.setdefault("QT_QPA_PLATFORM", "offscreen")
    load_before = loadavg().split()[0]
    with tempfile.TemporaryDirectory(prefix="startup-", dir=results) as tmp:
        rows = commands(args.graftal, args.cpfg, Path(tmp))
        # What /usr/bin/time adds: its own start, measured with /bin/true (less what
        # /bin/true itself takes, a few hundred microseconds: the floor is a little high).
        true = [run_once(["/bin/true"], env) for _ in range(args.runs)]
        floor = statistics.median(r[0] for r in true)
        floor_cpu = statistics.median(r[1] for r in true)
        runs: list[list[tuple[float, float, float]]] = [[] for _ in rows]
        for _ in range(args.runs):
            for i, (_, _, argv) in enumerate(rows):
                runs[i].append(run_once(argv, env))
        # cpfg finds its preprocessor, vlabcpp, on the PATH; without it cpfg still exits 0,
        # having read nothing, and sooner. Its string must be there.
        written = Path(tmp) / "k3.str"
        if not written.exists() or written.stat().st_size == 0:
            print("bench: cpfg wrote no string (is vlabcpp beside it?)", file=sys.stderr)
            return 1
    load_after = loadavg().split()[0]
    med = [(max(statistics.median(r[0] for r in rs) - floor, 1e-6),
            max(statistics.median(r[1] for r in rs) - floor_cpu, 1e-6),
            max(r[2] for r in rs)) for rs in runs]
    slowest = max(m[0] for (side, _, _), m in zip(rows, med) if side == "graftal")
    cpfg_fastest = min(m[0] for (side, _, _), m in zip(rows, med) if side == "cpfg")
    lines = ["| command | wall | CPU | peak RSS | ≤ 15 ms and ≤ 12 MiB |",
             "| --- | --- | --- | --- | --- |"]
    for (side, what, _), (wall, cpu, rss) in zip(rows, med):
        met = "—" if side == "cpfg" else (
            "yes" if wall <= WALL_TARGET and rss <= RSS_TARGET_MIB else "no")
        lines.append(f"| {what} | {fmt_time(wall)} | {fmt_time(cpu)} | {rss:.1f} MiB | {met} |")
    ratio = cpfg_fastest / slowest
    lines += ["", f"At least {SPEEDUP_TARGET}× faster than cpfg (graftal's slowest command but "
              f"the PNG, {fmt_time(slowest)}, against cpfg's faster, {fmt_time(cpfg_fastest)}): "
              f"{ratio:.2f}×, {'met' if ratio >= SPEEDUP_TARGET else 'missed'}.", "",
              f"Measured {time.strftime('%Y-%m-%d %H:%M %Z')}, {os.cpu_count()} cores, load "
              f"(1 min) {load_before} before and {load_after} after; medians of {args.runs} "
              f"whole-process runs, the commands interleaved, less /usr/bin/time's own start "
              f"({fmt_time(floor)} wall, {fmt_time(floor_cpu)} CPU: the medians of /bin/true "
              f"through it); peak RSS the largest "
              f"of the runs. Commands: [bench/startup_versus_cpfg.py]"
              f"(../bench/startup_versus_cpfg.py)."]
    md = "\n".join(lines)
    (results / "startup.md").write_text(md + "\n")
    print(md)
    if args.doc:
        if not replace_between_markers(Path(args.doc), "startup", md):
            print(f"bench: {args.doc} has no startup markers; the table is left in the results",
                  file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
