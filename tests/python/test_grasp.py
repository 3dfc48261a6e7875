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
