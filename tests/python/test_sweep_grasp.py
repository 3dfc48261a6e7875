"""`python3 -m topoplan.sweep grasp`: one task per (grasp, method, seed), the same results as
`topoplan grasp transfer --repeats N --seed S`, Wilson intervals in the summary, reruns skip
finished runs, bad input exits 2 and writes nothing."""

import csv
import json
import subprocess
import sys

import pytest

import topoplan

SWEEP = [sys.executable, "-m", "topoplan.sweep", "grasp"]
ARGS = ["--grasp", "power_bottle", "--method", "joint,human", "--seeds", "2", "--repeats", "1"]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run_sweep(*args, timeout=900):
    return subprocess.run([*SWEEP, *args], capture_output=True, text=True, timeout=timeout)


def test_sweep_equals_grasp_transfer(cli, tmp_path):
    out = tmp_path / "sweep"
    r = run_sweep(*ARGS, "--threads", "2", "-o", out)
    assert r.returncode == 0, r.stderr
    got = {(x["method"], int(x["seed"])): x for x in rows(out / "grasp.csv")}
    assert len(got) == 4
    assert all(float(x["close_by"]) == 0.15 for x in got.values())  # the protocol's grip
    for method in ("joint", "human"):
        for seed in (0, 1):
            d = tmp_path / f"cli_{method}_{seed}"
            cli("grasp", "transfer", "--grasp", "power_bottle", "--method", method,
                "--repeats", 1, "--seed", seed, "-o", d)
            report = json.loads((d / "report.json").read_text())
            m = report["grasps"][0]["methods"][method]
            row = got[(method, seed)]
            assert int(row["stable"]) == (1 if m["stable"] else 0)
            assert int(row["directions_passed"]) == m["directions_passed"]
            assert int(row["perturbed_trials"]) == m["perturbed"]["trials"] == 1
            assert int(row["perturbed_stable"]) == m["perturbed"]["stable"]

    summary = {x["method"]: x for x in rows(out / "grasp_summary.csv")}
    assert set(summary) == {"joint", "human"}
    for method, s in summary.items():
        stable = sum(int(got[(method, seed)]["perturbed_stable"]) for seed in (0, 1))
        assert int(s["trials"]) == 2 and int(s["stable"]) == stable
        lo, hi = topoplan.wilson_interval(stable, 2)
        assert float(s["ci95_lo"]) == pytest.approx(lo, abs=1e-5)
        assert float(s["ci95_hi"]) == pytest.approx(hi, abs=1e-5)

    # A rerun finds every run in the CSV and changes nothing.
    before = (out / "grasp.csv").read_text()
    r = run_sweep(*ARGS, "-o", out)
    assert r.returncode == 0, r.stderr
    assert (out / "grasp.csv").read_text() == before


def test_wilson_interval_known_values():
    lo, hi = topoplan.wilson_interval(2, 3)
    assert lo == pytest.approx(0.2077, abs=1e-4) and hi == pytest.approx(0.9385, abs=1e-4)
    lo, hi = topoplan.wilson_interval(0, 10)
    assert lo == 0.0 and hi == pytest.approx(0.2775, abs=1e-4)
    for bad in ((3, 2), (0, 0), (-1, 4)):
        with pytest.raises(ValueError, match="successes"):
            topoplan.wilson_interval(*bad)


@pytest.mark.parametrize(
    "args, message",
    [
        (["--grasp", "power_bottle,nothing"], "--grasp: unknown name 'nothing'"),
        (["--method", "winding,magic"], "--method: unknown name 'magic'"),
        (["--repeats", "1001"], "--repeats"),
        (["--mu", "nan"], "--mu"),
        (["--close-by", "0.6"], "--close-by"),
        (["--close-by", "nan"], "--close-by"),
        (["--seeds", "0"], "--seeds"),
        (["--seeds", "3"], "--seeds: without --repeats every seed is the same run"),
    ],
)
def test_bad_input_exits_2_and_writes_nothing(tmp_path, args, message):
    out = tmp_path / "out"
    r = run_sweep(*args, "-o", out, timeout=120)
    assert r.returncode == 2, r.stderr
    assert message in r.stderr
    assert not out.exists()


def test_a_rerun_with_another_perturbation_exits_2(tmp_path):
    out = tmp_path / "out"
    base = ["--grasp", "power_bottle", "--method", "joint", "--seeds", "1", "-o", out]
    assert run_sweep(*base).returncode in (0, 1)  # 1: an unstable grasp is a result
    r = run_sweep(*base, "--repeats", "1")
    assert r.returncode == 2 and "--repeats: " in r.stderr, r.stderr
