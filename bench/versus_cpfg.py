#!/usr/bin/env python3
"""graftal and cpfg side by side, on the same files, in three modes per model.

    bench/versus_cpfg.py --graftal BUILD/graftal --cpfg DEST/bin/cpfg --results DIR
                         [--runs 3] [--rows "koch8 honda23"] [--doc docs/performance.md]

Called by bench/run.sh when CPFG is set (`CPFG=DEST/bin/cpfg make bench`); cpfg is built
from vlab's sources outside the repository as ../shared/cpfg-anchor/ describes. The models
are bench/cpfg/*.l with their view files, in cpfg's layout (the angle in the view file),
and both programs read exactly those files. For every model and mode the two programs run
alternately (graftal, cpfg, then cpfg, graftal, ...), each run a whole process, timed from
fork to exit: wall time, CPU time (user + system) and peak RSS from wait4()'s rusage, and
the load average before and after the row.

The modes, and what each command produces:

  file    the derived string written to a file.
          graftal derive M.l M.v > OUT          cpfg -g -m MAP -str OUT M.l M.v
  derive  the derivation, nothing written.
          graftal stats M.l M.v --no-geometry   cpfg -g -m MAP M.l M.v
          graftal counts the last string's modules without holding that string: a D0L
          string streamed in runs through a counter, a parametric one streamed depth first
          on every core with its last step counted from the successors chosen, a
          context-sensitive one counted from the productions chosen for the string before;
          cpfg's batch mode always interprets the final string with its turtle to find the
          view volume (control.c, NO_GRAPHICS_MODE calls CalculateViewVolume), and has no
          mode without it, so its "derive" row does the turtle's work too.
  turtle  the derivation and the turtle: segment count and bounding box.
          graftal stats M.l M.v                 cpfg -g -m MAP -vv OUT M.l M.v
          (cpfg prints the view volume it found: the bounding box)

The first run of each pair checks that the two agree: the same string (cpfg wraps lines
and prints parameters with %g, so for parametric models only the module count is
compared) and the same bounding box. The table goes to DIR/versus-cpfg.md and, with
--doc, between <!-- cpfg:begin --> and <!-- cpfg:end --> in the doc.
Only the Python standard library is used; the measuring is report.py's.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from report import fmt_bytes, fmt_time, loadavg, replace_between_markers  # noqa: E402

HERE = Path(__file__).resolve().parent
MODELS = HERE / "cpfg"
MiB = 1024 * 1024

# key, model file (bench/cpfg/KEY's file, with FILE.v beside it), label, parametric
ROWS = [
    ("koch8", "koch-island", "Koch island n=8 (D0L)", False),
    ("abop16", "abop-1.24d", "ABOP 1.24d n=16 (bracketed D0L)", False),
    ("hogeweg70", "hogeweg-1.31a", "Hogeweg–Hesper 1.31a n=70 (context)", False),
    ("honda23", "honda-2.6a", "Honda 2.6a n=23 (parametric)", True),
]
MODES = ["file", "derive", "turtle"]

# The targets of the project's performance plan: the least graftal/cpfg speed-up (cpfg's
# wall time over graftal's), and for parametric models the most memory against cpfg's.
SPEEDUP = {
    ("koch8", "file"): 10, ("abop16", "file"): 10, ("honda23", "file"): 8,
    ("koch8", "derive"): 20, ("abop16", "derive"): 20, ("hogeweg70", "derive"): 20,
    ("honda23", "derive"): 15,
}
MEMORY = {("honda23", m): 0.75 for m in MODES}
# Whole-process wall-time targets (Koch n=8 with the turtle: 150 M segments/s).
WALL = {("koch8", "turtle"): 0.45}


def run_measured(cmd: list[str], stdout_path: Path | None, timeout: float, env: dict) -> dict:
    """One whole process, reaped with wait4() for its own CPU time and peak RSS; its
    standard output to a file or kept."""
    out = open(stdout_path, "wb") if stdout_path else subprocess.PIPE
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.PIPE, env=env,
                            start_new_session=True)
    # Drain the pipes on threads, reap on this one to get the child's rusage.
    chunks: dict[str, list[bytes]] = {"out": [], "err": []}
    readers = [threading.Thread(target=lambda: chunks["err"].append(proc.stderr.read()))]
    if not stdout_path:
        readers.append(threading.Thread(target=lambda: chunks["out"].append(proc.stdout.read())))
    for r in readers:
        r.start()
    killed = threading.Event()

    def kill():
        killed.set()
        try:
            os.killpg(proc.pid, 9)
        except ProcessLookupError:
            pass

    timer = threading.Timer(timeout, kill)
    timer.start()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    timer.cancel()
    for r in readers:
        r.join()
    if stdout_path:
        out.close()
    return {"rc": os.waitstatus_to_exitcode(status), "wall_s": wall,
            "cpu_s": usage.ru_utime + usage.ru_stime, "sys_s": usage.ru_stime,
            "maxrss_kb": usage.ru_maxrss, "timeout": killed.is_set(),
            "stdout": b"".join(chunks["out"]).decode("utf-8", "replace")[-100_000:],
            "stderr": b"".join(chunks["err"]).decode("utf-8", "replace")[-2000:]}


def commands(side: str, key: str, name: str, mode: str, tools: dict, work: Path):
    """(argv, stdout file or None, the file the run writes) for one side, model and mode."""
    models = tools["models"]
    model, view = str(models / f"{name}.l"), str(models / f"{name}.v")
    out = work / f"{key}.{mode}.{side}"
    if side == "graftal":
        g = tools["graftal"]
        if mode == "file":
            return [g, "derive", model, view, "--quiet"], out, out
        if mode == "derive":
            return [g, "stats", model, view, "--no-geometry", "--quiet"], None, None
        return [g, "stats", model, view, "--quiet"], None, None
    c = [tools["cpfg"], "-g", "-m", str(tools["map"])]
    if mode == "file":
        return c + ["-str", str(out), model, view], None, out
    if mode == "derive":
        return c + [model, view], None, None
    return c + ["-vv", str(out), model, view], None, out


def chunks(path: Path, drop_newlines: bool):
    """The file's bytes in 4 MiB pieces (without newlines if asked). The bench never holds
    a string whole: a child's peak RSS as wait4() reports it starts from this process's
    own peak (the kernel carries it over through exec), so this process stays small."""
    with open(path, "rb") as f:
        while piece := f.read(4 << 20):
            yield piece.replace(b"\n", b"") if drop_newlines else piece


def same_text(graftal_file: Path, cpfg_file: Path) -> tuple[bool, int, int]:
    """Whether graftal's string (one trailing newline) equals cpfg's without its line
    breaks, compared piece by piece; and the two lengths."""
    a, b = chunks(graftal_file, True), chunks(cpfg_file, True)
    abuf = bbuf = b""
    alen = blen = 0
    equal = True
    while True:
        if not abuf:
            abuf = next(a, b"")
            alen += len(abuf)
        if not bbuf:
            bbuf = next(b, b"")
            blen += len(bbuf)
        if not abuf or not bbuf:
            break
        n = min(len(abuf), len(bbuf))
        equal &= abuf[:n] == bbuf[:n]
        abuf, bbuf = abuf[n:], bbuf[n:]
    for rest in a:
        alen += len(rest)
    for rest in b:
        blen += len(rest)
    return equal and alen == blen and not abuf and not bbuf, alen, blen


def count_modules(path: Path) -> int:
    """Modules of a printed parametric string: symbols outside parentheses."""
    depth = 0
    n = 0
    for piece in chunks(path, True):
        for ch in piece:
            if ch == 40:  # (
                depth += 1
            elif ch == 41:  # )
                depth -= 1
            elif depth == 0 and ch != 32:
                n += 1
    return n


def agreement(key: str, mode: str, parametric: bool, g: dict, c: dict, gfile, cfile) -> str:
    """Whether the first pair of runs produced the same thing."""
    try:
        if mode == "file":
            if not cfile or not cfile.exists() or cfile.stat().st_size == 0:
                return "cpfg wrote no string"
            if not parametric:
                same, glen, clen = same_text(gfile, cfile)
                return "same string" if same else f"strings differ ({glen:,} / {clen:,} B)"
            gn, cn = count_modules(gfile), count_modules(cfile)
            return (f"same module count ({gn:,})" if gn == cn else
                    f"module counts differ ({gn:,} / {cn:,})")
        if mode == "turtle":
            stats = json.loads(g["stdout"][g["stdout"].find("{"):])
            box = cfile.read_text() if cfile and cfile.exists() else ""
            nums = [float(x) for x in re.findall(r"-?[0-9.]+(?:e[-+]?[0-9]+)?", box)]
            if len(nums) != 6:
                return "cpfg printed no view volume"
            cmin, cmax = nums[0::2], nums[1::2]
            gmin, gmax = stats["bbox"]["min"], stats["bbox"]["max"]
            # cpfg prints %g (6 digits); the z extent of a 2D picture is 0 in cpfg.
            def close(a, b):
                return abs(a - b) <= 1e-5 * max(1.0, abs(a), abs(b)) + 2e-5
            same = all(close(gmin[i], cmin[i]) and close(gmax[i], cmax[i]) for i in range(3))
            return "same bounding box" if same else "bounding boxes differ"
    except (OSError, ValueError, KeyError) as e:
        return f"not checked ({e})"
    return "—"


def summarise(runs: list[dict]) -> dict | None:
    ok = [r for r in runs if r["rc"] == 0 and not r["timeout"]]
    if not ok:
        return None
    ranked = sorted(ok, key=lambda r: r["wall_s"])
    mid = ranked[len(ranked) // 2]
    return {"wall": statistics.median(r["wall_s"] for r in ok), "cpu": mid["cpu_s"],
            "rss": max(r["maxrss_kb"] for r in ok) * 1024, "runs": len(ok)}


def failure(runs: list[dict]) -> str:
    if not runs:
        return "not run"
    last = runs[-1]
    if last["timeout"]:
        return "timeout"
    msg = (last.get("stderr") or "").strip().splitlines()
    return f"failed (exit {last['rc']}){': ' + msg[-1][:60] if msg else ''}"


def measure(args) -> dict:
    tools = {"graftal": args.graftal, "cpfg": args.cpfg, "models": Path(args.models)}
    results = Path(args.results)
    results.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="versus-cpfg-", dir=results))
    tools["map"] = work / "grey.map"
    # cpfg's batch mode needs a colour map: 256 grey entries, r g b bytes each.
    tools["map"].write_bytes(bytes(b for i in range(256) for b in (i, i, i)))
    env = dict(os.environ)
    # cpfg runs its preprocessor, vlabcpp, from the PATH; it sits beside cpfg.
    env["PATH"] = str(Path(args.cpfg).resolve().parent) + os.pathsep + env.get("PATH", "")
    env.setdefault("QT_QPA_PLATFORM", "offscreen")
    wanted = args.rows.split() if args.rows else [r[0] for r in ROWS]
    rows = []
    for key, name, label, parametric in ROWS:
        if key not in wanted:
            continue
        for mode in MODES:
            print(f"bench: {label}, {mode}: graftal and cpfg alternately, {args.runs} run(s) each",
                  file=sys.stderr)
            row = {"key": key, "label": label, "mode": mode, "load_before": loadavg()}
            runs = {"graftal": [], "cpfg": []}
            for i in range(args.runs):
                order = ["graftal", "cpfg"] if i % 2 == 0 else ["cpfg", "graftal"]
                for side in order:
                    argv, stdout_path, written = commands(side, key, name, mode, tools, work)
                    r = run_measured(argv, stdout_path, args.timeout, env)
                    if written and written.exists():
                        r["bytes"] = written.stat().st_size
                    runs[side].append(r)
                    r["written"] = str(written) if written else None
                if i == 0:
                    g, c = runs["graftal"][0], runs["cpfg"][0]
                    gf = Path(g["written"]) if g["written"] else None
                    cf = Path(c["written"]) if c["written"] else None
                    ok = g["rc"] == 0 and c["rc"] == 0 and not g["timeout"] and not c["timeout"]
                    row["check"] = (agreement(key, mode, parametric, g, c, gf, cf) if ok
                                    else "not checked")
                for side in runs:
                    w = runs[side][-1].get("written")
                    if w and Path(w).exists():
                        Path(w).unlink()
            row["load_after"] = loadavg()
            for side in runs:
                for r in runs[side]:
                    r.pop("stdout", None)
                row[side] = {"runs": runs[side], "summary": summarise(runs[side]),
                             "failure": failure(runs[side])}
                row[side]["bytes"] = next((r["bytes"] for r in runs[side] if "bytes" in r), None)
            rows.append(row)
            g, c = row["graftal"]["summary"], row["cpfg"]["summary"]
            if g and c:
                print(f"    graftal {fmt_time(g['wall'])} / {fmt_bytes(g['rss'])}, cpfg "
                      f"{fmt_time(c['wall'])} / {fmt_bytes(c['rss'])}: "
                      f"{c['wall'] / g['wall']:.3g}× ({row.get('check', '')})", file=sys.stderr)
    for f in work.iterdir():
        f.unlink()
    work.rmdir()
    env_info = {
        "date": time.strftime("%Y-%m-%d %H:%M %Z"),
        "cpu": subprocess.run("lscpu | sed -n 's/^Model name: *//p' | head -1", shell=True,
                              capture_output=True, text=True).stdout.strip(),
        "cores": os.cpu_count(),
        "graftal": args.graftal, "cpfg": args.cpfg, "runs": args.runs,
    }
    data = {"env": env_info, "rows": rows}
    (results / "versus-cpfg.json").write_text(json.dumps(data, indent=1) + "\n")
    return data


def cell(s: dict | None, fail: str) -> str:
    if not s:
        return fail
    return f"{fmt_time(s['wall'])} (CPU {fmt_time(s['cpu'])}), {fmt_bytes(s['rss'])}"


def verdict(key: str, mode: str, g: dict | None, c: dict | None) -> tuple[str, str]:
    """(target, met) for one row."""
    targets, mets = [], []
    if (key, mode) in SPEEDUP:
        t = SPEEDUP[(key, mode)]
        targets.append(f"≥ {t}× cpfg")
        if g and c:
            mets.append(("yes" if c["wall"] / g["wall"] >= t else "no") +
                        f" ({c['wall'] / g['wall']:.3g}×)")
    if (key, mode) in MEMORY:
        t = MEMORY[(key, mode)]
        targets.append(f"≤ {t}× cpfg's memory")
        if g and c:
            mets.append(("yes" if g["rss"] <= t * c["rss"] else "no") +
                        f" ({g['rss'] / c['rss']:.2f}×)")
    if (key, mode) in WALL:
        t = WALL[(key, mode)]
        targets.append(f"≤ {fmt_time(t)}")
        if g:
            mets.append(("yes" if g["wall"] <= t else "no") + f" ({fmt_time(g['wall'])})")
    if not targets:
        return "—", "—"
    return "; ".join(targets), "; ".join(mets) if mets else "not measured"


def table(data: dict) -> str:
    head = ["model", "mode", "graftal wall (CPU), peak RSS", "cpfg 6.6 wall (CPU), peak RSS",
            "speed-up (cpfg/graftal)", "memory (graftal/cpfg)", "output", "agreement",
            "target", "met", "load (1 min) before / after"]
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    for row in data["rows"]:
        g, c = row["graftal"]["summary"], row["cpfg"]["summary"]
        speed = f"{c['wall'] / g['wall']:.3g}×" if g and c else "—"
        mem = f"{g['rss'] / c['rss']:.2f}×" if g and c else "—"
        out = "—"
        if row["mode"] == "file" and row["graftal"]["bytes"] is not None:
            out = f"{fmt_bytes(row['graftal']['bytes'])} / {fmt_bytes(row['cpfg']['bytes'])}"
        target, met = verdict(row["key"], row["mode"], g, c)
        cells = [row["label"], row["mode"], cell(g, row["graftal"]["failure"]),
                 cell(c, row["cpfg"]["failure"]), speed, mem, out, row.get("check", "—"),
                 target, met,
                 f"{row['load_before'].split()[0]} / {row['load_after'].split()[0]}"]
        lines.append("| " + " | ".join(x.replace("|", "\\|") for x in cells) + " |")
    env = data["env"]
    lines += ["", f"Measured {env['date']} on {env['cpu']}, {env['cores']} cores; medians of "
              f"{env['runs']} whole-process runs per program, graftal and cpfg alternating. "
              "Output: the string file's size, graftal's / cpfg's (cpfg breaks lines every 70 "
              "characters and prints parameters with %g). Modes and commands: "
              "[bench/versus_cpfg.py](../bench/versus_cpfg.py)."]
    return "\n".join(lines)


def write_doc(doc: Path, md: str) -> None:
    if replace_between_markers(doc, "cpfg", md):
        print(f"bench: the cpfg table written to {doc}", file=sys.stderr)
    else:
        print(f"bench: {doc} has no <!-- cpfg:begin --> … <!-- cpfg:end --> markers; the table "
              "is left in the results", file=sys.stderr)


def side_by_side_arguments(description: str, runs: int) -> argparse.ArgumentParser:
    """The options of both side-by-side scripts: the two programs, the results folder, the
    runs per command and the doc whose table they rewrite."""
    ap = argparse.ArgumentParser(description=description,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--graftal", required=True)
    ap.add_argument("--cpfg", required=True)
    ap.add_argument("--results", required=True)
    ap.add_argument("--runs", type=int, default=runs)
    ap.add_argument("--doc", default="")
    return ap


def cpfg_missing(cpfg: str) -> bool:
    if Path(cpfg).is_file() and os.access(cpfg, os.X_OK):
        return False
    print(f"bench: no cpfg at {cpfg} (../shared/cpfg-anchor/ says how to build one)",
          file=sys.stderr)
    return True


def main() -> int:
    ap = side_by_side_arguments(__doc__, 3)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--rows", default="")
    ap.add_argument("--models", default=str(MODELS),
                    help="a folder with the same file names (e.g. copies at smaller n)")
    ap.add_argument("--report-only", action="store_true",
                    help="rebuild the table from RESULTS/versus-cpfg.json without running")
    args = ap.parse_args()
    if cpfg_missing(args.cpfg):
        return 2
    if args.report_only:
        data = json.loads((Path(args.results) / "versus-cpfg.json").read_text())
    else:
        data = measure(args)
    md = table(data)
    (Path(args.results) / "versus-cpfg.md").write_text(md + "\n")
    print(md)
    if args.doc and not args.rows:
        write_doc(Path(args.doc), md)
    elif args.doc:
        print("bench: a partial run (--rows): the doc is left alone", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
