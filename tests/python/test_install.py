"""`cmake --install` puts the package into the prefix's lib/python3/dist-packages, where it
imports and finds graftal's libraries (and the built-in surfaces) without the build tree."""
import os
import pathlib
import subprocess
import sys

import pytest


def test_installed_package_imports_and_derives(root, tmp_path):
    build = pathlib.Path(os.environ.get("GRAFTAL_BUILD_DIR", root / "build"))
    if not (build / "cmake_install.cmake").exists():
        pytest.skip("no configured build folder")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", str(build), "--prefix", str(prefix)], check=True,
                   capture_output=True)
    site = prefix / "lib" / "python3" / "dist-packages"
    assert (site / "graftal" / "__init__.py").is_file()
    assert (site / "graftal" / "__init__.pyi").is_file()
    script = (
        "import graftal, sys\n"
        "m = graftal.load(sys.argv[1])\n"
        "assert graftal.__file__.startswith(sys.argv[2]), graftal.__file__\n"
        "print(m.derive(1))\n"
        "print(len(m.export(format='glb', steps=1)) > 0)\n")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LD_LIBRARY_PATH")}
    env["PYTHONPATH"] = str(site)
    done = subprocess.run([sys.executable, "-c", script,
                           str(root / "examples/fig3.3-fibonacci-bush.l"), str(site)],
                          env=env, capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "True"
