"""`cmake --install` puts the package into <prefix>/lib/python3/dist-packages, where it imports
and finds the installed assets (share/topoplan) by itself."""

import os
import subprocess
import sys

import pytest


def test_installed_package_imports_and_finds_its_assets(tmp_path):
    build = os.environ.get("TOPOPLAN_BUILD_DIR")
    if not build:
        pytest.skip("TOPOPLAN_BUILD_DIR not set (run through ctest)")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True,
                   capture_output=True, timeout=300)
    site = prefix / "lib" / "python3" / "dist-packages"
    assert (site / "topoplan" / "__init__.py").exists()
    assert (site / "topoplan" / "sweep.py").exists()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TOPOPLAN_ASSETS")}
    env["PYTHONPATH"] = str(site)
    code = (
        "import topoplan; print(topoplan.__file__); print(topoplan.asset_root());"
        "s = topoplan.load_scenario('reach_through_ring'); print(s.name)"
    )
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                       cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    file, root, name = r.stdout.split()
    assert file.startswith(str(site))
    assert os.path.realpath(root) == os.path.realpath(prefix / "share" / "topoplan")
    assert name == "reach_through_ring"
