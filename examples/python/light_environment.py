"""An environment written in Python: a light model in NumPy shading a growing tree.

The tree is an open L-system: every apex carries a communication module ?E(light). After
every derivation step graftal hands all ?E modules to the environment (the library's
Environment interface, here a Python object): their positions as NumPy arrays, and their
parameters to answer. The light model counts, for each ?E, the others above it inside a cone
of CONE degrees about the vertical, each shading it by ABSORB, and answers the light that
is left. Lit apices fork; shaded ones stop and become buds. cpfg does this with an external
environmental process and L-Py with Python code; here the environment is a class.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/light_environment.py tree.png
"""
import argparse

import numpy as np

import graftal

TREE = """/* A tree whose apices fork only where light reaches them */
#define THRESHOLD 0.45
Lsystem: 1
derivation length: 9
axiom: !(0.3) ;(13) F(3) A ?E(1)
A > ?E(l) : l >= THRESHOLD --> /(137.5) [&(40) !(0.06) ;(5) F(1) A ?E(1)] ^(10) !(0.06) ;(5) F(1.1) A ?E(1)
A > ?E(l) : l < THRESHOLD --> ;(3) @O(0.12)
endlsystem
"""


class LightModel:
    """Light from above: each ?E is shaded by every other ?E above it within a cone."""

    def __init__(self, cone_degrees=35.0, absorb=0.18):
        self.cos_cone = np.cos(np.radians(cone_degrees))
        self.absorb = absorb
        self.history = []

    def respond(self, step, queries):
        p = queries.position  # (n, 3), y is up
        d = p[None, :, :] - p[:, None, :]  # d[i, j]: from module i to module j
        distance = np.linalg.norm(d, axis=2)
        above = (d[:, :, 1] > 1e-9) & (d[:, :, 1] >= self.cos_cone * distance)
        light = (1 - self.absorb) ** above.sum(axis=1)
        queries.parameters[:, 0] = light
        self.history.append((step, len(p), float(light.mean()) if len(p) else 1.0))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", help="the tree's picture (.png is ray traced) or 3D file")
    parser.add_argument("--steps", type=int, default=9)
    args = parser.parse_args()

    tree = graftal.parse(TREE, file="shaded-tree.l")
    light = LightModel()
    grown = tree.derive(args.steps, environment=light)
    for step, apices, mean in light.history:
        print(f"step {step}: {apices} modules ask for light, mean light {mean:.2f}")
    counts = grown.symbol_counts()
    print(f"{counts.get('F', 0)} internodes, {counts.get('A', 0)} growing apices")
    tree.export(args.output, steps=args.steps, environment=LightModel(), size=(480, 480))


if __name__ == "__main__":
    main()
