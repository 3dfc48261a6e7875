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


def test_concurrent_calls_from_threads_take_turns():
    # A multi-threaded Dask worker calls grasp_transfer from several threads at once; ODE is
    # initialised once per process, so the calls must take turns, not fail.
    import threading

    results, errors = [None] * 3, []

    def run(i):
        try:
            results[i] = topoplan.grasp_transfer("power_bottle", "human")
        except Exception as e:  # noqa: BLE001 - collected and asserted below
            errors.append(e)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert results[0] == results[1] == results[2]
