#!/usr/bin/env python3
"""Checks `topoplan plan unwrap --geometry FILE --start-wrap A -o PLAN` against the same geometry
and angle run by `topoplan bench unwrap --geometry FILE --angles A:A:A --seeds 1 --planners aico -o
BENCH`: plan applies the geometry exactly as bench does, so its AICO run (seed 0) is the same run:
the same verdict, start coil, final writhe, reach error and final winding; and its trajectory is the
geometry's arm (arm_joint_30 present).
Usage: check_plan_geometry.py PLAN BENCH"""
import csv
import json
import os
import sys


def main():
    plan, bench = sys.argv[1], sys.argv[2]
    with open(os.path.join(plan, "report.json")) as f:
        report = json.load(f)
    with open(os.path.join(bench, "geometry.csv")) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 1, "geometry.csv: expected 1 run, got %d" % len(rows)
    row = rows[0]
    assert report["success"] == (row["success"] == "1"), (report["success"], row)
    assert report["failure_reason"] == row["failure_reason"], (report["failure_reason"], row)
    assert abs(report["start_wrap_deg"] - float(row["start_wrap_deg"])) < 1e-6, row
    for key in ("final_writhe_total", "reach_error_m", "final_winding_turns"):
        assert abs(report[key] - float(row[key])) < 1e-9, (key, report[key], row[key])
    jumps = report["winding_jumps"]
    assert jumps["through_object"] == int(row["jumps_through_object"]), (jumps, row)
    assert jumps["beyond_ends"] == int(row["jumps_beyond_ends"]), (jumps, row)
    assert jumps["unlocated"] == int(row["jumps_unlocated"]), (jumps, row)
    with open(os.path.join(plan, "trajectory.csv")) as f:
        header = f.readline().strip().split(",")
    assert "arm_joint_30" in header, "trajectory.csv is not the 30-link arm's: %s" % header[:5]
    print("ok: plan --geometry = bench --geometry,", row["geometry"], row["angle_deg"], "deg")


if __name__ == "__main__":
    main()
