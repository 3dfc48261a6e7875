"""A sweep through a real dask-scheduler and two dask-worker processes on 127.0.0.1; one worker
is killed mid-sweep and every run must still be in the CSV exactly once."""

import csv
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

import pytest

ANGLES = "0:180:45"
PLANNERS = "aico,birrt"
SEEDS = 2


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start(cmd, log):
    return subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)


def stop(proc):
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGKILL)
    proc.wait(timeout=30)


def test_sweep_survives_a_killed_worker(tmp_path):
    for tool in ("dask-scheduler", "dask-worker"):
        if shutil.which(tool) is None:
            pytest.skip(f"{tool} not installed (python3-distributed)")
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "cluster.log", "w")
    procs = []
    try:
        procs.append(
            start(["dask-scheduler", "--host", "127.0.0.1", "--port", str(port),
                   "--dashboard-address", ":0"], log))
        for k in range(2):
            procs.append(
                start(["dask-worker", address, "--nthreads", "1", "--nworkers", "1",
                       "--host", "127.0.0.1", "--dashboard-address", ":0", "--no-nanny",
                       "--name", f"w{k}"], log))
        out = tmp_path / "out"
        sweep = subprocess.Popen(
            [sys.executable, "-m", "topoplan.sweep", "unwrap", "--angles", ANGLES, "--seeds",
             str(SEEDS), "--planners", PLANNERS, "--budget", "3000", "--scheduler", address,
             "--connect-timeout", "30", "-o", str(out)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        procs.append(sweep)
        # Kill worker 1 once a few runs are in the CSV.
        csv_path = out / "unwrap.csv"
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline and sweep.poll() is None:
            if csv_path.exists() and len(csv_path.read_text().splitlines()) >= 4:
                break
            time.sleep(0.2)
        assert sweep.poll() is None, "the sweep ended before a worker could be killed"
        stop(procs[2])
        _, err = sweep.communicate(timeout=600)
        assert sweep.returncode == 0, err
        with open(csv_path) as f:
            runs = [(float(r["angle_deg"]), r["planner"], int(r["seed"])) for r in csv.DictReader(f)]
        expected = {(a, p, s) for a in (0.0, 45.0, 90.0, 135.0, 180.0)
                    for p in PLANNERS.split(",") for s in range(SEEDS)}
        assert sorted(runs) == sorted(expected)  # every run, exactly once
        assert (out / "unwrap.png").exists()
    finally:
        for p in reversed(procs):
            stop(p)
        log.close()
