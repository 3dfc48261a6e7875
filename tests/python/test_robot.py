"""Robot bindings: names, limits, forward kinematics and Jacobians against finite differences,
chains, collision checks against placed objects."""

import os

import numpy as np
import pytest

import topoplan

ASSETS = topoplan.asset_root()
ARM = os.path.join(ASSETS, "robots", "arm20_sdh.urdf")
POLE = os.path.join(ASSETS, "objects", "pole.urdf")


@pytest.fixture(scope="module")
def robot():
    return topoplan.Robot.load(ARM)


def random_q(robot, seed):
    lo, hi = robot.limits
    lo, hi = np.maximum(lo, -1.0), np.minimum(hi, 1.0)
    return np.random.default_rng(seed).uniform(lo, hi) * 0.5


def test_names_and_limits(robot):
    n = len(robot.joint_names)
    assert n > 20
    assert "arm_link_1" in robot.link_names
    assert "arm" in robot.chain_names
    lo, hi = robot.limits
    assert lo.shape == (n,) and hi.shape == (n,) and (lo <= hi).all()


def test_fk_frames_and_dict_q(robot):
    q = random_q(robot, 0)
    frames = robot.fk(q)
    assert set(frames) == set(robot.link_names)
    T = robot.fk(q, link="sdh_grasp_link")
    assert T.shape == (4, 4) and np.allclose(T, frames["sdh_grasp_link"])
    assert np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=1e-12)
    # A dict q sets the named joints (others 0).
    q_dict = {name: v for name, v in zip(robot.joint_names, q)}
    assert np.allclose(robot.fk(q_dict, link="sdh_grasp_link"), T)


def test_point_and_frame_jacobians_match_finite_differences(robot):
    q = random_q(robot, 1)
    link, point = "arm_link_12", np.array([0.01, -0.02, 0.05])
    J = robot.point_jacobian(q, link, point)
    F = robot.frame_jacobian(q, link)
    n = q.size
    assert J.shape == (3, n) and F.shape == (6, n)
    h = 1e-6

    def pose(qq):
        return robot.fk(qq, link=link)

    T0 = pose(q)
    for k in range(n):
        dq = np.zeros(n)
        dq[k] = h
        Tp, Tm = pose(q + dq), pose(q - dq)
        p_fd = (Tp[:3, :3] @ point + Tp[:3, 3] - Tm[:3, :3] @ point - Tm[:3, 3]) / (2 * h)
        assert np.max(np.abs(p_fd - J[:, k])) < 1e-6
        o_fd = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        assert np.max(np.abs(o_fd - F[:3, k])) < 1e-6
        dR = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ T0[:3, :3].T  # skew(omega)
        omega = np.array([dR[2, 1], dR[0, 2], dR[1, 0]])
        assert np.max(np.abs(omega - F[3:, k])) < 1e-6


def test_chain_points_and_jacobian(robot):
    q = random_q(robot, 2)
    P = robot.chain_points(q, "arm")
    J = robot.chain_jacobian(q, "arm")
    n = q.size
    assert P.shape[1] == 3 and J.shape == (3 * P.shape[0], n)
    h = 1e-6
    for k in range(n):
        dq = np.zeros(n)
        dq[k] = h
        fd = (robot.chain_points(q + dq, "arm") - robot.chain_points(q - dq, "arm")) / (2 * h)
        assert np.max(np.abs(fd.reshape(-1) - J[:, k])) < 1e-6


def test_collision_against_placed_object():
    r = topoplan.Robot.load(ARM)
    q = np.zeros(len(r.joint_names))
    free = r.min_distance(q)
    grasp = r.fk(q, link="arm_link_10")[:3, 3]
    r.add_object(POLE, position=grasp + np.array([5.0, 0, 0]), name="far_pole")
    assert r.min_distance(q) <= free + 1e-12
    r2 = topoplan.Robot.load(ARM)
    r2.add_object(POLE, position=grasp, rpy=[np.pi / 2, 0, 0], name="through")
    assert r2.in_collision(q)
    assert r2.min_distance(q) < 0
    pairs = r2.distances(q, margin=0.01)
    assert any(p["is_object"] and p["other"] == "through" for p in pairs)
