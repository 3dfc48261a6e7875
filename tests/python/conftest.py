"""Shared fixtures of the Python tests: the `topoplan` CLI next to the module (TOPOPLAN_EXE, set
by ctest) and helpers to run it."""

import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    exe = os.environ.get("TOPOPLAN_EXE")
    if not exe or not os.path.exists(exe):
        pytest.skip("TOPOPLAN_EXE not set (run through ctest)")

    def run(*args, check=True):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, timeout=600)
        if check and r.returncode != 0:
            raise AssertionError(f"topoplan {' '.join(map(str, args))}: {r.returncode}\n{r.stderr}")
        return r

    run.exe = exe
    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    def run(*args):
        return json.loads(cli(*args).stdout)

    return run
