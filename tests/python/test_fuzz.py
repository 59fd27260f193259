"""A few seconds of the Python module's fuzzer (fuzz/fuzz_python.py): mutated models and
keyword arguments of random types through every entry point end in a value or a promised
exception, and never kill the interpreter (a crash shows as the child dying)."""
import os
import pathlib
import subprocess
import sys

import graftal


def test_fuzzer_finds_nothing(root, tmp_path):
    env = dict(os.environ)
    package = pathlib.Path(os.path.abspath(graftal.__file__)).parent.parent
    env["PYTHONPATH"] = os.pathsep.join([str(package), env.get("PYTHONPATH", "")])
    done = subprocess.run([sys.executable, str(root / "fuzz" / "fuzz_python.py"), "--seconds",
                           "3", "--seed", "7", "--findings", str(tmp_path)],
                          capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr + "".join(
        p.read_text() for p in tmp_path.glob("*.txt"))
    assert " 0 findings" in done.stdout
