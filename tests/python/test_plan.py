"""Scenarios: a plan of unwrap at 360 degrees equals `topoplan plan`'s report.json; callbacks
see every AICO sweep and can cancel."""

import json
import pathlib

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
    # The file also says which build and command made it (Python returns the plan's fields).
    assert set(expected.pop("provenance")) == {"version", "commit", "command"}
    assert set(report) == set(expected)
    for key in expected:
        if key not in ("time_s", "cpu_time_s"):  # the measured times
            assert report[key] == expected[key], key
    csv = np.loadtxt(tmp_path / "trajectory.csv", delimiter=",", skiprows=1)
    assert np.max(np.abs(csv[:, 2:] - trajectory)) < 1e-15
    assert abs(unwrap360.writhe_total(trajectory[-1]) - report["final_writhe_total"]) < 1e-12


def test_stop_when_solved_follows_the_scenario_and_can_be_replaced(unwrap360):
    # The shipped unwrap scenario stops at the first accepted sweep that is a success.
    _, solved = unwrap360.plan("aico")
    assert solved["success"] is True and solved["status"] == "solved"
    converged = topoplan.load_scenario(
        "unwrap", start_wrap=360, resolved=unwrap360.resolved_poses(), stop_when_solved=False
    )
    _, r = converged.plan("aico")
    assert r["success"] is True and r["status"] == "converged"
    assert r["iterations"] > solved["iterations"]
    with pytest.raises(TypeError):
        topoplan.load_scenario("unwrap", start_wrap=360, stop_when_solved="yes")


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
    assert {k: v for k, v in r1.items() if k not in ("time_s", "cpu_time_s")} == {
        k: v for k, v in expected.items() if k not in ("time_s", "cpu_time_s", "provenance")
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


def test_resolved_poses_skip_the_set_up_and_plan_the_same(unwrap360):
    poses = unwrap360.resolved_poses()
    assert set(poses) == {"q0", "unwinding", "goal_q"}
    n = len(unwrap360.joint_names)
    assert poses["q0"].shape == (n,) and poses["goal_q"].shape == (n,)
    # A pickled round trip, as a Dask set-up task ships them to another worker.
    import pickle

    again = topoplan.load_scenario("unwrap", start_wrap=360, resolved=pickle.loads(pickle.dumps(poses)))
    assert np.array_equal(again.q0, unwrap360.q0)
    assert np.array_equal(again.goal_q, unwrap360.goal_q)
    assert again.start_wrap_deg == unwrap360.start_wrap_deg
    for planner in ("aico", "birrt"):
        t1, r1 = unwrap360.plan(planner, seed=1)
        t2, r2 = again.plan(planner, seed=1)
        assert np.array_equal(t1, t2), planner
        for key in r1:
            if key not in ("time_s", "cpu_time_s"):  # the measured times
                assert r1[key] == r2[key], (planner, key)


def test_resolved_poses_are_checked(unwrap360):
    poses = unwrap360.resolved_poses()
    n = len(unwrap360.joint_names)
    with pytest.raises(ValueError, match="resolved: q0: expected %d finite numbers" % n):
        topoplan.load_scenario("unwrap", resolved={**poses, "q0": np.zeros(n + 1)})
    with pytest.raises(ValueError, match=r"resolved\['goal_q'\]: non-finite"):
        topoplan.load_scenario("unwrap", resolved={**poses, "goal_q": np.full(n, np.nan)})
    with pytest.raises(ValueError, match="resolved: no key 'goal_q'"):
        topoplan.load_scenario("unwrap", resolved={"q0": poses["q0"], "unwinding": poses["unwinding"]})
    with pytest.raises(ValueError, match="resolved: expected a dict"):
        topoplan.load_scenario("unwrap", resolved=[1, 2])
    with pytest.raises(ValueError, match="resolved: unwinding: expected none"):
        topoplan.load_scenario("unwrap", resolved={**poses, "unwinding": np.zeros((n, 51))})


def test_geometry_sets_up_the_held_out_scene_as_the_cli_does(cli, tmp_path):
    geometry = (pathlib.Path(topoplan.asset_root())
                / "scenarios/unwrap_geometries/test/test_09_arm30.json")
    s = topoplan.load_scenario("unwrap", start_wrap=90, geometry=geometry)
    assert "arm_joint_30" in s.joint_names  # the geometry's 30-link arm, not the shipped 20
    trajectory, report = s.plan("aico")
    cli("plan", "unwrap", "--geometry", geometry, "--start-wrap", 90, "-o", tmp_path)
    expected = json.loads((tmp_path / "report.json").read_text())
    for key in ("success", "failure_reason", "start_wrap_deg", "final_writhe_total",
                "reach_error_m", "winding_jumps"):
        assert report[key] == expected[key], key
    with pytest.raises(FileNotFoundError, match="geometry"):
        topoplan.load_scenario("unwrap", start_wrap=90, geometry=tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"tilt": [1, 2]}')
    with pytest.raises(ValueError, match="geometry: .*unknown key 'tilt'"):
        topoplan.load_scenario("unwrap", start_wrap=90, geometry=bad)
