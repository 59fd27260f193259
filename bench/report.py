#!/usr/bin/env python3
"""Measure commands and format the benchmark table of bench/run.sh.

Two subcommands, both used by bench/run.sh:

  report.py measure --out FILE.json [--runs R] [--budget S] [--timeout T] -- CMD ARGS...
      Run CMD up to R times (default 1), stopping early once the runs so far took S
      seconds in all (default: no limit) or when a run fails. Each run is killed (its
      whole process group) after T seconds (default: none). Writes FILE.json with the
      wall time and peak RSS of every run (peak RSS from the rusage wait4() returns for
      the child, so it is the command's own high-water mark, not this script's) and the
      last run's stdout and the tail of its stderr.

  report.py report --results DIR [--doc docs/performance.md] [--json OUT.json] [--only KEYS]
      Read the files `measure` wrote into DIR (ROW.graftal.json, ROW.peer.json,
      memcpy.json, env.json), print the table, and replace the text between
      `<!-- bench:begin -->` and `<!-- bench:end -->` in the doc with the markdown table.
      With --only (space-separated row keys: a partial run), the table lists those rows
      and the doc is left alone.

Only the Python standard library is used.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

# ---- the rows ----------------------------------------------------------------------------

MiB = 1024 * 1024

# Exact module counts of the benchmark's L-systems, for the "count" check:
#   Koch island:  F_n = 4*8^n, turns T_n = 3 + 24*(8^n - 1)/7
#   ABOP 1.24d:   computed by graftal and by the npm peer (X_n = 3^n, 279,672,611 at 16)
#   Hogeweg 1.31a: graftal's count; graftal agrees with scripts/reference_lsystem.py (an
#                 independent model of cpfg's context rules) up to n = 30 in the tests
#   Honda 2.6a:   2^n apices + 6 modules per apex per step = 7*2^n - 6
def koch_modules(n: int) -> int:
    return 4 * 8**n + 3 + 24 * (8**n - 1) // 7


EXPECTED = {
    "koch8": koch_modules(8),
    "abop16": 279_672_611,
    "hogeweg70": 102_054_636,
    "honda23": 7 * 2**23 - 6,
    "honda23d": 7 * 2**23 - 6,
    "interp8": koch_modules(8),
    "stream11": koch_modules(11),
    "render3d": 8_388_581,  # 1,048,575 segments
}

# Parameters per module of Honda's tree, to size its output (5 bytes per module plus 4
# per parameter in graftal's structure of arrays; 8 with --precision double).
HONDA_ARITY = {"!": 1, "F": 1, "&": 1, "/": 1, "+": 1, "-": 1, "A": 2, "B": 2, "C": 2}

# label, what graftal runs, target text, cpfg reference (quoted, not measured)
ROWS = [
    ("koch8", "1. Koch island n=8 (D0L)", "≤ 50 ms, ≤ 2 B/module", "2.55 s / 154 MB"),
    ("abop16", "2. ABOP 1.24d n=16 (bracketed D0L)", "≤ 150 ms", "7.5 s"),
    ("hogeweg70", "3. Hogeweg–Hesper 1.31a n=70 (context)", "≤ 0.5 s", "17.4 s"),
    ("honda23", "4. Honda 2.6a n=23 (parametric)", "≤ 0.51 s, ≤ 460 MiB",
     "5.14 s / 461 MiB"),
    ("honda23d", "4d. Honda n=23, --precision double", "—", "—"),
    ("pcond22", "4c. conditions over 2–3 parameters n=22", "—", "—"),
    ("pctx20", "4x. context with parameters n=20", "—", "—"),
    ("pblocks20", "4b. statement blocks n=20 (one thread)", "—", "—"),
    ("interp8", "5. Koch n=8 + 2D turtle", "≥ 300 M modules/s", "—"),
    ("memcpy", "6. memcpy probe (Koch n=8 output, 1 B/module)", "— (the floor)", "—"),
    ("stream11", "7. Koch n=11 streamed to PNG", "≤ 120 s, ≤ 100 MB", "—"),
    ("map17t1", "8. map L-system Fig 5.2 n=17 relaxed (131,072 cells), 1 thread", "seconds", "—"),
    ("map17t2", "8b. the same, 2 threads", "seconds", "—"),
    ("render3d", "9. Honda monopodial n=20 ray traced, 800×800", "≤ 2 s, ≤ 800 MB", "—"),
]


# ---- measure -----------------------------------------------------------------------------

def run_once(cmd: list[str], timeout: float | None) -> dict:
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    timed_out = threading.Event()

    def kill():
        timed_out.set()
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass

    timer = threading.Timer(timeout, kill) if timeout else None
    if timer:
        timer.start()
    # Drain the pipes on threads so a chatty command cannot block on a full pipe; wait4()
    # on the main thread gives the child's own rusage.
    out: list[bytes] = []
    err: list[bytes] = []
    readers = [threading.Thread(target=lambda: out.append(proc.stdout.read())),
               threading.Thread(target=lambda: err.append(proc.stderr.read()))]
    for r in readers:
        r.start()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    if timer:
        timer.cancel()
    for r in readers:
        r.join()
    proc.returncode = os.waitstatus_to_exitcode(status)
    return {
        "rc": proc.returncode,
        "wall_s": wall,
        "cpu_s": usage.ru_utime + usage.ru_stime,
        "sys_s": usage.ru_stime,
        "maxrss_kb": usage.ru_maxrss,
        "timeout": timed_out.is_set(),
        "stdout": b"".join(out).decode("utf-8", "replace"),
        "stderr": b"".join(err).decode("utf-8", "replace")[-2000:],
    }


def loadavg() -> str:
    """The 1-, 5- and 15-minute load averages, as /proc/loadavg gives them."""
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "?"


def cmd_measure(args: argparse.Namespace) -> int:
    cmd = args.cmd[1:] if args.cmd and args.cmd[0] == "--" else args.cmd
    if not cmd:
        print("report.py measure: no command", file=sys.stderr)
        return 2
    runs = []
    last = None
    total = 0.0
    load_before = loadavg()
    for _ in range(max(1, args.runs)):
        last = run_once(cmd, args.timeout)
        runs.append({k: last[k] for k in ("rc", "wall_s", "cpu_s", "sys_s", "maxrss_kb", "timeout")})
        total += last["wall_s"]
        if last["rc"] != 0 or last["timeout"]:
            break
        if args.budget is not None and total >= args.budget:
            break
    result = {"cmd": cmd, "timeout_s": args.timeout, "runs": runs,
              "stdout": last["stdout"][-200_000:], "stderr": last["stderr"]}
    result["load_before"] = load_before
    result["load_after"] = loadavg()
    Path(args.out).write_text(json.dumps(result, indent=1) + "\n")
    ok = [r for r in runs if r["rc"] == 0 and not r["timeout"]]
    state = ("timeout" if last["timeout"] else f"exit {last['rc']}") if not ok else \
        f"median {statistics.median(r['wall_s'] for r in ok):.3f} s over {len(ok)} run(s)"
    print(f"    {Path(args.out).stem}: {state}", file=sys.stderr)
    return 0


# ---- report ------------------------------------------------------------------------------

def load(path: Path) -> dict | None:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def stdout_json(m: dict | None) -> dict | None:
    """The JSON object a command printed (graftal stats prints one, so does the peer)."""
    if not m:
        return None
    text = m.get("stdout", "")
    start = text.find("{")
    if start < 0:
        return None
    try:
        return json.loads(text[start:])
    except ValueError:
        # The peer prints one line; take the last line that parses.
        for line in reversed(text.splitlines()):
            try:
                return json.loads(line)
            except ValueError:
                continue
    return None


class Measured:
    """The summary of one measure file: median wall time of the good runs, peak RSS."""

    def __init__(self, m: dict | None, unavailable: str | None = None):
        self.raw = m
        self.unavailable = unavailable
        self.ok_runs = [r for r in (m or {}).get("runs", []) if r["rc"] == 0 and not r["timeout"]]
        self.wall = statistics.median(r["wall_s"] for r in self.ok_runs) if self.ok_runs else None
        self.rss = max(r["maxrss_kb"] for r in self.ok_runs) * 1024 if self.ok_runs else None
        # CPU time (user + system) of the run whose wall time is the median or next above.
        self.cpu = None
        if self.ok_runs and "cpu_s" in self.ok_runs[0]:
            ranked = sorted(self.ok_runs, key=lambda r: r["wall_s"])
            mid = ranked[len(ranked) // 2]
            self.cpu, self.sys = mid["cpu_s"], mid["sys_s"]
        self.out = stdout_json(m) if self.ok_runs else None

    @property
    def n_runs(self) -> int:
        return len(self.ok_runs)

    def failure(self) -> str:
        if self.unavailable:
            return self.unavailable
        if not self.raw:
            return "not run"
        last = self.raw["runs"][-1] if self.raw.get("runs") else None
        if last and last["timeout"]:
            # wait4() reports the peak RSS of a killed process too.
            return (f"timeout (> {self.raw['timeout_s']:.0f} s; peak RSS "
                    f"{fmt_bytes(last['maxrss_kb'] * 1024)} until then)")
        out = stdout_json(self.raw) or {}
        if out.get("supported") is False:
            return "not supported"
        if out.get("error"):
            return "failed: " + out["error"][:60]
        err = (self.raw.get("stderr") or "").strip().splitlines()
        msg = err[-1][:70] if err else ""
        if last and last["rc"] in (-9, 137) and not msg:
            msg = "killed (out of memory?)"
        return f"failed (exit {last['rc'] if last else '?'}){': ' + msg if msg else ''}"


def fmt_time(s: float | None) -> str:
    if s is None:
        return "—"
    if s < 1:
        return f"{s * 1000:.1f} ms"
    return f"{s:.2f} s"


def fmt_bytes(b: float | None) -> str:
    if b is None:
        return "—"
    if b >= 1024 * MiB:
        return f"{b / (1024 * MiB):.2f} GiB"
    return f"{b / MiB:.0f} MiB"


def fmt_count(n: float | None) -> str:
    if n is None:
        return "—"
    if n >= 1e9:
        return f"{n / 1e9:.2f} G"
    if n >= 1e6:
        return f"{n / 1e6:.1f} M"
    return f"{n:,.0f}"


def fmt_rate(n: float | None, s: float | None) -> str:
    if n is None or not s:
        return "—"
    return f"{n / s / 1e6:,.0f} M/s"


def fmt_ratio(a: float | None, b: float | None) -> str:
    if a is None or not b:
        return "—"
    r = a / b
    return f"{r:.3g}×"


def row_load(*measures: dict | None) -> str:
    """1-minute load average before/after the row's measurements."""
    ms = [m for m in measures if m and "load_before" in m]
    if not ms:
        return "—"
    return f"{ms[0]['load_before'].split()[0]} / {ms[-1]['load_after'].split()[0]}"


def build_rows(res: Path, only: list[str] | None = None) -> tuple[list[dict], dict]:
    env = load(res / "env.json") or {}
    probe_m = load(res / "memcpy.json")
    probe = stdout_json(probe_m) if probe_m else None
    bandwidth = probe["bytes"] / probe["copy_s"] if probe and probe.get("copy_s") else None

    rows = []
    for key, label, target, cpfg in ROWS:
        if only and key not in only:
            continue
        row = {"key": key, "label": label, "target": target, "cpfg": cpfg}
        rows.append(row)
        if key == "memcpy":
            modules = EXPECTED["koch8"]
            row.update(modules=modules, count="")
            if probe:
                row.update(g_time=f"{fmt_time(probe['copy_s'])} ({probe['copy_GBps']:.2f} GB/s "
                                  f"copy, {probe['fill_GBps']:.2f} GB/s fill; first touch "
                                  f"{fmt_time(probe['first_touch_s'])})",
                           g_rate=fmt_rate(modules, probe["copy_s"]),
                           g_rss=fmt_bytes((probe_m["runs"][0]["maxrss_kb"] * 1024)
                                           if probe_m.get("runs") else None),
                           peer="—", ratio_peer="—", ratio_floor="1×", met="—",
                           wall=probe["copy_s"])
            else:
                row.update(g_time="failed", peer="—", ratio_peer="—", ratio_floor="—", met="—")
            continue

        unavailable = None
        marker = res / f"{key}.graftal.unavailable"
        if marker.exists():
            unavailable = marker.read_text().strip() or "not available"
        g = Measured(load(res / f"{key}.graftal.json"), unavailable)
        # The derivation alone inside one process (bench/derive_timing.cpp): the first run
        # maps fresh memory, the warm ones reuse what the process gave back.
        inproc = Measured(load(res / f"{key}.inproc.json")).out
        row["load"] = row_load(g.raw, load(res / f"{key}.inproc.json"))
        row["inproc"] = (f"{fmt_time(inproc['first_s'])} / {fmt_time(inproc['warm_s'])}"
                         if inproc else "—")
        warm = inproc["warm_s"] if inproc else None
        peer_marker = res / f"{key}.peer.unavailable"
        p = Measured(load(res / f"{key}.peer.json"),
                     peer_marker.read_text().strip() if peer_marker.exists() else None)

        modules = (g.out or {}).get("modules") if g.out else None
        counted = modules is not None
        if modules is None:
            modules = EXPECTED.get(key)
        row["modules"] = modules
        # The output a derivation writes once: 1 byte per module, plus for parametric
        # strings a 4-byte offset per module and 8 bytes per parameter.
        out_bytes = None
        if modules is not None:
            out_bytes = modules
            if key in ("honda23", "honda23d") and g.out and "symbols" in g.out:
                params = sum(HONDA_ARITY.get(s, 0) * c for s, c in g.out["symbols"].items())
                out_bytes = 5 * modules + (8 if key == "honda23d" else 4) * params
        floor = out_bytes / bandwidth if out_bytes and bandwidth else None
        row["floor_s"] = floor

        # count check
        checks = []
        if counted and EXPECTED.get(key) is not None and modules != EXPECTED[key]:
            checks.append(f"graftal ≠ expected {EXPECTED[key]:,}")
        if p.out and p.out.get("modules") is not None and counted and p.out["modules"] != modules:
            checks.append(f"peer {p.out['modules']:,}")
        row["count"] = "; ".join(checks) if checks else (
            "✓" if counted else ("computed" if modules is not None else ""))

        if g.wall is not None:
            cpu = f"; CPU {fmt_time(g.cpu)}, {fmt_time(g.sys)} sys" if g.cpu is not None else ""
            row.update(wall=g.wall, g_time=f"{fmt_time(g.wall)} ({g.n_runs}{cpu})",
                       g_rate=fmt_rate(modules, g.wall), g_rss=fmt_bytes(g.rss),
                       rss=g.rss)
        else:
            row.update(g_time=g.failure(), g_rate="—", g_rss="—")

        if p.wall is not None:
            peer_time = p.wall
            row["peer"] = f"{fmt_time(peer_time)} ({p.n_runs}), {fmt_bytes(p.rss)}"
            row["ratio_peer"] = fmt_ratio(g.wall, peer_time)
        else:
            row["peer"] = p.failure()
            if p.raw and p.raw.get("runs") and p.raw["runs"][-1]["timeout"] and g.wall:
                row["ratio_peer"] = f"< {g.wall / p.raw['timeout_s']:.2g}×"
            else:
                row["ratio_peer"] = "—"
        row["ratio_floor"] = fmt_ratio(g.wall, floor)
        row["met"] = target_met(key, g, modules)
        limit = TIME_TARGETS.get(key)
        if warm is not None and limit is not None and g.wall is not None:
            row["met"] += f"; in-process warm {warm / limit:.3g}× target"
    return rows, {"env": env, "probe": probe, "bandwidth": bandwidth}


TIME_TARGETS = {"koch8": 0.050, "abop16": 0.150, "hogeweg70": 0.5, "honda23": 0.51}


def target_met(key: str, g: Measured, modules: int | None) -> str:
    if g.wall is None:
        if g.unavailable:
            return "n/a (" + g.unavailable + ")"
        if g.raw and g.raw.get("runs") and g.raw["runs"][-1]["timeout"]:
            return f"no (over {g.raw['timeout_s']:.0f} s)"
        return "no (did not run)" if key != "stream11" else "no (" + g.failure() + ")"
    t, rss = g.wall, g.rss
    if key == "koch8":
        bpm = rss / modules
        ok = t <= 0.050 and bpm <= 2.0
        return ("yes" if ok else "no") + f" ({t / 0.050:.3g}× time, {bpm:.2f} B/module)"
    if key == "abop16":
        return ("yes" if t <= 0.150 else "no") + f" ({t / 0.150:.3g}× target)"
    if key == "hogeweg70":
        return ("yes" if t <= 0.5 else "no") + f" ({t / 0.5:.3g}× target)"
    if key == "honda23":
        ok = t <= 0.51 and rss <= 460 * MiB
        return ("yes" if ok else "no") + f" ({t / 0.51:.3g}× time, {rss / MiB:.0f} MiB)"
    if key == "interp8":
        rate = modules / t / 1e6
        return ("yes" if rate >= 300 else "no") + f" ({rate:,.0f} M/s)"
    if key.startswith("map17"):
        return ("yes" if t <= 10 else "no") + f" ({t:.1f} s)"
    if key == "render3d":
        ok = t <= 2 and rss <= 800 * 1000**2
        return ("yes" if ok else "no") + f" ({t:.2f} s, {rss / 1000**2:.0f} MB)"
    if key == "stream11":
        ok = t <= 120 and rss <= 100 * MiB
        return ("yes" if ok else "no") + f" ({t:.0f} s, {rss / MiB:.0f} MiB)"
    return "—"


COLUMNS = [
    ("row", "label"),
    ("modules", "modules_fmt"),
    ("graftal whole process (runs)", "g_time"),
    ("graftal modules/s", "g_rate"),
    ("derivation in process, first / warm", "inproc"),
    ("graftal peak RSS", "g_rss"),
    ("lindenmayer time (runs), peak RSS", "peer"),
    ("graftal/lindenmayer", "ratio_peer"),
    ("graftal/floor", "ratio_floor"),
    ("cpfg (published, quoted — not measured)", "cpfg"),
    ("target", "target"),
    ("met", "met"),
    ("count check", "count"),
    ("load (1 min) before / after", "load"),
]


def table_cells(rows: list[dict]) -> list[list[str]]:
    out = []
    for r in rows:
        r["modules_fmt"] = fmt_count(r.get("modules"))
        out.append([str(r.get(k, "—")) for _, k in COLUMNS])
    return out


def markdown(rows: list[dict], meta: dict) -> str:
    cells = table_cells(rows)
    lines = ["| " + " | ".join(h for h, _ in COLUMNS) + " |",
             "|" + "|".join("---" for _ in COLUMNS) + "|"]
    for c in cells:
        lines.append("| " + " | ".join(x.replace("|", "\\|") for x in c) + " |")
    env = meta["env"]
    notes = [
        "",
        f"Measured {env.get('date', '?')} on {env.get('cpu', '?')}, {env.get('cores', '?')} cores, "
        f"{env.get('memory', '?')} RAM; load average before/after the run: "
        f"{env.get('load_before', '?')} / {env.get('load_after', '?')}.",
        f"graftal {env.get('graftal_commit', '?')} (built in `{env.get('build_dir', '?')}`, "
        f"{env.get('graftal_flags', '')}); lindenmayer {env.get('peer_version', '?')} on "
        f"Node {env.get('node', '?')}.",
        "Times are wall-clock medians of the runs in brackets (whole process: start, parse, "
        "derive, print), with the CPU time (user + system, all threads) of the median run; "
        "peak RSS is the largest of those runs. "
        "graftal/lindenmayer and graftal/floor are ratios of times (below 1: graftal is "
        "faster). The floor is the row's output size (1 B/module; Honda 5 B/module + 4 B/"
        "parameter, 8 with --precision double) divided by the memcpy bandwidth of row 6. "
        "`stats --no-geometry` counts the last step without writing it; the in-process "
        "column derives every step in full. The last column is the 1-minute load average "
        "when the row's runs began and ended. "
        "\"Derivation in process\" is derive() alone timed inside one process "
        "(bench/derive_timing.cpp): the first run maps its buffers fresh from the kernel, "
        "the warm one (fastest of 4 more) reuses memory the process just gave back; the gap "
        "is this VM's first-touch cost.",
    ]
    return "\n".join(lines + notes)


def text_table(rows: list[dict], meta: dict) -> str:
    cells = table_cells(rows)
    # Too wide for one table on a terminal: print each row as a block.
    out = []
    for c in cells:
        out.append(c[0])
        for (h, _), v in zip(COLUMNS[1:], c[1:]):
            out.append(f"    {h:<42} {v}")
    env = meta["env"]
    out.append("")
    out.append(f"load average before/after: {env.get('load_before', '?')} / "
               f"{env.get('load_after', '?')} ({env.get('cores', '?')} cores)")
    return "\n".join(out)


def cmd_report(args: argparse.Namespace) -> int:
    res = Path(args.results)
    only = args.only.split() if args.only else None
    rows, meta = build_rows(res, only)
    print(text_table(rows, meta))
    md = markdown(rows, meta)
    (res / "table.md").write_text(md + "\n")
    if args.json:
        Path(args.json).write_text(json.dumps({"rows": rows, **meta}, indent=1, default=str) + "\n")
    if args.doc and only:
        print(f"\npartial run (--only): {args.doc} left alone; table in {res / 'table.md'}")
    elif args.doc:
        if replace_between_markers(Path(args.doc), "bench", md):
            print(f"\ntable written to {args.doc}")
        else:
            print(f"\n{args.doc} has no <!-- bench:begin --> ... <!-- bench:end --> markers; "
                  f"table left in {res / 'table.md'}", file=sys.stderr)
    return 0


def replace_between_markers(doc: Path, name: str, md: str) -> bool:
    """Puts `md` between <!-- NAME:begin --> and <!-- NAME:end --> in `doc`; False (and the
    doc left alone) when it has no such pair."""
    text = doc.read_text() if doc.exists() else ""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    if not (begin in text and end in text and text.index(begin) < text.index(end)):
        return False
    head, rest = text.split(begin, 1)
    _, tail = rest.split(end, 1)
    doc.write_text(f"{head}{begin}\n{md}\n{end}{tail}")
    return True


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)
    m = sub.add_parser("measure")
    m.add_argument("--out", required=True)
    m.add_argument("--runs", type=int, default=1)
    m.add_argument("--budget", type=float)
    m.add_argument("--timeout", type=float)
    m.add_argument("cmd", nargs=argparse.REMAINDER)
    r = sub.add_parser("report")
    r.add_argument("--results", required=True)
    r.add_argument("--doc")
    r.add_argument("--json")
    r.add_argument("--only")
    args = ap.parse_args()
    return cmd_measure(args) if args.command == "measure" else cmd_report(args)


if __name__ == "__main__":
    sys.exit(main())
