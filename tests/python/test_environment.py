"""An environment written in Python answers the ?E modules each step (the library's
Environment interface): the same answers as the built-in `occupancy` environment give the
same plant as `graftal derive`."""
import numpy as np

import graftal

CROWDING = "examples/open-crowding-stops-branches.l"


class Occupancy:
    """How many other ?E modules lie within `radius` of each, as `environment: occupancy
    radius R` answers."""

    def __init__(self, radius):
        self.radius = radius
        self.steps = []

    def respond(self, step, queries):
        self.steps.append(step)
        p = queries.position
        d2 = ((p[:, None, :] - p[None, :, :]) ** 2).sum(axis=2)
        others = (d2 <= self.radius ** 2 * (1 + 1e-9)).sum(axis=1) - 1
        queries.parameters[:, 0] = others


def test_python_environment_gives_the_commands_plant(root, cli):
    model = graftal.load(root / CROWDING)
    env = Occupancy(0.9)
    s = model.derive(8, environment=env, threads=1)
    assert str(s) + "\n" == cli("derive", CROWDING, "-n", 8)
    # Asked for the axiom (step 0) and after every step.
    assert env.steps == list(range(9))


def test_queries_carry_the_turtle_frame(root):
    model = graftal.parse("Lsystem: 1\nderivation length: 1\naxiom: F(2) ?E(0,0) +(90) F ?E(7)\n"
                          "endlsystem\n", file="frame.l")
    seen = {}

    def env(step, queries):
        seen["index"] = queries.index.tolist()
        seen["position"] = queries.position.copy()
        seen["heading"] = queries.heading.copy()
        seen["parameters"] = queries.parameters
        return [[step, 1.5], [step + 10]]

    s = model.derive(0, environment=env)
    assert seen["index"] == [1, 4]
    assert np.allclose(seen["position"], [[0, 2, 0], [-1, 2, 0]])
    assert np.allclose(seen["heading"][1], [-1, 0, 0])
    assert [list(p) for p in seen["parameters"]] == [[0, 0], [7]]
    assert str(s) == "F(2)?E(0,1.5)+(90)F?E(10)"


def test_statistics_and_exports_derive_with_the_python_environment(root, cli, tmp_path):
    import json
    model = graftal.load(root / CROWDING)
    stats = model.statistics(8, environment=Occupancy(0.9))
    assert stats["modules"] == json.loads(cli("stats", CROWDING, "-n", 8))["modules"]
    cli("render", CROWDING, "-n", 8, "-o", tmp_path / "crowd.svg")
    svg = model.export(format="svg", steps=8, environment=Occupancy(0.9))
    assert svg == (tmp_path / "crowd.svg").read_bytes()
    # An environment that answers otherwise grows another plant.
    never = model.statistics(8, environment=lambda step, q: None)
    assert never["modules"] > stats["modules"]
