"""A Python program that sets a comma-decimal locale (locale.setlocale, as a German or French user's
program may) reads the assets and renders exactly as in the C locale: the library's numbers never
follow the host's locale. The locale comes from the locale_de_DE test fixture (LOCPATH)."""

import os
import subprocess
import sys

import pytest

PROGRAM = r"""
import json, locale, sys
import numpy as np
import topoplan
if sys.argv[1] != "C":
    locale.setlocale(locale.LC_ALL, sys.argv[1])
    assert locale.localeconv()["decimal_point"] == ","
root = topoplan.asset_root()
out = {}
robot = topoplan.Robot.load(root + "/robots/lwr4_sdh.urdf")
q = np.full(len(robot.joint_names), 0.1)
out["fk"] = robot.fk(q, "lwr_link_7").tolist()
s = topoplan.load_scenario("reach_through_ring")
out["q0"] = np.asarray(s.q0).tolist()
traj, report = s.plan("aico")
out["plan"] = [report["success"], report["final_writhe_total"], report["collision_checks"]]
out["chain"] = topoplan.writhe_matrix(
    np.loadtxt(root + "/chains/hopf_a.csv", delimiter=","),
    np.loadtxt(root + "/chains/hopf_b.csv", delimiter=",")).sum()
image = topoplan.render(root + "/scenes/example.json", size=(96, 72))
out["render"] = int(image.astype(np.int64).sum())
print(json.dumps(out))
"""


def run(loc):
    env = dict(os.environ)
    r = subprocess.run([sys.executable, "-c", PROGRAM, loc], env=env, capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_comma_decimal_locale_changes_nothing():
    if not os.environ.get("LOCPATH"):
        pytest.fail("LOCPATH not set: run through ctest (the locale_de_DE fixture makes the locale)")
    assert run("de_DE.UTF-8") == run("C")
