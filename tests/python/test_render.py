"""Images: render gives the CLI's pixels; heatmap is the `topoplan heatmap` figure."""

import os

import numpy as np
import pytest

import topoplan

ASSETS = topoplan.asset_root()


def test_render_matches_cli(cli, tmp_path):
    urdf = os.path.join(ASSETS, "robots", "lwr4_sdh.urdf")
    out = tmp_path / "cli.png"
    n = len(topoplan.Robot.load(urdf).joint_names)
    q = [0.1 * (k + 1) for k in range(n)]
    cli("render", urdf, "--size", "160x120", "-o", out, "--q", ",".join("%.17g" % v for v in q))
    image = topoplan.render(urdf, q=q, size=(160, 120))
    assert image.shape == (120, 160, 3) and image.dtype == np.uint8
    assert np.array_equal(image, topoplan.read_png(str(out)))


def test_render_of_a_scene_file_matches_cli(cli, tmp_path):
    scene = os.path.join(ASSETS, "scenes", "example.json")
    out = tmp_path / "scene.png"
    cli("render", scene, "--size", "160x120", "-o", out)
    image = topoplan.render(scene, size=(160, 120))
    assert np.array_equal(image, topoplan.read_png(str(out)))
    with pytest.raises(ValueError, match="^q: only for a robot"):
        topoplan.render(scene, q=[0.0])


def test_render_q_errors_name_q():
    urdf = os.path.join(ASSETS, "robots", "lwr4_sdh.urdf")
    with pytest.raises(ValueError, match="^q: expected 14"):
        topoplan.render(urdf, q=[0.0, 1.0])
    with pytest.raises(ValueError, match="^q: joint 'lwr_joint_1' is not a number"):
        topoplan.Robot.load(urdf).fk({"lwr_joint_1": "a"})


def test_render_scenario_and_robot():
    s = topoplan.load_scenario("reach_through_ring")
    a = topoplan.render(s, size=(96, 64))
    assert a.shape == (64, 96, 3) and a.std() > 0
    r = topoplan.Robot.load(os.path.join(ASSETS, "robots", "arm20_sdh.urdf"))
    b = topoplan.render(r, size=(96, 64))
    assert b.shape == (64, 96, 3)


def test_heatmap_matches_cli(cli, tmp_path):
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(8, 3)), rng.normal(size=(6, 3))
    pa, pb = tmp_path / "A.csv", tmp_path / "B.csv"
    np.savetxt(pa, a, delimiter=",", fmt="%.17g")
    np.savetxt(pb, b, delimiter=",", fmt="%.17g")
    out = tmp_path / "h.png"
    cli("heatmap", pa, pb, "-o", out, "--size", "320x240")
    w = topoplan.writhe_matrix(a, b)
    image = topoplan.heatmap(w, "A", "B", size=(320, 240))
    assert np.array_equal(image, topoplan.read_png(str(out)))
