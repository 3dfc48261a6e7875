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
"""
import json
import os
import random

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
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


def geometry(rng, split, index, links):
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
        "arm": {"urdf": "../../../robots/arm%d_sdh.urdf" % links,
                "disabled_groups": [["sdh_", "arm_link_%d" % links]]},
    }


def main():
    for split, (seed, count, arms) in SETS.items():
        folder = os.path.join(OUT, split)
        os.makedirs(folder, exist_ok=True)
        rng = random.Random(seed)
        for i in range(count):
            g = geometry(rng, split, i, arms[i % len(arms)])
            with open(os.path.join(folder, g["name"] + ".json"), "w") as f:
                json.dump(g, f, indent=1)
                f.write("\n")
    print("wrote", OUT)


if __name__ == "__main__":
    main()
