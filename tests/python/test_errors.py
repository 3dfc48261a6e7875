"""Every error path: ValueError naming the argument, FileNotFoundError, RuntimeError for GL."""

import os
import subprocess
import sys

import numpy as np
import pytest

import topoplan

ASSETS = topoplan.asset_root()
ARM = os.path.join(ASSETS, "robots", "arm20_sdh.urdf")


@pytest.fixture(scope="module")
def robot():
    return topoplan.Robot.load(ARM)


def test_writhe_shape_nan_and_type_errors():
    good = np.zeros((3, 3))
    good[:, 0] = [0, 1, 2]
    with pytest.raises(ValueError, match=r"A: expected shape \(N, 3\)"):
        topoplan.writhe_matrix(np.zeros((4, 2)), good)
    with pytest.raises(ValueError, match="B: needs at least 2 points"):
        topoplan.writhe_matrix(good, np.zeros((1, 3)))
    bad = good.copy()
    bad[1, 1] = np.nan
    with pytest.raises(ValueError, match="B: non-finite"):
        topoplan.writhe_matrix(good, bad)
    with pytest.raises(ValueError, match="A: expected real numbers, got dtype <U3"):
        topoplan.writhe_matrix("abc", good)
    with pytest.raises(ValueError, match="A:"):
        topoplan.writhe_jacobian(np.zeros(3), good)


def test_writhe_jacobian_refuses_sizes_beyond_its_dense_limit():
    # (N-1)^2 * 2N * 3 doubles: N = 400 needs 3.8e8 > 2^27, N = 100 needs 5.9e6 (fine).
    big = np.random.default_rng(0).normal(size=(400, 3))
    with pytest.raises(ValueError, match=r"A, B: the dense Jacobians of 400 x 400 points"):
        topoplan.writhe_jacobian(big, big)
    w, da, db = topoplan.writhe_jacobian(big[:100], big[:100] + 5.0)
    assert w.shape == (99, 99) and da.shape == (99, 99, 100, 3) and db.shape == (99, 99, 100, 3)
    # Coordinates beyond 1e100 are refused (their squared lengths would overflow).
    with pytest.raises(ValueError, match=r"beyond ±1e100"):
        topoplan.writhe_matrix(big[:10] * 1e155, big[:10])
    # The matrix alone has no such limit.
    assert topoplan.writhe_matrix(big, big + 5.0).shape == (399, 399)


def test_winding_errors():
    chain = np.array([[1.0, 0, 0], [0, 1.0, 0]])
    with pytest.raises(ValueError, match="axis_dir: must be non-zero"):
        topoplan.winding(chain, [0, 0, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="axis_point"):
        topoplan.winding(chain, [0, 0], [0, 0, 1])
    with pytest.raises(ValueError, match="chain"):
        topoplan.winding(chain[:1], [0, 0, 0], [0, 0, 1])


def test_robot_errors(robot, tmp_path):
    n = len(robot.joint_names)
    with pytest.raises(FileNotFoundError, match="urdf"):
        topoplan.Robot.load(str(tmp_path / "missing.urdf"))
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'/><joint name='j' type='revolute'/></robot>")
    with pytest.raises(ValueError, match="bad.urdf"):
        topoplan.Robot.load(str(bad))
    with pytest.raises(ValueError, match=rf"q: expected shape \({n},\)"):
        robot.fk(np.zeros(n + 1))
    q = np.zeros(n)
    q[3] = np.inf
    with pytest.raises(ValueError, match="q: non-finite"):
        robot.fk(q)
    with pytest.raises(ValueError, match="q: unknown joint 'elbow'"):
        robot.fk({"elbow": 0.3})
    with pytest.raises(ValueError, match="link: unknown link 'hand'"):
        robot.fk(np.zeros(n), link="hand")
    with pytest.raises(ValueError, match="chain: unknown chain 'tail'"):
        robot.chain_points(np.zeros(n), "tail")
    with pytest.raises(ValueError, match="point"):
        robot.point_jacobian(np.zeros(n), "arm_link_1", [0, 0])
    with pytest.raises(FileNotFoundError, match="urdf"):
        robot.add_object(str(tmp_path / "nothing.urdf"))
    with pytest.raises(ValueError, match="margin"):
        robot.distances(np.zeros(n), margin=-1)


def test_scenario_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="path_or_name"):
        topoplan.load_scenario("no_such_scenario")
    bad = tmp_path / "bad.json"
    bad.write_text('{"name": "x", "robot": "nowhere.urdf", "tasks": []}')
    with pytest.raises(ValueError, match="bad.json"):
        topoplan.load_scenario(str(bad))
    with pytest.raises(ValueError, match="start_wrap"):
        topoplan.load_scenario("unwrap", start_wrap=float("nan"))
    with pytest.raises(ValueError, match=r"start_wrap: must be in \[0, 2000\]"):
        topoplan.load_scenario("unwrap", start_wrap=-5)
    # The message names the Python argument, not the CLI's positional.
    with pytest.raises(FileNotFoundError, match="^path_or_name: no file"):
        topoplan.load_scenario("no_such_scenario")
    s = topoplan.load_scenario("reach_through_ring")
    with pytest.raises(ValueError, match="planner: unknown planner 'prm'"):
        s.plan("prm")
    # A callback returns True, False or None: anything else is a TypeError naming it.
    for bad in ("yes", 1, 0.0):
        with pytest.raises(TypeError, match="callback: must return True, False or None"):
            s.plan(callback=lambda sweep, cost, q, bad=bad: bad)
    assert s.plan(callback=lambda sweep, cost, q: np.bool_(True))[1]["success"]


def test_image_errors(tmp_path):
    with pytest.raises(ValueError, match="size"):
        topoplan.render(ARM, size=(4, 4))
    with pytest.raises(FileNotFoundError, match="scene"):
        topoplan.render(str(tmp_path / "none.json"))
    with pytest.raises(ValueError, match="scene"):
        topoplan.render(12)
    with pytest.raises(ValueError, match="W"):
        topoplan.heatmap(np.zeros(3))
    with pytest.raises(FileNotFoundError, match="path"):
        topoplan.read_png(str(tmp_path / "none.png"))


def test_grasp_errors():
    with pytest.raises(ValueError, match="method: unknown transfer method 'magic'"):
        topoplan.grasp_transfer("power_bottle", "magic")
    with pytest.raises(ValueError, match="mu"):
        topoplan.grasp_transfer("power_bottle", "winding", mu=-1)
    for bad in (-0.1, 0.6, float("nan")):
        with pytest.raises(ValueError, match="close_by"):
            topoplan.grasp_transfer("power_bottle", "winding", close_by=bad)
    with pytest.raises(FileNotFoundError, match="^grasp: no grasp file 'no_such_grasp'"):
        topoplan.grasp_transfer("no_such_grasp", "winding")


def test_no_gl_is_runtime_error(tmp_path):
    # A GL backend that cannot start: an EGL device that does not exist, or OSMesa without its
    # library. The render call must raise RuntimeError (topoplan.GLError).
    code = (
        "import topoplan, sys\n"
        "try:\n"
        f"    topoplan.render({ARM!r}, size=(32, 32))\n"
        "except RuntimeError as e:\n"
        "    print('RuntimeError', isinstance(e, topoplan.GLError)); sys.exit(0)\n"
        "print('rendered'); sys.exit(0)\n"
    )
    env = dict(os.environ, TOPOPLAN_GL="nonsense")
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("RuntimeError True"), r.stdout
