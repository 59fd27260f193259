"""Python callables for func(id, x): load(..., functions=...) makes the derivation call them
(the library's user functions), keyed by func()'s id or a name the model gives it; what a
callable raises is a graftal.Error naming the production, the module and the step."""
import pickle

import pytest

import graftal

GROWING = ("#define LIGHT 1\nLsystem: 1\nderivation length: 3\naxiom: A(0)\n"
           "A(t) : * --> F(func(LIGHT, t)) A(t + 1)\nendlsystem\n")


def light(x):
    return 2 * x + 1


def test_a_callable_answers_func_by_define_or_by_id():
    by_name = graftal.parse(GROWING, file="grow.l", functions={"LIGHT": light})
    assert str(by_name.derive()) == "F(1)F(3)F(5)A(3)"
    by_id = graftal.parse(GROWING, file="grow.l", functions={1: lambda x: x * x})
    assert str(by_id.derive(threads=2)) == "F(0)F(1)F(4)A(3)"
    # The model's other readings keep the callables: step by step, statistics, exports.
    assert [str(s) for s in by_name.derivation(2)] == ["A(0)", "F(1)A(1)", "F(1)F(3)A(2)"]
    assert by_name.statistics(3)["modules"] == 4
    assert b"<svg" in by_name.export(format="svg")
    assert str(by_name.with_defines({}).derive(1)) == "F(1)A(1)"


def test_a_callable_stands_for_an_item_of_the_function_set(tmp_path):
    (tmp_path / "shapes.fset").write_text(
        "funcgalleryver 1 1\nitems: 2\n"
        "fver 1 1\nname: RISE\nsamples: 0\nflip: off\npoints: 4\n"
        "0 0\n0.333333 0.333333\n0.666667 0.666667\n1 1\n"
        "fver 1 1\nname: FLAT.func\nsamples: 0\nflip: off\npoints: 4\n"
        "0 2\n0.333333 2\n0.666667 2\n1 2\n")
    (tmp_path / "m.v").write_text("angle increment: 30\nfunction set: shapes.fset\n")
    (tmp_path / "m.l").write_text("Lsystem: 1\nderivation length: 1\nAxiom: A\n"
                                  "A --> B(func(FLAT, 0.5), func(RISE, 0.5))\nendlsystem\n")
    assert str(graftal.load(tmp_path).derive()) == "B(2,0.5)"
    seen = []

    def flat(x):
        seen.append(x)
        return 9

    model = graftal.load(tmp_path, functions={"FLAT": flat})
    assert str(model.derive()) == "B(9,0.5)"
    assert seen == [0.5]
    with pytest.raises(ValueError, match="knows no function 'DARK'.*RISE, FLAT"):
        graftal.load(tmp_path, functions={"DARK": flat})


def test_a_model_with_callables_pickles_with_them():
    model = graftal.parse(GROWING, file="grow.l", functions={"LIGHT": light})
    again = pickle.loads(pickle.dumps(model))
    assert str(again.derive()) == "F(1)F(3)F(5)A(3)"


def test_an_exception_in_a_callable_names_the_production_module_and_step():
    def refuses(x):
        if x >= 2:
            raise ValueError("too dark")
        return x

    model = graftal.parse(GROWING, file="grow.l", functions={"LIGHT": refuses})
    with pytest.raises(graftal.Error) as raised:
        model.derive()
    assert str(raised.value) == (
        "grow.l:5:1: error: 'func(1, t)': func(1, 2) failed: the Python function LIGHT "
        "raised ValueError: too dark (while rewriting module 2 'A(2)' in derivation step 3)")
    assert isinstance(raised.value.__cause__, ValueError)
    assert raised.value.diagnostics[0].line == 5


def test_bad_callables_and_answers_are_python_errors():
    with pytest.raises(TypeError, match="expected a callable"):
        graftal.parse(GROWING, file="grow.l", functions={"LIGHT": 3})
    with pytest.raises(TypeError, match="expected a dict"):
        graftal.parse(GROWING, file="grow.l", functions=[light])
    with pytest.raises(ValueError, match="not a func\\(\\) id"):
        graftal.parse(GROWING, file="grow.l", functions={0: light})
    words = graftal.parse(GROWING, file="grow.l", functions={"LIGHT": lambda x: "1.5"})
    with pytest.raises(graftal.Error, match="returned '1.5', not a number"):
        words.derive()
    infinite = graftal.parse(GROWING, file="grow.l", functions={"LIGHT": lambda x: float("inf")})
    with pytest.raises(graftal.Error, match="func\\(1, 0\\) gave .*, not a finite number"):
        infinite.derive()


def test_a_callable_called_by_its_name_in_expressions():
    # As L-Py's models call Python functions: light(t) in the model, {"light": f} here.
    text = ("#define K 2\nLsystem: 1\nderivation length: 3\naxiom: A(0)\n"
            "A(t) : * --> F(light(t) * K) A(t + 1)\nendlsystem\n")
    model = graftal.parse(text, file="named.l", functions={"light": light})
    assert str(model.derive()) == "F(2)F(6)F(10)A(3)"
    assert model.defines == {"K": "2"}  # the name is no constant of the model
    assert str(model.with_defines({"K": 1}).derive(2)) == "F(1)F(3)A(2)"
    assert str(pickle.loads(pickle.dumps(model)).derive(1)) == "F(2)A(1)"
    with pytest.raises(graftal.ParseError, match="named.l:5:16: error: unknown function 'light'"):
        graftal.parse(text, file="named.l")
    with pytest.raises(ValueError, match="knows no function 'dark'.* call as dark\\(x\\)"):
        graftal.parse(text, file="named.l", functions={"light": light, "dark": light})

    def fails(x):
        raise ArithmeticError("no light here")

    with pytest.raises(graftal.Error, match="the Python function light raised ArithmeticError"):
        graftal.parse(text, file="named.l", functions={"light": fails}).derive()
