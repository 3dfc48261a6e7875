"""Every argument that names a file takes a str or an os.PathLike (pathlib.Path)."""

import pathlib

import numpy as np
import pytest

import topoplan

ASSETS = pathlib.Path(topoplan.asset_root())
ARM = ASSETS / "robots" / "arm20_sdh.urdf"


def test_robot_load_and_add_object_take_paths():
    by_path = topoplan.Robot.load(ARM, package_paths=[ASSETS / "robots"])
    by_str = topoplan.Robot.load(str(ARM))
    assert by_path.joint_names == by_str.joint_names
    by_path.add_object(ASSETS / "objects" / "cylinder.urdf", position=[0.5, 0.0, 0.0])
    assert isinstance(by_path.in_collision(np.zeros(len(by_path.joint_names))), bool)


def test_missing_path_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="urdf"):
        topoplan.Robot.load(tmp_path / "missing.urdf")
    with pytest.raises(FileNotFoundError):
        topoplan.load_scenario(tmp_path / "missing.json")
    with pytest.raises(FileNotFoundError):
        topoplan.read_png(tmp_path / "missing.png")


def test_scenario_from_path_equals_by_name():
    path = ASSETS / "scenarios" / "reach_through_ring.json"
    a = topoplan.load_scenario(path)
    b = topoplan.load_scenario("reach_through_ring")
    np.testing.assert_array_equal(a.q0, b.q0)


def test_png_round_trip_through_path(tmp_path):
    image = np.zeros((4, 5, 3), dtype=np.uint8)
    image[1, 2] = [10, 20, 30]
    out = tmp_path / "img.png"
    topoplan.write_png(out, image)
    np.testing.assert_array_equal(topoplan.read_png(out), image)


def test_write_png_refuses_other_dtypes_and_missing_folders(tmp_path):
    for bad in (np.full((4, 4, 3), 300), np.full((4, 4, 3), 0.9)):
        with pytest.raises(ValueError, match="image: expected dtype uint8"):
            topoplan.write_png(tmp_path / "x.png", bad)
    with pytest.raises(FileNotFoundError, match="path: no folder"):
        topoplan.write_png(tmp_path / "none" / "x.png", np.zeros((4, 4, 3), np.uint8))
    assert not (tmp_path / "none").exists() and not (tmp_path / "x.png").exists()
