#!/usr/bin/env python3
"""Time vs segments for the Gauss linking integral: exact matrix, exact streamed, far field.

Runs `bench_topology --benchmark_filter=BM_LinkingScale` (the (2, 6) torus link, N segments per
component, one thread, CPU time; see tests/bench/bench_topology.cc), writes the measured numbers
as CSV and draws them on log-log axes with the fitted growth exponent of each method. Needs
Debian's python3-matplotlib (scripts/setup.sh installs it).

Usage:
  /usr/bin/python3 tests/bench/plot_linking_scale.py --bench build/tests/bench/bench_topology \
      -o docs/gallery/linking_scale.png
  /usr/bin/python3 tests/bench/plot_linking_scale.py --json results.json -o out.png   # re-plot

Writes OUT (PNG), OUT with .csv (method,segments,cpu_s,total) and, when it ran the benchmark,
OUT with .json (Google Benchmark's output). Exit 2 for bad arguments or
a benchmark output without BM_LinkingScale rows.
"""
import argparse
import json
import math
import os
import subprocess
import sys

METHODS = {
    0: "exact, matrix stored (WritheMatrix)",
    1: "exact, streamed (writhe --total, linking --method gauss)",
    2: "far field, tol 1e-3 (linking --tol)",
    3: "far field, tol 1e-1 (linking --tol)",
    4: "exact, signed crossings (linking, the default)",
}
UNIT_S = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def run_bench(bench, repetitions, out):
    """Runs the benchmark, keeping its JSON output in `out` (for --json re-plots)."""
    tmp = out + ".tmp"
    cmd = [bench, "--benchmark_filter=BM_LinkingScale/", f"--benchmark_out={tmp}",
           "--benchmark_out_format=json", f"--benchmark_repetitions={repetitions}",
           "--benchmark_report_aggregates_only=true"]
    print("$", " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True, stdout=sys.stderr)
    os.replace(tmp, out)
    with open(out) as f:
        return json.load(f)


def rows_of(data):
    """(method, segments, cpu seconds per iteration, T) per benchmark, medians when aggregated."""
    rows = {}
    for b in data.get("benchmarks", []):
        name = b.get("run_name", b["name"])
        if not name.startswith("BM_LinkingScale/"):
            continue
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        method, n = (int(x) for x in name.split("/")[1:3])
        cpu = b["cpu_time"] * UNIT_S[b.get("time_unit", "ns")]
        rows[(method, n)] = (cpu, b.get("T", float("nan")))
    return sorted((m, n, cpu, t) for (m, n), (cpu, t) in rows.items())


def slope(points):
    """Least-squares exponent k of time ~ N^k over the three largest N."""
    pts = [(math.log(n), math.log(t)) for n, t in sorted(points)[-3:] if t > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bench", help="the bench_topology program to run")
    ap.add_argument("--json", help="a saved Google Benchmark JSON output instead of running")
    ap.add_argument("--repetitions", type=int, default=1)
    ap.add_argument("-o", "--output", required=True, help="PNG to write")
    args = ap.parse_args()
    if bool(args.bench) == bool(args.json):
        print("plot_linking_scale: give exactly one of --bench and --json", file=sys.stderr)
        return 2
    if args.json:
        with open(args.json) as f:
            data = json.load(f)
    else:
        data = run_bench(args.bench, args.repetitions, os.path.splitext(args.output)[0] + ".json")
    rows = rows_of(data)
    if not rows:
        print("plot_linking_scale: no BM_LinkingScale results", file=sys.stderr)
        return 2

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    base, _ = os.path.splitext(args.output)
    with open(base + ".csv", "w") as f:
        f.write("method,segments,cpu_s,total\n")
        for m, n, cpu, t in rows:
            f.write(f"{METHODS[m].split(' (')[0]},{n},{cpu:.6g},{t:.12g}\n")
    fig, ax = plt.subplots(figsize=(7.5, 5.0), dpi=110)
    styles = {0: ("C3", "s"), 1: ("C0", "o"), 2: ("C2", "^"), 3: ("C1", "v"), 4: ("C4", "D")}
    for m, label in METHODS.items():
        pts = [(n, cpu) for mm, n, cpu, _ in rows if mm == m]
        if not pts:
            continue
        k = slope(pts)
        colour, marker = styles[m]
        ax.plot([n for n, _ in pts], [t for _, t in pts], marker=marker, color=colour,
                label=f"{label}: slope {k:.2f}")
        print(f"{label}: exponent {k:.2f}; " +
              ", ".join(f"{n}: {t:.3g} s" for n, t in pts))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("segments per curve N (two curves, N × N segment pairs)")
    ax.set_ylabel("CPU time, one thread [s]")
    ax.text(0.99, 0.02, "slope: fitted over the three largest N", transform=ax.transAxes,
            ha="right", va="bottom", fontsize=8, color="0.35")
    ax.set_title("Linking number of the (2, 6) torus link: Gauss integral and crossings")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    tmp = args.output + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, args.output)
    print(f"wrote {args.output} and {base}.csv", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
