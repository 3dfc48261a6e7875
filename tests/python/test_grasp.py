"""grasp_transfer returns the grasp's entry of `topoplan grasp transfer`'s report.json."""

import json

import topoplan


def test_grasp_transfer_matches_cli(cli, tmp_path):
    entry = topoplan.grasp_transfer("power_bottle", "winding", mu=1.0)
    cli("grasp", "transfer", "--grasp", "power_bottle", "--method", "winding", "--mu", "1.0",
        "-o", tmp_path, check=False)
    report = json.loads((tmp_path / "report.json").read_text())
    assert entry == report["grasps"][0]
    assert "winding" in json.dumps(entry)


def test_grip_travel_matches_cli(cli, tmp_path):
    entry = topoplan.grasp_transfer("lateral_pinch_box", "winding", close_by=0.05)
    cli("grasp", "transfer", "--grasp", "lateral_pinch_box", "--method", "winding",
        "--close-by", "0.05", "-o", tmp_path, check=False)
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["protocol"]["close_by_rad"] == 0.05
    assert entry == report["grasps"][0]
