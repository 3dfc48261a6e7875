"""The package says what it is: topoplan.__version__ (and the commit it was built from), and type
stubs (_core.pyi, py.typed) that match the compiled module's signatures."""

import os
import pathlib
import subprocess
import sys

import topoplan

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_version_and_commit():
    assert topoplan.__version__.count(".") == 2
    assert all(part.isdigit() for part in topoplan.__version__.split("."))
    assert isinstance(topoplan._core.__commit__, str) and topoplan._core.__commit__


def test_stubs_match_the_module():
    env = dict(os.environ)
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_stubs.py"), "--check"],
                       env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    package = pathlib.Path(topoplan.__file__).parent
    assert (package / "_core.pyi").exists() and (package / "py.typed").exists()
