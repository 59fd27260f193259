#!/usr/bin/python3
"""A fuzzer of the Python module's entry points: mutated models (the parse corpus and the
examples, bytes flipped, cut, repeated, spliced) through parse(), derive(), derivation(),
statistics(), predict(), scene(), mesh() and export(), with keyword arguments of random
values and types. Every outcome must be a value or one of the exceptions the module
promises (graftal.Error, TypeError, ValueError, OverflowError, KeyError, IndexError); an
interpreter crash or any other exception is a finding, written with its input to FINDINGS.

  PYTHONPATH=build/python /usr/bin/python3 fuzz/fuzz_python.py [--seconds 60] [--seed 1]
      [--findings build-fuzz/findings/python]

tests/python/test_fuzz.py runs it for a few seconds; a crash of the interpreter shows there
as the child process dying.
"""
import argparse
import pathlib
import random
import sys
import time
import traceback

import graftal

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXPECTED = (graftal.Error, TypeError, ValueError, OverflowError, KeyError, IndexError)
FORMATS = ["svg", "png", "obj", "ply", "glb", "gif", "mid", "musicxml", "bmp", "", "frames"]
VALUES = [None, -1, 0, 1, 2, 3, 7, 2**31, -2**63, 2**64, 0.5, float("nan"), "2", "1K", "x",
          (1, 2), (1, 2, 3), [], {}, b"\0", "#zzzzzz", "#336699", "front", "single", "double",
          "cpfg", "graftal"]


def corpus():
    texts = []
    for folder in (ROOT / "fuzz" / "corpus" / "parse", ROOT / "examples"):
        for path in sorted(folder.glob("*"))[:400]:
            if path.is_file() and path.stat().st_size < 20000:
                texts.append(path.read_bytes())
    return texts


def mutate(rng, data, texts):
    data = bytearray(data)
    for _ in range(rng.randint(1, 6)):
        choice = rng.random()
        if not data or choice < 0.2:
            data += rng.choice(texts)[:rng.randint(0, 400)]
        elif choice < 0.5:
            data[rng.randrange(len(data))] = rng.choice(b"()[]{}+-*/:;<>?,.$%&!~#@0123456789FAB \n")
        elif choice < 0.7:
            i = rng.randrange(len(data))
            del data[i:i + rng.randint(1, 40)]
        elif choice < 0.85:
            i = rng.randrange(len(data))
            data[i:i] = data[i:i + rng.randint(1, 30)] * rng.randint(1, 4)
        else:
            data[rng.randrange(len(data))] = rng.randrange(256)
    return bytes(data)


def keywords(rng, names):
    return {name: rng.choice(VALUES) for name in names if rng.random() < 0.3}


def exercise(rng, text):
    """One input through the entry points; returns normally or raises what it may."""
    functions = rng.choice([None, {1: lambda x: x * 2}, {"N": lambda x: 1 / x},
                            {2: lambda x: "x"}, {1: rng.choice(VALUES)}])
    model = graftal.parse(text.decode("utf-8", "replace"), file="fuzz.l",
                          defines=rng.choice([None, {}, {"N": rng.choice(VALUES[1:9])}]),
                          functions=None if rng.random() < 0.7 else functions)
    steps = rng.choice([None, 0, 1, 2, 3, 4])
    if isinstance(model, graftal.MapModel):
        geometry = rng.choice(["siero", "relaxed", "spline", rng.choice(VALUES)])
        str(model.derive(rng.choice([0, 1, 2, 3]), threads=1, geometry=geometry))
        model.export(format=rng.choice(["svg", "png", "pdf", rng.choice(FORMATS)]),
                     steps=rng.choice([0, 1, 2]), threads=1, size=(32, 32),
                     fill=rng.choice(["none", "age", "sides", "labels", "x"]))
        return
    limits = dict(memory_limit="8M", threads=1)
    try:
        s = model.derive(steps, **limits, **keywords(rng, ["seed", "precision", "random"]))
    except graftal.Error:
        return
    str(s), len(s), s.symbol_counts()
    s.symbols.sum(), s.parameters.sum(), s.parameter_offsets[-1]
    if len(s):
        s[rng.randrange(-len(s), len(s))]
    for _ in zip(range(3), model.derivation(steps, **limits)):
        pass
    model.predict(rng.choice([0, 1, 5, 30]))
    model.statistics(steps, **limits, geometry=rng.random() < 0.5)
    if len(s) < 20000:
        scene = s.scene()
        scene.segments, scene.polygon_vertices, scene.bounds
        if len(scene.segments) < 5000:
            scene.mesh(rng.choice([3, 4, 8]))
        options = keywords(rng, ["size", "line_width", "margin", "background", "view",
                                 "viewpoint", "samples_per_pixel", "tube_sides", "spline"])
        options.setdefault("size", (32, 32))
        options["samples_per_pixel"] = 1
        model.export(format=rng.choice(FORMATS), steps=steps, **limits, **options)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--findings", type=pathlib.Path,
                        default=ROOT / "build-fuzz" / "findings" / "python")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    texts = corpus()
    end = time.monotonic() + args.seconds
    runs = findings = 0
    while time.monotonic() < end:
        text = mutate(rng, rng.choice(texts), texts)
        runs += 1
        try:
            exercise(random.Random(runs), text)
        except EXPECTED:
            pass
        except Exception:  # a finding: anything the module does not promise
            findings += 1
            args.findings.mkdir(parents=True, exist_ok=True)
            (args.findings / f"input-{args.seed}-{runs}.l").write_bytes(text)
            (args.findings / f"input-{args.seed}-{runs}.txt").write_text(traceback.format_exc())
    print(f"fuzz_python: {runs} inputs, {findings} findings")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
