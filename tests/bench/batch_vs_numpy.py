#!/usr/bin/env python3
"""Whole-process `topoplan linking --batch` against numpy on many small closed-curve pairs.

Writes K pairs of noisy closed loops (n segments each; the second loop's offset varies, so about
half the pairs are linked) as JSON lines, then times
  - topoplan: `topoplan linking --batch FILE --method gauss` as a whole process (start, parsing,
    the Gauss integrals, JSON output), wall and CPU time (best of --repeat runs), with --threads 1
    and with the default threads; and with the default method (signed crossings);
  - numpy: the vectorised writhe matrix of tests/bench/numpy_writhe.py summed per pair (arrays
    already in memory, the interpreter already started: numpy's best case), one pair at a time
    and batched over pairs (chunks of 256 pairs broadcast together);
and checks that every total agrees (|difference| < 1e-9) and that every certified crossing count
is the rounded total. Needs python3-numpy.

Usage: /usr/bin/python3 tests/bench/batch_vs_numpy.py --topoplan build/app/topoplan
           [--pairs 20000] [--segments 32] [--repeat 3]
Prints the times and the ratios numpy / topoplan.
"""
import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from numpy_writhe import writhe_matrix  # noqa: E402


def loops(k, n, seed):
    """k pairs of closed loops with n segments: (k, n+1, 3) arrays a and b."""
    rng = np.random.default_rng(seed)
    t = 2 * np.pi * np.arange(n) / n
    a = np.stack([np.cos(t), np.sin(t), 0 * t], axis=-1)[None] + 0.05 * rng.standard_normal(
        (k, n, 3))
    b = np.stack([np.cos(t), 0 * t, np.sin(t)], axis=-1)[None] + 0.05 * rng.standard_normal(
        (k, n, 3))
    b[:, :, 0] += rng.uniform(0.3, 3.7, size=(k, 1))  # linked when the shift is below ~2
    a = np.concatenate([a, a[:, :1]], axis=1)
    b = np.concatenate([b, b[:, :1]], axis=1)
    return a, b


def batched_totals(a, b, chunk=256):
    """Σ W per pair, broadcasting chunk pairs at a time (numpy_writhe's formula)."""
    out = [writhe_matrix(a[s:s + chunk], b[s:s + chunk]).sum(axis=(1, 2))
           for s in range(0, len(a), chunk)]
    return np.concatenate(out)


def run_topoplan(exe, path, threads, repeat, method="gauss"):
    best = None
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        cmd = [exe, "linking", "--batch", path, f"--method={method}"] + (
            [f"--threads={threads}"] if threads else [])
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode not in (0, 1):
            sys.exit(f"batch_vs_numpy: {' '.join(cmd)} exited {p.returncode}: {p.stderr}")
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        if best is None or wall < best[0]:
            best = (wall, cpu, p.stdout)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--topoplan", required=True)
    ap.add_argument("--pairs", type=int, default=20000)
    ap.add_argument("--segments", type=int, default=32)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    if args.pairs < 1 or args.segments < 3 or args.repeat < 1:
        sys.exit("batch_vs_numpy: --pairs >= 1, --segments >= 3, --repeat >= 1")
    a, b = loops(args.pairs, args.segments, seed=1)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "pairs.jsonl")
        with open(path, "w") as f:
            for i in range(args.pairs):
                f.write(json.dumps({"id": i, "a": a[i].tolist(), "b": b[i].tolist()}) + "\n")
        one = run_topoplan(args.topoplan, path, 1, args.repeat)
        auto = run_topoplan(args.topoplan, path, 0, args.repeat)
        crossings = run_topoplan(args.topoplan, path, 0, args.repeat, method="auto")
    totals = np.array([json.loads(line)["gauss_integral"] for line in one[2].splitlines()])
    crossing_lk = [json.loads(line) for line in crossings[2].splitlines()]

    t0, c0 = time.perf_counter(), time.process_time()
    per_pair = np.array([writhe_matrix(a[i], b[i]).sum() for i in range(args.pairs)])
    t_loop, c_loop = time.perf_counter() - t0, time.process_time() - c0
    best_batched, cpu_batched = math.inf, math.inf
    for _ in range(args.repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        batched = batched_totals(a, b)
        best_batched = min(best_batched, time.perf_counter() - t0)
        cpu_batched = min(cpu_batched, time.process_time() - c0)
    err = max(np.abs(per_pair - totals).max(), np.abs(batched - totals).max())
    linked = int(np.sum(np.abs(np.rint(totals)) > 0))
    print(f"{args.pairs} pairs of closed loops, {args.segments} x {args.segments} segments "
          f"({linked} linked); max |numpy - topoplan| = {err:.2e}")
    # The default method counts crossings: the same integers as the rounded Gauss integrals.
    wrong = sum(1 for r, t in zip(crossing_lk, totals)
                if r["status"] == "certified" and r["linking_number"] != int(np.rint(t)))
    by_crossings = sum(1 for r in crossing_lk if r["method"] == "crossings")
    print(f"default method: {by_crossings} of {args.pairs} pairs by crossings, {wrong} linking "
          f"numbers differ from the rounded Gauss integral")
    for label, (wall, cpu, _) in (("--method gauss --threads 1", one),
                                  ("--method gauss, default threads", auto),
                                  ("default method: crossings", crossings)):
        print(f"topoplan linking --batch ({label}): {wall:.3f} s wall, {cpu:.3f} s CPU, whole "
              f"process ({wall / args.pairs * 1e6:.1f} us per pair)")
    print(f"numpy, one pair at a time: {t_loop:.3f} s wall, {c_loop:.3f} s CPU; batched over "
          f"pairs: {best_batched:.3f} s wall, {cpu_batched:.3f} s CPU (arrays in memory)")
    print(f"ratio numpy / topoplan --threads 1: CPU {c_loop / one[1]:.1f}x (per-pair loop), "
          f"{cpu_batched / one[1]:.1f}x (batched); wall {t_loop / one[0]:.1f}x, "
          f"{best_batched / one[0]:.1f}x")
    print(f"ratio numpy / topoplan, default threads: wall {t_loop / auto[0]:.1f}x (per-pair loop), "
          f"{best_batched / auto[0]:.1f}x (batched)")
    print(f"ratio numpy / topoplan, default method (crossings): CPU {c_loop / crossings[1]:.1f}x "
          f"(per-pair loop), {cpu_batched / crossings[1]:.1f}x (batched)")
    if wrong:
        print("batch_vs_numpy: crossings and Gauss integrals disagree", file=sys.stderr)
        sys.exit(1)
    if err > 1e-9:
        print("batch_vs_numpy: totals disagree", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
