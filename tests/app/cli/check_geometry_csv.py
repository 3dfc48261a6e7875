#!/usr/bin/env python3
"""Checks DIR/geometry.csv and DIR/unwrap.csv of `topoplan bench unwrap --geometry FILE`: the
header, one row per run, the geometry's name and split, the start coil reached the angle, and
(the property) the frozen set-up solved it: success, reach within the 5 cm criterion, the set-up's
goal meeting the end conditions.
With --closed (a scenario judged by the chord-closed winding, success.winding.final_closure
"chord"): the final winding is that of the closed loop, a whole number of turns (0: unwrapped).
Usage: check_geometry_csv.py DIR NAME SPLIT ANGLE_DEG [--closed]"""
import csv
import os
import sys

HEADER = ("geometry,split,angle_deg,planner,seed,start_wrap_deg,start_closed_wrap_deg,success,"
          "failure_reason,final_writhe_total,reach_error_m,final_winding_turns,"
          "unwound_winding_turns,goal_meets_end_conditions,state_queries,cpu_time_s,setup_time_s,"
          "jumps_through_object,jumps_beyond_ends,jumps_unlocated")


def main():
    out, name, split, angle = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    closed = sys.argv[5:] == ["--closed"]
    with open(os.path.join(out, "geometry.csv")) as f:
        text = f.read()
    lines = text.splitlines()
    assert lines[0] == HEADER, "header: " + lines[0]
    rows = list(csv.DictReader(text.splitlines()))
    assert len(rows) == 1, "expected 1 run, got %d" % len(rows)
    r = rows[0]
    assert r["geometry"] == name and r["split"] == split, r
    assert float(r["angle_deg"]) == angle, r
    assert abs(float(r["start_wrap_deg"]) - angle) < 5.0, "start coil %s" % r["start_wrap_deg"]
    # Closed by its chord (hand back to base), a coil of less than half a turn makes no loop round
    # the pole: its closed writhe stays below a quarter turn (the open one is the angle asked).
    if angle < 180.0:
        assert 0.0 <= float(r["start_closed_wrap_deg"]) < 90.0, r
    assert r["success"] == "1" and r["failure_reason"] == "none", r
    assert 0.0 <= float(r["reach_error_m"]) < 0.05, r
    assert abs(float(r["final_writhe_total"])) < 0.05, r
    assert r["goal_meets_end_conditions"] == "1", r
    if closed:
        # The loop arm + chord does not go round the pole: exactly 0 turns (up to rounding).
        assert abs(float(r["final_winding_turns"])) < 1e-9, r
    else:
        # The arm unwrapped: its final winding is near that of the straight base -> target segment.
        assert abs(float(r["final_winding_turns"]) - float(r["unwound_winding_turns"])) < 0.1, r
    assert int(r["state_queries"]) > 0, r
    # A success has no winding jump that counts as tunnelling: none through the pole or unlocated.
    assert r["jumps_through_object"] == "0" and r["jumps_unlocated"] == "0", r
    with open(os.path.join(out, "unwrap.csv")) as f:
        assert len(f.read().splitlines()) == 2, "unwrap.csv: expected a header and one row"
    print("ok:", name, angle, "deg,", r["state_queries"], "state queries")


if __name__ == "__main__":
    main()
