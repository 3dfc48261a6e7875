#!/usr/bin/env python3
"""Writes the geometries of the unwrap generalisation study (pure Python, deterministic):
  assets/scenarios/unwrap_geometries/tuning/*.json  (the only set parameters may be chosen on)
  assets/scenarios/unwrap_geometries/test/*.json    (held out: the frozen set-up is judged on it)
Each file is read by `topoplan bench unwrap --geometry FILE` (planning/motion/unwrap_geometry.h).

Every geometry draws, from random.Random(seed) in this order:
  pole_tilt_deg      two angles uniform in [-20, 20] (about the pole's own x and y axes, through
                     its centre)
  pole_radius        uniform in [0.02, 0.06] m
  pole_translation   uniform in [-0.1, 0.1] m along each of the pole's two axes perpendicular to
                     its length (written in world coordinates)
  target_offset      uniform in [-0.1, 0.1] m per pole-frame axis, plus the arm's nominal offset
The arm cycles through ARMS of the set. The tuning set had 8 geometries until 2026-12-06 and 24
since: the draws are sequential, so its first 8 files did not change. The 12-link arm's nominal target is 0.8 m nearer its base
along the pole (the shipped target is out of its reach: 0.25 m short when unwrapped).
Run from anywhere: python3 scripts/make_unwrap_geometries.py
More tuning geometries from the same draws (the shipped files are their first 24), elsewhere:
  python3 scripts/make_unwrap_geometries.py --tuning-count 48 --out /tmp/geometries
A second held-out draw, never used to choose anything (test_20 to test_39; the shipped test files
are the first 20 of the same draws):
  python3 scripts/make_unwrap_geometries.py --test-count 40 --out /tmp/geometries
Check that the shipped files are its output (ctest unwrap_geometries_script):
  python3 scripts/make_unwrap_geometries.py --check
"""
import argparse
import filecmp
import json
import os
import random
import sys
import tempfile

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
OUT = os.path.join(ROOT, "assets/scenarios/unwrap_geometries")

# links -> nominal target offset in the pole's frame [m] (its z axis is the pole's length, +z
# towards the robot's base)
NOMINAL = {12: (0.0, 0.0, 0.8), 20: (0.0, 0.0, 0.0), 30: (0.0, 0.0, 0.0)}
SETS = {
    # name: (seed, count, arms)
    "tuning": (1, 24, (20, 12, 30, 20)),
    "test": (2, 20, (12, 30)),
}


def r3(v):
    return [round(x, 4) for x in v]


def geometry(rng, split, index, links, urdf):
    tilt = [rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0)]
    radius = rng.uniform(0.02, 0.06)
    tx, ty = rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)
    # The pole's x axis is the world's x, its y axis the world's -z (unwrap.json: rpy (-pi/2, 0, 0)).
    translation = [tx, 0.0, -ty]
    offset = [NOMINAL[links][k] + rng.uniform(-0.1, 0.1) for k in range(3)]
    return {
        "name": "%s_%02d_arm%d" % (split, index, links),
        "split": split,
        "pole_tilt_deg": [round(a, 2) for a in tilt],
        "pole_radius": round(radius, 4),
        "pole_translation": r3(translation),
        "target_offset": r3(offset),
        "arm": {"urdf": urdf % links,
                "disabled_groups": [["sdh_", "arm_link_%d" % links]]},
    }


def write(out, tuning_count, urdf_from=None, test_count=None):
    """Writes DIR/tuning and DIR/test; the arm URDF paths are relative to the file's folder, or to
    the same-named folder under `urdf_from` (the files then read as if written there)."""
    out = os.path.realpath(out)
    for split, (seed, default_count, arms) in SETS.items():
        count = tuning_count if split == "tuning" else (test_count or default_count)
        folder = os.path.join(out, split)
        os.makedirs(folder, exist_ok=True)
        here = os.path.join(os.path.realpath(urdf_from), split) if urdf_from else folder
        urdf = os.path.relpath(os.path.join(ROOT, "assets/robots"), here) + "/arm%d_sdh.urdf"
        rng = random.Random(seed)
        for i in range(count):
            g = geometry(rng, split, i, arms[i % len(arms)], urdf)
            with open(os.path.join(folder, g["name"] + ".json"), "w") as f:
                json.dump(g, f, indent=1)
                f.write("\n")


def check():
    """The shipped files are, byte for byte, the script's output, and --tuning-count and
    --test-count extend them (two more files of each set are drawn and their arm URDFs exist)."""
    errors = []
    with tempfile.TemporaryDirectory() as tmp:
        write(tmp, SETS["tuning"][1] + 2, urdf_from=OUT, test_count=SETS["test"][1] + 2)
        for split in SETS:
            shipped, made = os.path.join(OUT, split), os.path.join(tmp, split)
            names = sorted(n for n in os.listdir(shipped) if n.endswith(".json"))
            extra = 2
            if len(os.listdir(made)) != len(names) + extra:
                errors.append("%s: not the files the script writes" % shipped)
            for n in names:
                if not os.path.exists(os.path.join(made, n)) or not filecmp.cmp(
                        os.path.join(shipped, n), os.path.join(made, n), shallow=False):
                    errors.append("%s: differs from the script's output" % os.path.join(shipped, n))
            for n in sorted(os.listdir(made)):
                with open(os.path.join(made, n)) as f:
                    urdf = json.load(f)["arm"]["urdf"]
                if not os.path.isfile(os.path.join(shipped, urdf)):
                    errors.append("%s: its arm URDF %s does not exist" % (n, urdf))
    for e in errors:
        print("make_unwrap_geometries.py --check:", e, file=sys.stderr)
    print("make_unwrap_geometries.py --check:", "failed" if errors else "ok")
    return 1 if errors else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tuning-count", type=int, default=SETS["tuning"][1],
                        help="tuning geometries to write (default %(default)s, the shipped set)")
    parser.add_argument("--test-count", type=int, default=SETS["test"][1],
                        help="test geometries to write (default %(default)s, the shipped set)")
    parser.add_argument("--out", default=OUT,
                        help="folder for tuning/ and test/ (default: the shipped folder)")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 unless the shipped files are, byte for byte, "
                        "the script's output (--tuning-count, --test-count and --out are "
                        "ignored)")
    args = parser.parse_args()
    if args.check:
        sys.exit(check())
    if args.tuning_count < 1:
        parser.error("--tuning-count must be >= 1")
    if args.test_count < 1:
        parser.error("--test-count must be >= 1")
    write(args.out, args.tuning_count, test_count=args.test_count)
    print("wrote", os.path.abspath(args.out))


if __name__ == "__main__":
    main()
