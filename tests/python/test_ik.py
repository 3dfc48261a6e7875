"""Robot.ik: targets from forward kinematics are reached inside the limits, approach axes,
frozen joints, unreachable targets, collision rejection, bad arguments."""

import os

import numpy as np
import pytest

import topoplan

ASSETS = topoplan.asset_root()
LWR = os.path.join(ASSETS, "robots", "lwr4_sdh.urdf")


@pytest.fixture(scope="module")
def robot():
    return topoplan.Robot.load(LWR)


def random_q(robot, rng):
    lo, hi = robot.limits
    return rng.uniform(np.maximum(lo, -np.pi), np.minimum(hi, np.pi))


def test_fk_targets_reached_inside_limits(robot):
    rng = np.random.default_rng(0)
    lo, hi = robot.limits
    for _ in range(10):
        T = robot.fk(random_q(robot, rng), link="sdh_palm")
        target = T[:3, :3] @ [0, 0, 0.1] + T[:3, 3]
        r = robot.ik("sdh_palm", target, offset=[0, 0, 0.1], axis=([0, 0, 1], T[:3, 2]))
        assert r["status"] == "solved"
        assert r["position_error"] < 1e-3 and r["axis_error"] < 1e-3
        q = r["q"]
        assert q.shape == (len(robot.joint_names),)
        assert (q >= lo).all() and (q <= hi).all()
        # The errors are those of q.
        T2 = robot.fk(q, link="sdh_palm")
        assert np.linalg.norm(T2[:3, :3] @ [0, 0, 0.1] + T2[:3, 3] - target) < 1e-3


def test_frozen_joints_and_q0(robot):
    q0 = np.zeros(len(robot.joint_names))
    q0[2] = 0.3
    r = robot.ik("sdh_palm", [0.4, 0.2, 0.7], q0=q0, frozen=["lwr_joint_3"])
    assert r["status"] == "solved"
    assert r["q"][2] == 0.3


def test_unreachable_and_deterministic(robot):
    r = robot.ik("lwr_link_7", [3.0, 0.0, 0.31], starts=2, seed=5)
    assert r["status"] == "not_reached"
    assert r["position_error"] == pytest.approx(3.0 - 0.8685, abs=2e-3)
    again = robot.ik("lwr_link_7", [3.0, 0.0, 0.31], starts=2, seed=5)
    assert np.array_equal(r["q"], again["q"])


def test_collision_checked_solution_is_free(robot):
    r = robot.ik("sdh_palm", [0.5, 0.0, 0.4], check_collision=True)
    assert r["status"] in ("solved", "invalid")
    if r["status"] == "solved":
        assert not robot.in_collision(r["q"])


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(link="nope", position=[0, 0, 0]), "link: unknown link 'nope'"),
        (dict(link="sdh_palm", position=[0, np.nan, 0]), "position"),
        (dict(link="sdh_palm", position=[0, 0]), "position"),
        (dict(link="sdh_palm", position=[0, 0, 0], frozen=["x"]), "frozen: .*no joint named 'x'"),
        (dict(link="sdh_palm", position=[0, 0, 0], starts=0), "starts"),
        (dict(link="sdh_palm", position=[0, 0, 0], axis=([0, 0, 0], [1, 0, 0])), "axis"),
    ],
)
def test_bad_arguments(robot, kwargs, message):
    with pytest.raises(ValueError, match=message):
        robot.ik(**kwargs)
