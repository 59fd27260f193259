#!/usr/bin/env python3
"""Independent reference implementation of the graftal example L-systems.

A deliberately small, obviously-correct model of what graftal must compute, written
without looking at the C++ engine:

  * a reader for the subset of the .l language the examples use (cpfg-style files with an
    `Lsystem:` line, and legacy pfg data files without one, seed Appendix A);
  * a string rewriter: parallel rewriting, first applicable production in file order,
    bracketed context matching (seed ch. 3.4 and pfg's lcondiff/rcondiff);
  * a 2D turtle counting segments and the bounding box of every position visited by
    F and f (the start point included).

tests/expected_examples.json is a JSON array with one object per examples/*.l file:
  {"file", "format" ("cpfg" or "pfg"), "derivation_length", "dimension" (2 or 3),
   "steps": [{"n", "modules", "segments", "polygons", "bbox", "drawn_bbox", "string"}]}
for every n from 0 to the file's derivation length, where
  modules     the number of modules in the derived string (a declared multi-letter
              name is one module);
  segments    the number of F modules (each draws one segment);
  polygons    the number of '}' (filled polygons closed);
  bbox        2D files only, and only when something is drawn:
              [[minx, miny], [maxx, maxy]] over the start point (0,0) and every position
              reached by F or f; step 1, heading up (+y), '+' counter-clockwise in cpfg
              files and clockwise in pfg files; rounded to 1e-6;
  drawn_bbox  only where it differs from bbox: the box of the segment end points and
              polygon vertices alone (a move with f can go beyond what is drawn);
  string      the derived string, module names concatenated without spaces, when it
              has at most 400 characters.

Usage:
  reference_lsystem.py derive FILE [-n N]     print the derived string
  reference_lsystem.py stats FILE [-n N]      print modules / segments / bbox as JSON
  reference_lsystem.py check                  check against the strings printed in the book
  reference_lsystem.py expected [-o OUT]      write tests/expected_examples.json
  reference_lsystem.py compare GRAFTAL_EXE [FILE...] [--every-step]
                                              compare graftal's derive/stats with this
"""

import argparse
import json
import math
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = os.path.join(ROOT, "examples")

BRACKETS = ("[", "]")


# --------------------------------------------------------------------------- reading


def strip_comments(text):
    """Blank out /* */ comments and `//` comments.

    As in graftal's language, `//` starts a comment only at the start of a line or when
    white space is on both sides of it; elsewhere it is two roll-right modules."""
    out = []
    i = 0
    in_block = False
    line = []
    while i < len(text):
        c = text[i]
        if in_block:
            if text.startswith("*/", i):
                in_block = False
                i += 2
            else:
                if c == "\n":
                    out.append("".join(line))
                    line = []
                i += 1
            continue
        if c == "\n":
            out.append("".join(line))
            line = []
            i += 1
            continue
        if text.startswith("/*", i):
            in_block = True
            i += 2
            continue
        if text.startswith("//", i):
            at_start = "".join(line).strip() == ""
            space_before = not line or line[-1] in " \t"
            space_after = i + 2 >= len(text) or text[i + 2] in " \t\r\n"
            if at_start or (space_before and space_after):
                while i < len(text) and text[i] != "\n":
                    i += 1
                continue
        line.append(c)
        i += 1
    if line:
        out.append("".join(line))
    return out


def tokenize(text, names):
    """Split module text into module names: declared names longest first, whitespace
    ignored, otherwise one character per module."""
    by_length = sorted(names, key=len, reverse=True)
    mods = []
    i = 0
    while i < len(text):
        c = text[i]
        if c.isspace():
            i += 1
            continue
        if c.isalpha() or c == "_":
            for n in by_length:
                if text.startswith(n, i):
                    mods.append(n)
                    i += len(n)
                    break
            else:
                mods.append(c)
                i += 1
        else:
            mods.append(c)
            i += 1
    return mods


class LSystem:
    def __init__(self):
        self.path = None
        self.pfg = False
        self.n = 0
        self.delta = 90.0
        self.angle_factor = None
        self.axiom = []
        self.productions = []  # (left, pred, right, succ) lists of module names
        self.ignore = set()
        self.consider = None
        self.names = []
        self.defines = {}

    def ignored(self, m):
        if self.consider is not None:
            return m not in self.consider and m not in BRACKETS
        return m in self.ignore


def eval_number(expr, defines):
    expr = expr.strip()
    for _ in range(20):  # expand #define'd names
        new = re.sub(r"[A-Za-z_]\w*", lambda m: "(" + defines[m.group(0)] + ")"
                     if m.group(0) in defines else m.group(0), expr)
        if new == expr:
            break
        expr = new
    if not re.fullmatch(r"[0-9eE.+\-*/() \t]+", expr):
        raise ValueError("not a number: " + expr)
    return eval(expr, {"__builtins__": {}}, {})


def parse_production(line, names, split_pred):
    lhs, succ = line.split("-->", 1)
    left, right = "", ""
    if "<" in lhs:
        left, lhs = lhs.split("<", 1)
    if ">" in lhs:
        lhs, right = lhs.split(">", 1)

    def mods(t):
        t = t.strip()
        return [] if t in ("", "*") else tokenize(t, names)

    pred = mods(lhs)
    if not split_pred and len(pred) != 1:
        raise ValueError("cpfg-style predecessor must be one module: " + line)
    return (mods(left), pred, mods(right), mods(succ))


def load(path):
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    lines = strip_comments(text)
    ls = LSystem()
    ls.path = path
    ls.pfg = not any(re.match(r"\s*Lsystem\s*:", l, re.I) for l in lines)
    for raw in lines:
        line = raw.strip()
        if not line:
            continue
        m = re.match(r"#define\s+(\w+)\s+(.*)$", line)
        if m:
            ls.defines[m.group(1)] = m.group(2).strip()
            continue
        m = re.match(r"module\s+(.*?);?$", line)
        if m and not ls.pfg:
            ls.names += [n.strip() for n in m.group(1).split(",") if n.strip()]
            continue
        m = re.match(r"(Lsystem|endlsystem)\b", line, re.I)
        if m:
            continue
        # How a curve is smoothed, dotted or played changes neither string nor turtle path.
        if re.match(r"(spline|kolam dots|music [a-z]+)\s*:", line, re.I):
            continue
        m = re.match(r"(derivation length|angle factor|angle increment|scale factor|axiom"
                     r"|ignore|consider)\s*:(.*)$", line, re.I)
        if m:
            key, val = m.group(1).lower(), m.group(2).strip()
            if key == "derivation length":
                ls.n = int(eval_number(val, ls.defines))
            elif key == "angle factor":
                ls.angle_factor = int(eval_number(val, ls.defines))
                ls.delta = 360.0 / ls.angle_factor
            elif key == "angle increment":
                ls.delta = float(eval_number(val, ls.defines))
                ls.angle_factor = None
            elif key == "axiom":
                ls.axiom = tokenize(val, ls.names)
            elif key == "ignore":
                ls.ignore = set(tokenize(val, ls.names))
            elif key == "consider":
                ls.consider = set(tokenize(val, ls.names))
            continue
        if "-->" in line:
            ls.productions.append(parse_production(line, ls.names, ls.pfg))
            continue
        raise ValueError("%s: cannot read line: %r" % (path, line))
    return ls


# --------------------------------------------------------------------------- rewriting


def match_left(ls, s, i, left):
    """Left context: walk toward the root from s[i-1]. Ignored symbols and '[' (entering
    the parent) are skipped, and so is every whole sibling branch met as ']'...'['."""
    k = len(left) - 1
    j = i - 1
    while k >= 0:
        if j < 0:
            return False
        m = s[j]
        if m == "[" or ls.ignored(m):
            j -= 1
        elif m == "]":
            depth = 0
            while True:  # to the '[' that opens this branch
                if s[j] == "]":
                    depth += 1
                elif s[j] == "[":
                    depth -= 1
                    if depth == 0:
                        break
                j -= 1
            j -= 1
        else:
            if m != left[k]:
                return False
            k -= 1
            j -= 1
    return True


def match_right(ls, s, i, right):
    """Right context: walk right from s[i]; ignored symbols and whole lateral branches
    '[...]' are skipped; a ']' ending the current branch, or the end, fails."""
    k = 0
    j = i
    while k < len(right):
        if j >= len(s):
            return False
        m = s[j]
        if ls.ignored(m):
            j += 1
        elif m == "[":
            depth = 0
            while True:
                if s[j] == "[":
                    depth += 1
                elif s[j] == "]":
                    depth -= 1
                    if depth == 0:
                        break
                j += 1
            j += 1
        elif m == "]":
            return False
        else:
            if m != right[k]:
                return False
            k += 1
            j += 1
    return True


def step(ls, s):
    out = []
    i = 0
    while i < len(s):
        for left, pred, right, succ in ls.productions:
            if s[i:i + len(pred)] != pred:
                continue
            if right and not match_right(ls, s, i + len(pred), right):
                continue
            if left and not match_left(ls, s, i, left):
                continue
            out.extend(succ)
            i += len(pred)
            break
        else:
            out.append(s[i])
            i += 1
    return out


def derive(ls, n=None, limit=20_000_000):
    """Yields (k, string) for k = 0..n."""
    n = ls.n if n is None else n
    s = list(ls.axiom)
    yield 0, s
    for k in range(1, n + 1):
        s = step(ls, s)
        if len(s) > limit:
            raise RuntimeError("string too long at step %d" % k)
        yield k, s


# --------------------------------------------------------------------------- turtle


def turtle2d(ls, s):
    """Segments, polygons and bbox of the 2D turtle interpretation.

    Heading starts up (+y); '+' turns left (counter-clockwise) in cpfg-style files and
    right (clockwise) in pfg data files. The heading is kept as an integer number of
    turns when 360/delta is an integer, so that the positions stay exact to rounding."""
    sign = -1 if ls.pfg else 1
    exact = ls.angle_factor is not None
    if not exact and abs(360.0 / ls.delta - round(360.0 / ls.delta)) < 1e-12:
        exact = True
    steps = round(360.0 / ls.delta) if exact else None
    if exact:
        dirs = []
        for k in range(steps):
            a = math.radians(90.0 + k * 360.0 / steps)
            dirs.append((round(math.cos(a), 15), round(math.sin(a), 15)))
    x = y = 0.0
    h = 0  # turns (exact) or degrees counter-clockwise from up
    minx = maxx = miny = maxy = 0.0
    drawn = [math.inf, math.inf, -math.inf, -math.inf]  # segment ends, polygon vertices
    in_polygon = False

    def extend(px, py):
        drawn[0], drawn[1] = min(drawn[0], px), min(drawn[1], py)
        drawn[2], drawn[3] = max(drawn[2], px), max(drawn[3], py)

    segments = 0
    polygons = 0
    stack = []
    for m in s:
        if m in ("F", "f", "G", "g"):  # G and g move without a polygon vertex, as in cpfg
            if exact:
                dx, dy = dirs[h % steps]
            else:
                a = math.radians(90.0 + h)
                dx, dy = math.cos(a), math.sin(a)
            if m in ("F", "G"):
                extend(x, y)
            x += dx
            y += dy
            minx, maxx = min(minx, x), max(maxx, x)
            miny, maxy = min(miny, y), max(maxy, y)
            if m in ("F", "G"):
                segments += 1
                extend(x, y)
            if in_polygon and m in ("F", "f"):
                extend(x, y)
        elif m == "+":
            h += sign * (1 if exact else ls.delta)
        elif m == "-":
            h -= sign * (1 if exact else ls.delta)
        elif m == "|":
            h += steps // 2 if exact else 180.0
        elif m == "[":
            stack.append((x, y, h))
        elif m == "]":
            x, y, h = stack.pop()
        elif m == "{":
            in_polygon = True
            extend(x, y)
        elif m == "}":
            in_polygon = False
            polygons += 1
    assert not stack, "unbalanced brackets"

    def r(v):
        v = round(v, 6)
        return 0.0 if v == 0 else v

    box = [[r(minx), r(miny)], [r(maxx), r(maxy)]]
    drawn_box = None
    if drawn[0] <= drawn[2]:
        drawn_box = [[r(drawn[0]), r(drawn[1])], [r(drawn[2]), r(drawn[3])]]
    return segments, polygons, box, drawn_box


def count_segments(s):
    return sum(1 for m in s if m in ("F", "G"))


def is_3d(ls):
    symbols = set(ls.axiom)
    for p in ls.productions:
        symbols.update(p[3])
    return bool(symbols & set("&^\\/"))


def stats(ls, s):
    d = {"modules": len(s)}
    if is_3d(ls):
        d["segments"] = count_segments(s)
        d["polygons"] = sum(1 for m in s if m == "}")
    else:
        seg, poly, box, drawn_box = turtle2d(ls, s)
        d["segments"] = seg
        d["polygons"] = poly
        if drawn_box is not None:  # nothing drawn: no box (graftal's scene is empty)
            d["bbox"] = box
            if drawn_box != box:
                d["drawn_bbox"] = drawn_box
    return d


# --------------------------------------------------------------------------- checks


def derive_strings(name, n=None):
    ls = load(os.path.join(EXAMPLES, name))
    return ["".join(s) for _, s in derive(ls, n)]


def check_book():
    """Compare with the strings printed in the book (book) text. Returns failures."""
    failures = []
    checks = []

    def expect(what, got, want):
        ok = got == want
        checks.append(what)
        print("%-4s %s" % ("ok" if ok else "FAIL", what))
        if not ok:
            print("     want %r\n     got  %r" % (want, got))
            failures.append(what)

    # Ch. 1.2 / Fig 1.3: b, a, ab, aba, abaab, abaababa, abaababaabaab.
    expect("Fig 1.3 Fibonacci words", derive_strings("fig1.3-fibonacci.l", 6),
           ["b", "a", "ab", "aba", "abaab", "abaababa", "abaababaabaab"])
    expect("Fig 1.3 word lengths are Fibonacci numbers",
           [len(w) for w in derive_strings("fig1.3-fibonacci.l", 10)],
           [1, 1, 2, 3, 5, 8, 13, 21, 34, 55, 89])
    # Ch. 1.2 Anabaena: ar, al br, bl ar ar, al al br al br, bl ar bl ar ar bl ar ar.
    ana = load(os.path.join(EXAMPLES, "fig1.4-anabaena.l"))
    expect("Fig 1.4 Anabaena catenula sequence",
           [" ".join(s) for _, s in derive(ana, 4)],
           ["ar", "al br", "bl ar ar", "al al br al br", "bl ar bl ar ar bl ar ar"])
    # Ch. 3.1: a -> b, b -> ba generates lengths 1, 1, 2, 3, 5, 8, ...
    expect("Sec 3.1 internode lengths 1,1,2,3,5,8",
           [len(w) for w in derive_strings("sec3.1-fibonacci-internode.l", 5)],
           [1, 1, 2, 3, 5, 8])
    # Ch. 3.4 hormone diffusion. The book prints baaaaaaaaa, bbaaaaaaaaa, bbbaaaaaaaa,
    # bbbbaaaaaaaa, bbbbbaaaaa: the number of a's is garbled in the transcription (the
    # axiom baaaaaaaa has 9 cells, and a DOL step never changes the length here); the
    # leading b's 1, 2, 3, 4, 5 are what the L-system produces.
    hd = derive_strings("sec3.4-hormone-diffusion.l", 4)
    expect("Sec 3.4 hormone diffusion (b's spread one cell a step)", hd,
           ["b" * (k + 1) + "a" * (8 - k) for k in range(5)])
    # Ch. 3.4: in ABCD[EF][G[HI[JKL]M]NOPQ], D is the left context of G and N its right.
    expect("Sec 3.4 context in trees",
           derive_strings("sec3.4-context-in-trees.l", 1)[1],
           "ABCD[ZF][Y[HI[TKL]U]VOPQ]")
    # Fig 3.12: acropetal signal J[I]I[I]I[I]I with J < I -> J (geometry stripped).
    strip = lambda w: re.sub(r"[F+\-]", "", w)
    expect("Fig 3.12 acropetal signal propagation",
           [strip(w) for w in derive_strings("fig3.12-acropetal-signal.l", 3)],
           ["J[I]I[I]I[I]I", "J[J]J[I]I[I]I", "J[J]J[J]J[I]I", "J[J]J[J]J[J]J"])
    # Fig 3.13: basipetal signal I[I]I[I]I[I]J with I > J -> J; lateral branches are
    # not part of the mother axis' context, so they are never reached.
    expect("Fig 3.13 basipetal signal propagation",
           [strip(w) for w in derive_strings("fig3.13-basipetal-signal.l", 3)],
           ["I[I]I[I]I[I]J", "I[I]I[I]J[I]J", "I[I]J[I]J[I]J", "J[I]J[I]J[I]J"])
    # Ch. 2: the dragon curve in its three printed forms derives the same curve:
    # Fl/Fr (declared modules), Fl/rF (pfg multi-letter predecessors), and l/r.
    fr = derive_strings("fig2.6-dragon-curve-fl-fr.l", 10)
    lr = derive_strings("fig2.6-dragon-curve-lr.l", 10)
    pf = derive_strings("fig2.6-dragon-curve-pfg.l", 10)
    expect("Fig 2.6 dragon: pfg Fl/rF form == l/r form", pf, lr)
    expect("Fig 2.6 dragon: Fl/Fr form rewritten with Fl->Fl, Fr->rF == l/r form",
           [w.replace("Fr", "rF") for w in fr], lr)
    # Ch. 2 Fig 2.2: F+F+F+F, F -> F+F-F-FF+F+F-F; each step multiplies segments by 8.
    ko = load(os.path.join(EXAMPLES, "fig2.2-quadratic-koch-island.l"))
    expect("Fig 2.2 segment counts 4, 32, 256, 2048",
           [count_segments(s) for _, s in derive(ko, 3)], [4, 32, 256, 2048])
    # The island is closed: the turtle comes back to the start point.
    expect("Fig 2.2 step 1 string", "".join(list(derive(ko, 1))[1][1]),
           "F+F-F-FF+F+F-F+F+F-F-FF+F+F-F+F+F-F-FF+F+F-F+F+F-F-FF+F+F-F")
    # Kolams: mango leaves grow polynomially (segments ~ n^2), anklets exponentially.
    mg = load(os.path.join(EXAMPLES, "fig6.6-mango-leaves.l"))
    seg = [count_segments(s) for _, s in derive(mg, 7)]
    d2 = [seg[k + 2] - 2 * seg[k + 1] + seg[k] for k in range(len(seg) - 2)]
    expect("Fig 6.6 mango leaves: constant second difference (quadratic growth)",
           len(set(d2)), 1)
    print("%d passed, %d failed" % (len(checks) - len(failures), len(failures)))
    return failures


# --------------------------------------------------------------------------- expected


STRING_LIMIT = 400  # strings up to this many characters go into the JSON


def example_files():
    return sorted(f for f in os.listdir(EXAMPLES) if f.endswith(".l"))


def expected_for(name):
    ls = load(os.path.join(EXAMPLES, name))
    entry = {"file": name, "format": "pfg" if ls.pfg else "cpfg",
             "derivation_length": ls.n, "dimension": 3 if is_3d(ls) else 2, "steps": []}
    chosen = set(range(0, ls.n + 1))
    for k, s in derive(ls):
        if k not in chosen:
            continue
        st = {"n": k}
        st.update(stats(ls, s))
        text = "".join(s)
        if len(text) <= STRING_LIMIT:
            st["string"] = text
        entry["steps"].append(st)
    return entry


def format_expected(entries):
    """A JSON array, one object per example, one line per step (diff-friendly)."""
    parts = []
    for e in entries:
        head = {k: v for k, v in e.items() if k != "steps"}
        lines = [json.dumps(st) for st in e["steps"]]
        parts.append(json.dumps(head)[:-1] + ', "steps": [\n   ' + ",\n   ".join(lines)
                     + "\n ]}")
    return "[\n " + ",\n ".join(parts) + "\n]\n"


def compare(exe, names=None, every_step=False):
    """Runs `EXE derive` and `EXE stats` on every example and compares with the
    reference: the final step always, every step with every_step. Returns the number of
    disagreements (each printed as file, step, expected, got)."""
    import subprocess
    bad = 0

    def run(args):
        r = subprocess.run([exe] + args, capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            raise RuntimeError("exit %d: %s" % (r.returncode, (r.stderr or r.stdout).strip()))
        return r.stdout

    def report(name, k, what, want, got):
        nonlocal bad
        bad += 1
        print("DIFF  %s n=%d %s: expected %s, got %s" % (name, k, what, want, got))

    for name in names or example_files():
        path = os.path.join(EXAMPLES, name)
        ls = load(path)
        ok = True
        for k, s in derive(ls):
            if not every_step and k not in (0, 1, ls.n):
                continue
            ref = stats(ls, s)
            try:
                got_string = run(["derive", path, "-n", str(k)]).strip()
                got = json.loads(run(["stats", path, "-n", str(k)]))
            except Exception as e:  # noqa: BLE001 - report and go on
                report(name, k, "run", "success", e)
                ok = False
                break
            text = "".join(s)
            if re.sub(r"\s", "", got_string) != text:
                report(name, k, "string", text if len(text) < 200 else "%d chars" % len(text),
                       got_string if len(got_string) < 200 else "%d chars" % len(got_string))
                ok = False
            for key in ("modules", "segments", "polygons"):
                if key in got and got[key] != ref[key]:
                    report(name, k, key, ref[key], got[key])
                    ok = False
            gb = got.get("bbox")
            if "bbox" in ref:
                if not gb or gb.get("min") is None:
                    report(name, k, "bbox", ref["bbox"], gb)
                    ok = False
                else:
                    box = [[gb["min"][0], gb["min"][1]], [gb["max"][0], gb["max"][1]]]
                    cands = [ref["bbox"]] + ([ref["drawn_bbox"]] if "drawn_bbox" in ref else [])
                    if not any(all(abs(box[i][j] - c[i][j]) < 1e-4 for i in range(2)
                                   for j in range(2)) for c in cands):
                        report(name, k, "bbox", cands, box)
                        ok = False
        print("%-5s %s" % ("ok" if ok else "FAIL", name))
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    for c in ("derive", "stats"):
        p = sub.add_parser(c)
        p.add_argument("file")
        p.add_argument("-n", type=int)
    sub.add_parser("check")
    p = sub.add_parser("compare", help="compare graftal's derive/stats with the reference")
    p.add_argument("exe")
    p.add_argument("files", nargs="*", help="example file names (default: all)")
    p.add_argument("--every-step", action="store_true",
                   help="compare every step, not only 0, 1 and the last")
    p = sub.add_parser("expected")
    p.add_argument("-o", "--output", default=os.path.join(ROOT, "tests",
                                                          "expected_examples.json"))
    a = ap.parse_args()
    if a.cmd == "derive":
        ls = load(a.file)
        s = list(derive(ls, a.n))[-1][1]
        print("".join(s))
    elif a.cmd == "stats":
        ls = load(a.file)
        k, s = list(derive(ls, a.n))[-1]
        d = {"steps": k}
        d.update(stats(ls, s))
        print(json.dumps(d))
    elif a.cmd == "check":
        failures = check_book()
        sys.exit(1 if failures else 0)
    elif a.cmd == "compare":
        bad = compare(a.exe, [os.path.basename(f) for f in a.files] or None, a.every_step)
        print("%d disagreements" % bad)
        sys.exit(1 if bad else 0)
    elif a.cmd == "expected":
        entries = [expected_for(f) for f in example_files()]
        with open(a.output, "w") as fh:
            fh.write(format_expected(entries))
        print("wrote %s (%d examples)" % (a.output, len(entries)))


if __name__ == "__main__":
    main()
