"""Map L-systems (the book's chapter 5) from Python: graftal.load() reads one as a MapModel,
its derived cells print as `graftal derive` prints them, its statistics are `graftal stats`'s
and its pictures `graftal render`'s."""
import json
import pickle

import pytest

import graftal

SQUARE = "examples/fig5.1-square-map.l"
LAYER = "examples/fig5.2-cell-layer.l"


def test_a_map_derives_to_the_commands_cells(root, cli):
    model = graftal.load(root / LAYER)
    assert isinstance(model, graftal.MapModel)
    assert model.derivation_length == 5
    cells = model.derive(4)
    assert str(cells) == cli("derive", LAYER, "-n", 4)
    assert (cells.steps, cells.cells) == (4, 16)
    assert cells.positions.shape == (cells.vertices, 3)
    relaxed = model.derive(3, geometry="relaxed", outline="polygon")
    assert str(relaxed) == cli("derive", LAYER, "-n", 3, "--map-geometry", "relaxed",
                               "--map-outline", "polygon")


def test_map_statistics_are_the_commands(root, cli):
    stats = graftal.load(root / SQUARE).statistics(geometry="relaxed")
    expected = json.loads(cli("stats", SQUARE, "--map-geometry", "relaxed"))
    assert stats["cells"] == expected["cells"]
    assert stats["edges"] == expected["edges"]
    assert stats["vertices"] == expected["vertices"]
    assert {str(k): v for k, v in stats["cell_sides"].items()} == expected["cell sides"]
    assert stats["relaxation_iterations"] == expected["relaxation iterations"]


def test_map_pictures_are_the_commands(root, cli, tmp_path):
    model = graftal.load(root / LAYER)
    cli("render", LAYER, "-n", 4, "--map-fill", "age", "-o", tmp_path / "layer.svg")
    svg = model.export(format="svg", steps=4, fill="age")
    assert svg == (tmp_path / "layer.svg").read_bytes()
    cli("render", LAYER, "--map-geometry", "spline", "-o", tmp_path / "layer.png")
    model.export(tmp_path / "mine.png", geometry="spline")
    assert (tmp_path / "mine.png").read_bytes() == (tmp_path / "layer.png").read_bytes()
    assert model._repr_svg_().startswith("<?xml")


def test_map_text_and_pickles(root):
    text = (root / SQUARE).read_text()
    model = graftal.parse(text, file="square.l")
    again = pickle.loads(pickle.dumps(model))
    assert str(again.derive(2)) == str(model.derive(2))


def test_bad_map_requests_are_python_errors(root):
    model = graftal.load(root / SQUARE)
    with pytest.raises(ValueError, match="geometry 'bent'"):
        model.derive(geometry="bent")
    with pytest.raises(ValueError, match="fill 'stripes'"):
        model.export(format="svg", fill="stripes")
    with pytest.raises(graftal.Error, match="a map L-system is drawn as a picture"):
        model.export(format="glb")
    with pytest.raises(ValueError, match="takes no view file"):
        graftal.load(root / SQUARE, view=root / "examples" / "cpfg-generalized-cylinder.v")
    with pytest.raises(graftal.ParseError):
        graftal.parse("map L-system: 1\naxiom: ab\nendlsystem\n", file="bad.l")


def square_with_length(root):
    """The square map with its derivation length a #define."""
    text = (root / SQUARE).read_text().replace("derivation length: 4",
                                               "#define LENGTH 2\nderivation length: LENGTH")
    return graftal.parse(text, file="square.l")


def test_map_with_defines(root):
    model = square_with_length(root)
    assert model.derivation_length == 2 and model.derive().cells == 4
    longer = model.with_defines({"LENGTH": 3})
    assert isinstance(longer, graftal.MapModel)
    assert (longer.derivation_length, longer.overrides) == (3, {"LENGTH": "3"})
    assert longer.derive().cells == 8
    assert pickle.loads(pickle.dumps(longer)).derivation_length == 3
    with pytest.raises(ValueError, match="no #define WIDTH .it defines LENGTH"):
        model.with_defines({"WIDTH": 2})
    with pytest.raises(ValueError, match="no #define LENGTH .it defines none"):
        graftal.load(root / SQUARE, defines={"LENGTH": 2})


def test_a_sweep_over_a_map(root, cli):
    model = square_with_length(root)
    frame = graftal.sweep(model, {"LENGTH": [1, 2, 3]}, export="svg", size=64)
    assert frame["LENGTH"].tolist() == [1, 2, 3]
    assert frame["cells"].tolist() == [2, 4, 8]
    stats = json.loads(cli("stats", SQUARE, "-n", 3))
    row = frame.iloc[2]
    assert (row["edges"], row["vertices"]) == (stats["edges"], stats["vertices"])
    assert row["svg"] == model.export(format="svg", steps=3, size=(64, 64))
    with pytest.raises(ValueError, match="draws no random numbers"):
        graftal.sweep(model, {"seed": [1, 2]})


def test_show_draws_a_map_flat(root):
    viewer = graftal.show(graftal.load(root / LAYER), steps=3)
    assert viewer.glb is None and viewer.svg.startswith(b"<?xml")
    assert "data:image/svg+xml;base64," in viewer._repr_html_()
