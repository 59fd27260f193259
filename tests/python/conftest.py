"""Shared fixtures of the Python module's tests: the source tree, the graftal command of
the same build (to compare with), and a scratch folder per test."""
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def graftal_exe():
    exe = os.environ.get("GRAFTAL_EXE") or str(ROOT / "build" / "graftal")
    if not os.path.exists(exe):
        pytest.fail(f"the graftal command is missing: {exe} (set GRAFTAL_EXE)")
    return exe


@pytest.fixture(scope="session")
def cli(graftal_exe):
    """Runs `graftal ARGS...` and returns its standard output."""

    def run(*args):
        done = subprocess.run([graftal_exe, *map(str, args)], capture_output=True, text=True,
                              cwd=ROOT, check=True)
        return done.stdout

    return run
