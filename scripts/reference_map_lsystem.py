#!/usr/bin/env python3
"""Independent reference for map L-systems: vertex, edge and cell counts per step.

A deliberately different representation from graftal's half-edge map: every region is a
plain list of (edge id, traversed along the edge) pairs, and a region is divided by cutting
its list in two at each connected pair, recursively. The rules (docs/maps.md) are those of
the book's chapter 5 with graftal's documented choices where the chapter is silent:

- the axiom cycle runs clockwise around the first cell (the cell on the right of its
  unreversed edges); `+` branches enter the region on the left of their edge (seen along the predecessor's direction), `-` the right;
- an away branch pairs with the next branch of the same label counter-clockwise around
  the region when that one points towards its axis and starts at another vertex;
- pairs whose edges would cross are both dropped; branches entering the outside are removed.

Usage: reference_map_lsystem.py FILE.l [STEPS]  -> one line per step: step V E cells
"""
import re
import sys


def parse(path):
    axiom, prods, length = None, {}, 0
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    for raw in text.splitlines():
        line = raw.split("//")[0].strip()
        if not line or line.startswith("#") or line.lower().startswith("map l"):
            continue
        if line.lower().startswith("derivation length:"):
            length = int(line.split(":", 1)[1])
        elif line.lower().startswith("axiom:"):
            body = line.split(":", 1)[1].replace(" ", "")
            axiom = [(m.group(2), m.group(1) == "~") for m in re.finditer(r"(~?)(\w)", body)]
        elif "-->" in line or "->" in line:
            pred, succ = re.split(r"-->|->", line, maxsplit=1)
            axis, branches = [], []
            for m in re.finditer(r"\[([+-])(~?)(\w)\]|(~?)(\w)", succ.replace(" ", "")):
                if m.group(1):
                    branches.append((len(axis), m.group(1) == "+", m.group(2) == "~", m.group(3)))
                else:
                    axis.append((m.group(5), m.group(4) == "~"))
            prods[pred.strip()] = (axis, branches)
    return axiom, prods, length


class Counter:
    def __init__(self, start=0):
        self.n = start

    def __call__(self):
        self.n += 1
        return self.n - 1


def axiom_map(axiom):
    # The axiom cycle runs clockwise: the cell is on the right of its unreversed edges.
    n = len(axiom)
    edges = {}
    for i, (lab, rev) in enumerate(axiom):
        a, b = i, (i + 1) % n
        edges[i] = (lab, b, a) if rev else (lab, a, b)
    cell = [(i, axiom[i][1]) for i in reversed(range(n))]
    outside = [(i, not axiom[i][1]) for i in range(n)]
    return edges, [outside, cell], n


def split(items):
    """items: list of ('e', id, along) and ('s', vertex, chord id, chord edge id, is_tail).
    Returns the list of regions (lists of (id, along)) made by cutting at every chord."""
    stubs = [i for i, it in enumerate(items) if it[0] == "s"]
    if not stubs:
        return [[(it[1], it[2]) for it in items]]
    i = stubs[0]
    j = next(k for k in stubs[1:] if items[k][2] == items[i][2])
    _, vi, _, ce, i_tail = items[i]
    # piece one walks from vertex(i) to vertex(j) inside, and closes back along the chord
    one = items[i + 1:j] + [("e", ce, not i_tail)]
    two = items[j + 1:] + items[:i] + [("e", ce, i_tail)]
    return split(one) + split(two)


def step(edges, regions, vcount, prods):
    vnew = Counter(vcount)
    enew = Counter()
    chain = {}
    new_edges = {}
    for e in sorted(edges):
        lab, t, h = edges[e]
        axis, branches = prods[lab]
        verts = [t] + [vnew() for _ in axis[1:]] + [h]
        subs = []
        for i, (alab, rev) in enumerate(axis):
            ne = enew()
            a, b = verts[i], verts[i + 1]
            new_edges[ne] = (alab, b, a) if rev else (alab, a, b)
            subs.append((ne, not rev))
        chain[e] = (verts, subs, branches)
    chord = Counter()
    result = []
    pending_chords = []
    for ri, region in enumerate(regions):
        items = []
        for e, along in region:
            verts, subs, branches = chain[e]
            n = len(subs)
            order = range(n + 1) if along else range(n, -1, -1)
            for k in order:
                brs = branches if along else list(reversed(branches))
                for (bk, left, towards, lab) in brs:
                    if bk == k and left == along and ri != 0:
                        items.append(["s", verts[k], lab, towards])
                if along and k < n:
                    items.append(["e", subs[k][0], subs[k][1]])
                if not along and k > 0:
                    items.append(["e", subs[k - 1][0], not subs[k - 1][1]])
        stubs = [i for i, it in enumerate(items) if it[0] == "s"]
        m = len(stubs)
        pairs = {}
        for a in range(m):
            sa = items[stubs[a]]
            if sa[3]:
                continue
            for d in range(1, m):
                sb = items[stubs[(a + d) % m]]
                if sb[2] != sa[2]:
                    continue
                if sb[3] and sb[1] != sa[1]:
                    pairs[a] = (a + d) % m
                break
        chords = [(min(a, b), max(a, b), a) for a, b in pairs.items()]
        good = []
        for (i, j, away) in chords:
            crosses = any((i < k < j) != (i < l < j) for (k, l, _) in chords if (k, l) != (i, j))
            if not crosses:
                good.append((i, j, away))
        keep = {}
        for (i, j, away) in good:
            cid = chord()
            ce = len(new_edges) + len(pending_chords)
            towards = j if away == i else i
            pending_chords.append((items[stubs[away]][2], items[stubs[away]][1],
                                   items[stubs[towards]][1]))
            keep[stubs[i]] = ("s", items[stubs[i]][1], cid, ce, away == i)
            keep[stubs[j]] = ("s", items[stubs[j]][1], cid, ce, away == j)
        final = []
        for idx, it in enumerate(items):
            if it[0] == "e":
                final.append(("e", it[1], it[2]))
            elif idx in keep:
                final.append(keep[idx])
        result.extend(split(final) if ri != 0 else [[(it[1], it[2]) for it in final]])
    base = len(new_edges)
    for k, (lab, t, h) in enumerate(pending_chords):
        new_edges[base + k] = (lab, t, h)
    return new_edges, result, vnew.n


def counts(edges, regions):
    verts = set()
    for lab, t, h in edges.values():
        verts.add(t)
        verts.add(h)
    return len(verts), len(edges), len(regions) - 1


def main():
    axiom, prods, length = parse(sys.argv[1])
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else length
    edges, regions, vcount = axiom_map(axiom)
    print(0, *counts(edges, regions))
    for s in range(1, steps + 1):
        edges, regions, vcount = step(edges, regions, vcount, prods)
        print(s, *counts(edges, regions))


if __name__ == "__main__":
    main()
