"""graftal.load / graftal.parse / derive: strings equal to the command's, NumPy views of the
library's storage, counts and growth, step by step, statistics as `graftal stats`."""
import json
import pathlib
import pickle

import numpy as np
import pytest

import graftal

KOCH = "examples/fig2.2-quadratic-koch-island.l"
HONDA = "examples/honda-monopodial-tree.l"


@pytest.mark.parametrize("example, steps", [
    (KOCH, 2),
    ("examples/fig1.3-fibonacci.l", None),
    (HONDA, 4),
    ("examples/fig3.16-stochastic-bush.l", 3),
    ("examples/open-crowding-stops-branches.l", 5),
])
def test_derived_string_is_the_commands(root, cli, example, steps):
    model = graftal.load(root / example)
    args = ["derive", example] + (["-n", steps] if steps is not None else [])
    assert str(model.derive(steps)) + "\n" == cli(*args)


def test_seed_and_defines_as_on_the_command_line(root, cli):
    model = graftal.load(root / HONDA, defines={"R2": 0.8})
    assert str(model.derive(3, seed=7)) + "\n" == cli("derive", HONDA, "-n", 3, "-D", "R2=0.8",
                                                      "--seed", 7)
    assert model.overrides == {"R2": "0.8"}


def test_cpfg_random_numbers_as_on_the_command_line(root, cli):
    bush = "examples/fig3.16-stochastic-bush.l"
    expected = cli("derive", bush, "-n", 4, "--random", "cpfg")
    model = graftal.load(root / bush)
    assert str(model.derive(4, random="cpfg")) + "\n" == expected
    assert str(graftal.load(root / bush, random="cpfg").derive(4)) + "\n" == expected
    assert str(model.derive(4)) + "\n" == cli("derive", bush, "-n", 4)
    assert str(model.derive(4)) + "\n" != expected
    assert str(model.derive(4, seed=5, random="cpfg")) + "\n" == cli(
        "derive", bush, "-n", 4, "--random", "cpfg", "--seed", 5)
    with pytest.raises(ValueError, match="random='lcg': expected 'graftal'"):
        model.derive(random="lcg")


def test_parse_text_and_print(root):
    text = (root / KOCH).read_text()
    koch = graftal.parse(text, file="koch.l")
    s = koch.derive(1)
    assert str(s) == "F+F-F-FF+F+F-F+F+F-F-FF+F+F-F+F+F-F-FF+F+F-F+F+F-F-FF+F+F-F"
    assert len(s) == 59 and s.steps == 1
    assert s[0] == ("F", ()) and s[-1] == ("F", ())
    assert repr(s) == "<graftal.ModuleString steps=1 modules=59>"
    assert koch.derivation_length == 3
    assert "F --> F+F-F-FF+F+F-F" in str(koch)


def test_arrays_are_views_of_the_library_storage(root):
    honda = graftal.load(root / HONDA)
    s = honda.derive(5)
    symbols, offsets, params = s.symbols, s.parameter_offsets, s.parameters
    assert symbols.dtype == np.uint8 and offsets.dtype == np.uint32
    assert params.dtype == np.float32
    assert len(symbols) == len(s) and len(offsets) == len(s) + 1
    assert offsets[-1] == len(params)
    # No copy: the same memory each time, owned by the ModuleString, and read-only.
    assert s.symbols.ctypes.data == symbols.ctypes.data
    assert s.parameters.ctypes.data == params.ctypes.data
    assert not params.flags.writeable and not params.flags.owndata
    assert np.shares_memory(np.asarray(memoryview(s)), symbols)
    # The first module is !(0.2): its parameter is float32(0.2).
    names = honda.symbols
    assert names[symbols[0]] == "!"
    assert params[offsets[0]:offsets[1]].tolist() == [np.float32(0.2)]
    # Counting with NumPy agrees with the library's counts.
    counts = s.symbol_counts()
    assert counts["F"] == int(np.count_nonzero(symbols == names.index("F")))
    # Views outlive the name they came from.
    del s
    assert names[symbols[0]] == "!"


def test_double_precision_and_no_parameters(root):
    honda = graftal.load(root / HONDA)
    assert honda.derive(2, precision="double").parameters.dtype == np.float64
    koch = graftal.load(root / KOCH).derive(1)
    assert koch.parameters.size == 0
    assert koch.parameter_offsets.tolist() == [0] * 60


def test_counts_and_growth_prediction_match_statistics(root, cli):
    koch = graftal.load(root / KOCH)
    g = koch.predict(4)
    assert g["exact"] and g["modules"] == [7, 59, 475, 3803, 30427]
    assert g["symbols"]["F"] == 4 * 8 ** 4
    stats = koch.statistics(2, geometry=False)
    cli_stats = json.loads(cli("stats", KOCH, "-n", 2, "--no-geometry"))
    assert stats["modules"] == cli_stats["modules"] == 475
    assert stats["symbols"] == cli_stats["symbols"]
    full = koch.statistics(2)
    assert full["segments"] == 256 and full["polygons"] == 0
    (lo, hi) = full["bounds"]
    assert lo[:2] == pytest.approx((-21, -5)) and hi[:2] == pytest.approx((5, 21))
    big = koch.predict(40)
    assert big["modules"][-1] > 2 ** 64  # exact Python ints past 64 bits


def test_derivation_step_by_step(root):
    koch = graftal.load(root / KOCH)
    sizes = [len(s) for s in koch.derivation(3)]
    assert sizes == [7, 59, 475, 3803]
    steps = list(koch.derivation(2))
    assert [s.steps for s in steps] == [0, 1, 2]
    assert str(steps[0]) == "F+F+F+F"
    assert steps[-1] == koch.derive(2)
    d = koch.derivation(1)
    d.step()
    assert d.steps_done == 1 and len(d.current) == 59


def test_model_folder_view_file_and_warnings(root, tmp_path):
    folder = tmp_path / "plant"
    folder.mkdir()
    (folder / "plant.l").write_text((root / KOCH).read_text())
    (folder / "plant.v").write_text("line style: cylinder\nsparkle: 9\n")
    model = graftal.load(folder)
    assert len(model.derive(1)) == 59
    # The view file's unknown line is a warning returned, not printed.
    [w] = model.warnings
    assert (w.severity, w.line, pathlib.Path(w.file).name) == ("warning", 2, "plant.v")
    assert "unknown view-file line 'sparkle: 9'" in w.message
    assert str(w).endswith("warning: unknown view-file line 'sparkle: 9', ignored")
    same = graftal.load(folder / "plant.l", view=folder / "plant.v")
    assert len(same.warnings) == 1


def test_models_pickle_as_their_source(root):
    honda = graftal.load(root / HONDA, defines={"R2": 0.7})
    again = pickle.loads(pickle.dumps(honda))
    assert str(again.derive(3)) == str(honda.derive(3))
    text = graftal.parse("axiom: A\nA --> AB\nB --> A\n", file="t.l")
    assert str(pickle.loads(pickle.dumps(text)).derive(3)) == "ABAAB"
    assert str(honda.with_defines({"R2": 0.9}).derive(3)) != str(honda.derive(3))


def test_other_threads_run_while_the_library_works(root):
    import threading
    koch = graftal.load(root / KOCH)
    ticks, running = [0], [True]

    def ticker():
        while running[0]:
            ticks[0] += 1

    thread = threading.Thread(target=ticker)
    thread.start()
    try:
        before = ticks[0]
        s = koch.derive(7, threads=1)  # 4 * 8**7 segments' worth of modules: a second or so
    finally:
        running[0] = False
        thread.join()
    assert len(s) == koch.predict(7)["modules"][-1]
    assert ticks[0] - before > 10000  # the GIL was free while it derived


def test_import_is_light(root):
    """`import graftal` loads neither NumPy nor pandas nor Dask: a short script pays for
    what it uses (NumPy comes with the first array)."""
    import os
    import subprocess
    import sys
    script = ("import sys, graftal\n"
              "heavy = ('numpy', 'pandas', 'distributed', 'dask')\n"
              "print(sorted(m for m in heavy if m in sys.modules))\n"
              "s = graftal.load(sys.argv[1]).derive(2)\n"
              "print(s.symbols.dtype, 'numpy' in sys.modules, callable(graftal.sweep))\n")
    done = subprocess.run([sys.executable, "-c", script, str(root / KOCH)], env=os.environ,
                          capture_output=True, text=True, check=True)
    assert done.stdout.splitlines() == ["[]", "uint8 True True"]
