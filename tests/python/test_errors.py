"""Bad input from Python is a Python exception with a clear message, never a crash: parse
errors with their diagnostics (worded as the command words them), wrong types, negative
steps, unknown defines, limits, environments that raise, Ctrl-C."""
import os
import signal
import subprocess
import threading
import time

import pytest

import graftal

KOCH = "examples/fig2.2-quadratic-koch-island.l"
BROKEN = """Lsystem: 1
derivation length: 2
axiom: F
F --> F[+F
endlsystem
"""


def test_parse_error_carries_diagnostics_worded_as_the_command(tmp_path, graftal_exe):
    path = tmp_path / "broken.l"
    path.write_text(BROKEN)
    with pytest.raises(graftal.ParseError) as caught:
        graftal.load(path)
    error = caught.value
    assert isinstance(error, graftal.Error)
    d = error.diagnostics[0]
    assert (d.file, d.line, d.severity) == (str(path), 4, "error")
    assert d.column > 0 and d.end_line >= d.line
    assert "'['" in d.message
    # The message is the command's: `graftal derive` prints the same lines on stderr.
    done = subprocess.run([graftal_exe, "derive", str(path)], capture_output=True, text=True)
    assert done.returncode == 1
    assert str(error).splitlines() == done.stderr.splitlines()
    with pytest.raises(graftal.ParseError) as from_text:
        graftal.parse(BROKEN, file="broken.l")
    assert from_text.value.diagnostics[0].file == "broken.l"


def test_missing_file(tmp_path):
    with pytest.raises(graftal.ParseError) as caught:
        graftal.load(tmp_path / "nothing.l")
    assert caught.value.diagnostics[0].line == 0


def test_wrong_types_and_values(root):
    koch = graftal.load(root / KOCH)
    with pytest.raises(TypeError):
        koch.derive("3")
    with pytest.raises(TypeError):
        koch.derive(2.5)
    with pytest.raises(TypeError):
        graftal.load(root / KOCH, defines=["N", 3])
    with pytest.raises(TypeError, match="environment"):
        koch.derive(1, environment=42)
    with pytest.raises(ValueError, match="memory_limit"):
        koch.derive(1, memory_limit="lots")
    with pytest.raises(ValueError, match="precision"):
        koch.derive(1, precision="half")
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        koch.export(format="svg", colour="red")
    with pytest.raises(graftal.Error, match="format"):
        koch.export(format="bmp")


def test_negative_steps_name_the_keyword(root):
    koch = graftal.load(root / KOCH)
    with pytest.raises(graftal.Error) as caught:
        koch.derive(-1)
    assert "it must be 0 or more: steps" in str(caught.value)
    with pytest.raises(graftal.Error):
        list(koch.derivation(-3))


def test_unknown_define(root):
    with pytest.raises(ValueError, match="no #define NX .*it defines N"):
        graftal.load(root / KOCH, defines={"NX": 3})


def test_a_model_over_its_memory_limit(root):
    koch = graftal.load(root / KOCH)
    with pytest.raises(graftal.Error) as caught:
        koch.derive(9, memory_limit="1M")
    text = str(caught.value)
    assert "memory_limit" in text and "lower steps" in text


def test_an_environment_that_raises(root):
    model = graftal.load(root / "examples/open-crowding-stops-branches.l")

    def light(step, queries):
        if step == 2:
            raise ZeroDivisionError("no light at step 2")

    with pytest.raises(ZeroDivisionError, match="no light at step 2"):
        model.derive(4, environment=light)
    with pytest.raises(ValueError, match="answered 2 modules; the string has 1"):
        model.derive(2, environment=lambda step, q: [[1.0]] * (len(q.index) + 1))


def test_ctrl_c_stops_a_long_derivation():
    # A billion steps of a string that does not grow: hours of work in little memory.
    endless = graftal.parse("Lsystem: 1\naxiom: F\nF --> F\nendlsystem\n")
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        endless.derive(10**9, threads=1)
    assert time.monotonic() - start < 10
    # The model is still usable afterwards.
    assert str(endless.derive(3)) == "F"
