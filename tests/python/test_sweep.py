"""`python3 -m topoplan.sweep unwrap`: the same runs as `topoplan bench unwrap`, reruns skip
finished runs, bad input exits 2 and writes nothing."""

import csv
import os
import subprocess
import sys
import time

import pytest

import topoplan

SWEEP = [sys.executable, "-m", "topoplan.sweep", "unwrap"]
ARGS = ["--angles", "0:90:90", "--seeds", "2", "--planners", "aico,birrt,rrt", "--budget", "3000"]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def key(row):
    return (float(row["angle_deg"]), row["planner"], int(row["seed"]))


def without_time(row):
    return {k: v for k, v in row.items() if k not in ("time_s", "cpu_time_s", "setup_time_s", "goal_sampler_cpu_time_s")}


def run_sweep(*args, timeout=600):
    return subprocess.run([*SWEEP, *args], capture_output=True, text=True, timeout=timeout)


def test_sweep_equals_bench_unwrap(cli, tmp_path):
    out = tmp_path / "sweep"
    r = run_sweep(*ARGS, "--threads", "2", "-o", out)
    assert r.returncode == 0, r.stderr
    cli("bench", "unwrap", *ARGS, "-o", tmp_path / "bench")
    got = {key(x): without_time(x) for x in rows(out / "unwrap.csv")}
    want = {key(x): without_time(x) for x in rows(tmp_path / "bench" / "unwrap.csv")}
    assert len(rows(out / "unwrap.csv")) == len(got) == 2 * 3 * 2
    assert got == want
    # The same figure code: equal sizes. (Its third panel plots wall time, so two runs cannot give
    # equal pixels; the figure of given rows is deterministic.)
    assert topoplan.read_png(str(out / "unwrap.png")).shape == topoplan.read_png(
        str(tmp_path / "bench" / "unwrap.png")
    ).shape
    bench_rows = [
        {k: (float(v) if k in ("angle_deg", "time_s") else v) for k, v in r.items()}
        for r in rows(tmp_path / "bench" / "unwrap.csv")
    ]
    for r in bench_rows:
        r["seed"], r["success"] = int(r["seed"]), int(r["success"])
        r["collision_checks"] = int(r["collision_checks"])
        r["narrow_phase_calls"] = int(r["narrow_phase_calls"])
    args = ([0.0, 90.0], ["aico", "birrt", "rrt"], 2)
    first = topoplan.unwrap_figure(bench_rows, *args)
    assert (first == topoplan.unwrap_figure(bench_rows, *args)).all()

    # A rerun finds every run in the CSV and starts no cluster.
    before = (out / "unwrap.csv").read_text()
    t0 = time.monotonic()
    r = run_sweep(*ARGS, "-o", out)
    assert r.returncode == 0, r.stderr
    assert (out / "unwrap.csv").read_text() == before
    assert time.monotonic() - t0 < 60

    # A torn last line (a crash mid-write) is dropped and that run redone, once.
    lines = before.splitlines(keepends=True)
    (out / "unwrap.csv").write_text("".join(lines[:-1]) + lines[-1][:5])
    r = run_sweep(*ARGS, "--threads", "1", "-o", out)
    assert r.returncode == 0, r.stderr
    again = rows(out / "unwrap.csv")
    assert len(again) == 12 and {key(x): without_time(x) for x in again} == want


@pytest.mark.parametrize(
    "args, message",
    [
        (["--angles", "90:0:10"], "--angles"),
        (["--angles", "a:b"], "--angles"),
        (["--planners", "aico,prm"], "unknown planner 'prm'"),
        (["--angles", "nan:10:1"], "--angles"),
        (["--planners", "aico,birrt,aico"], "'aico' is listed twice"),
        (["--planners", "aico,"], "--planners: empty name"),
        (["--seeds", "0"], "--seeds"),
        (["--seeds", "1001"], "--seeds"),
        (["--angles", "0:1000:1", "--planners", "aico,rrt,birrt", "--seeds", "1000"], "more than 1000000"),
        (["--pole-offset", "nan"], "--pole-offset"),
        (["--pole-offset", "-0.01"], "--pole-offset"),
        (["--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", "2"], "--scheduler: cannot reach"),
        (["--scheduler", "notaurl"], "--scheduler: expected tcp://HOST:PORT"),
        (["--timeout", "nan"], "--timeout"),
        (["--timeout", "-1"], "--timeout"),
        (["--budget", "0"], "--budget"),
        (["--angles", "100:100.0003:0.0001"], "print alike"),
    ],
)
def test_bad_input_exits_2_and_writes_nothing(tmp_path, args, message):
    out = tmp_path / "out"
    t0 = time.monotonic()
    r = run_sweep(*args, "-o", out, timeout=120)
    assert r.returncode == 2, r.stderr
    assert message in r.stderr
    assert not out.exists()
    assert time.monotonic() - t0 < 60


def test_perturbed_sweep_equals_bench_unwrap(cli, tmp_path):
    """--pole-offset moves the pole of each seed exactly as `bench unwrap --pole-offset` does."""
    args = ["--angles", "90:90:90", "--seeds", "2", "--planners", "aico,birrt", "--budget", "3000",
            "--pole-offset", "0.03"]
    out = tmp_path / "sweep"
    r = run_sweep(*args, "--threads", "2", "-o", out)
    assert r.returncode == 0, r.stderr
    cli("bench", "unwrap", *args, "-o", tmp_path / "bench")
    got = {key(x): without_time(x) for x in rows(out / "unwrap.csv")}
    want = {key(x): without_time(x) for x in rows(tmp_path / "bench" / "unwrap.csv")}
    assert len(got) == 4 and got == want
    offsets = topoplan.unwrap_perturbation("unwrap", 2, 0.03)["offsets"]
    assert offsets.shape == (2, 3) and 0 < max(sum(o * o for o in row) ** 0.5 for row in offsets) <= 0.03
    assert {x["pole_offset_m"] for x in got.values()} != {"0"}
    # A rerun into the same folder with another perturbation is refused; nothing changes.
    before = (out / "unwrap.csv").read_text()
    r = run_sweep(*args[:-1], "0.01", "-o", out)
    assert r.returncode == 2 and "--pole-offset" in r.stderr
    assert (out / "unwrap.csv").read_text() == before


def test_local_cluster_workers_run_without_the_profiler():
    """The local cluster's workers have Dask's statistical profiler off (it slowed every run)."""
    import dask
    import distributed  # noqa: F401  (loads the distributed.* configuration)
    from topoplan.sweep import connect

    before = dask.config.get("distributed.worker.profile.enabled")
    client, cluster = connect(None, 1, 30)
    try:
        flags = client.run(lambda: dask.config.get("distributed.worker.profile.enabled"))
        assert flags and all(v is False for v in flags.values()), flags
    finally:
        client.close()
        cluster.close()
    # Only the cluster's workers: this process keeps its own configuration.
    assert dask.config.get("distributed.worker.profile.enabled") == before


@pytest.mark.parametrize("output", ["/dev/null/out", "", "/proc/topoplan_out"])
def test_unusable_output_exits_2_before_starting_a_cluster(output):
    t0 = time.monotonic()
    r = run_sweep("--angles", "0:0:90", "--seeds", "1", "--planners", "aico", "-o", output,
                  timeout=120)
    assert r.returncode == 2, r.stderr
    assert "-o: " in r.stderr and "Traceback" not in r.stderr
    assert time.monotonic() - t0 < 20  # refused before a LocalCluster is started


def test_a_csv_with_a_torn_header_is_started_afresh(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "unwrap.csv").write_text("angle_deg,plan")  # a crash before the header was complete
    for _ in range(2):  # the second run finds every run done
        r = run_sweep("--angles", "0:0:90", "--seeds", "1", "--planners", "aico", "-o", out)
        assert r.returncode == 0, r.stderr
    lines = (out / "unwrap.csv").read_text().splitlines()
    assert lines[0].startswith("angle_deg,planner,seed,success") and len(lines) == 2


def test_a_rerun_with_another_budget_exits_2(tmp_path):
    # --budget is not in the rows: a rerun with another budget would silently reuse them.
    out = tmp_path / "out"
    base = ["--angles", "90:90:90", "--seeds", "1", "--planners", "rrt", "-o", out]
    assert run_sweep(*base, "--budget", "200").returncode == 0
    r = run_sweep(*base, "--budget", "100000")
    assert r.returncode == 2 and "--budget: " in r.stderr and "200" in r.stderr, r.stderr
    assert run_sweep(*base, "--budget", "200").returncode == 0  # the same flags go on
