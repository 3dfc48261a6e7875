"""Scenarios: a plan of unwrap at 360 degrees equals `topoplan plan`'s report.json; callbacks
see every AICO sweep and can cancel."""

import json

import numpy as np
import pytest

import topoplan


@pytest.fixture(scope="module")
def unwrap360():
    return topoplan.load_scenario("unwrap", start_wrap=360)


def test_unwrap_360_matches_cli(unwrap360, cli, tmp_path):
    sweeps = []
    trajectory, report = unwrap360.plan(
        "aico", seed=0, callback=lambda sweep, cost, q: sweeps.append((sweep, cost, q.shape))
    )
    assert report["success"] is True
    assert trajectory.shape == (51, len(unwrap360.joint_names))
    assert len(sweeps) == report["iterations"]
    cli("plan", "unwrap", "--start-wrap", 360, "--planner", "aico", "--seed", 0, "-o", tmp_path)
    expected = json.loads((tmp_path / "report.json").read_text())
    assert set(report) == set(expected)
    for key in expected:
        if key != "time_s":
            assert report[key] == expected[key], key
    csv = np.loadtxt(tmp_path / "trajectory.csv", delimiter=",", skiprows=1)
    assert np.max(np.abs(csv[:, 2:] - trajectory)) < 1e-15
    assert abs(unwrap360.writhe_total(trajectory[-1]) - report["final_writhe_total"]) < 1e-12


def test_rrt_seed_is_deterministic(cli, tmp_path):
    s = topoplan.load_scenario("unwrap", start_wrap=0)
    _, r1 = s.plan("birrt", seed=2)
    _, r2 = s.plan("birrt", seed=2)
    assert r1["collision_checks"] == r2["collision_checks"]
    # Exit 1 (the run failed the success criterion) is a result too: only the reports must agree.
    r = cli("plan", "unwrap", "--start-wrap", 0, "--planner", "birrt", "--seed", 2, "-o", tmp_path,
            check=False)
    assert r.returncode in (0, 1), r.stderr
    expected = json.loads((tmp_path / "report.json").read_text())
    assert {k: v for k, v in r1.items() if k != "time_s"} == {
        k: v for k, v in expected.items() if k != "time_s"
    }


def test_callback_false_cancels(unwrap360):
    seen = []

    def stop_after_two(sweep, cost, q):
        seen.append(sweep)
        return sweep < 1

    with pytest.raises(topoplan.PlanCancelled) as info:
        unwrap360.plan("aico", callback=stop_after_two)
    assert seen == [0, 1]
    assert info.value.sweep == 1
    assert info.value.trajectory.shape[1] == len(unwrap360.joint_names)


def test_callback_exception_propagates(unwrap360):
    def boom(sweep, cost, q):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        unwrap360.plan("aico", callback=boom)
