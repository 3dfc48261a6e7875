#!/usr/bin/env python3
"""Generates the threading objects of the grasp study (`topoplan bench grasp`, issue 36).

Adds (or replaces, by name) these objects in assets/grasps/objects.json and writes one grasp spec
per object, assets/grasps/specs/ring_grip_<name>.json: the ring grip of ring_grip_torus (same
object pose, palm pose, start joints and closing order), so every hole sits where the torus's
does (centre (0, 0, 0.012) in the object frame, normal +z) and the index finger is closed through
it. The grasp files themselves come from the specs:
  topoplan grasp synthesize assets/grasps/specs/ring_grip_NAME.json \
      -o assets/grasps/study/ring_grip_NAME.json
Objects are unions of primitives (analytic signed distance); sizes in metres:
  key_ring         wire ring: torus R 30 mm, wire radius 2.5 mm (hole 55 mm across), 20 g
  bangle           thin torus: R 40 mm, wire radius 5 mm (hole 70 mm across), 30 g
  torus_small_hole thick torus: R 36 mm, tube radius 16 mm (hole 40 mm across), 120 g
  carabiner        stadium loop of 5 mm wire: two half rings R 22 mm whose centres are 40 mm
                   apart (y = ±20 mm), joined by two straight 40 mm bars; 40 g
Run from the repository root: python3 scripts/make_grasp_objects.py
"""
import json
import math
import os

ROOT = os.path.join(os.path.dirname(__file__), "..", "assets", "grasps")
Z = 0.012  # height of every hole's centre plane (the torus lies on z = 0 with tube 12 mm)


def circle(radius, segments=24):
    return {"type": "circle", "center": [0, 0, Z], "normal": [0, 0, 1], "radius": radius,
            "segments": segments}


def stadium(half_length, radius, segments=12):
    """Closed loop: semicircles of `radius` about (0, ±half_length), joined by straight sides."""
    pts = []
    for end, start in ((half_length, 0.0), (-half_length, math.pi)):
        for i in range(segments + 1):
            a = start + math.pi * i / segments  # +y end: 0..pi, −y end: pi..2 pi
            pts.append([round(radius * math.cos(a), 6), round(end + radius * math.sin(a), 6), Z])
    pts.append(pts[0])
    return {"type": "loop", "points": pts}


def objects():
    half_pi = math.pi / 2
    wire = 0.005
    return [
        {"name": "key_ring", "mass": 0.02,
         "description": "key ring: wire torus R 30 mm, wire radius 2.5 mm, lying flat; "
                        "reference = core circle",
         "primitives": [{"type": "torus", "size": [0.03, 0.0025, math.pi], "xyz": [0, 0, Z]}],
         "reference": circle(0.03)},
        {"name": "bangle", "mass": 0.03,
         "description": "bangle: thin torus R 40 mm, wire radius 5 mm (hole 70 mm across), "
                        "lying flat; reference = core circle",
         "primitives": [{"type": "torus", "size": [0.04, 0.005, math.pi], "xyz": [0, 0, Z]}],
         "reference": circle(0.04)},
        {"name": "torus_small_hole", "mass": 0.12,
         "description": "thick torus R 36 mm, tube radius 16 mm (hole 40 mm across), lying flat; "
                        "reference = core circle",
         "primitives": [{"type": "torus", "size": [0.036, 0.016, math.pi], "xyz": [0, 0, Z]}],
         "reference": circle(0.036)},
        {"name": "carabiner", "mass": 0.04,
         "description": "carabiner-like stadium loop of 5 mm wire: half rings R 22 mm at "
                        "y = +-20 mm joined by 40 mm bars, lying flat; reference = core loop",
         "primitives": [
             {"type": "torus", "size": [0.022, wire, half_pi], "xyz": [0, 0.02, Z],
              "rpy": [0, 0, half_pi]},
             {"type": "torus", "size": [0.022, wire, half_pi], "xyz": [0, -0.02, Z],
              "rpy": [0, 0, -half_pi]},
             {"type": "capsule", "size": [wire, 0.04, 0], "xyz": [0.022, 0, Z],
              "rpy": [half_pi, 0, 0]},
             {"type": "capsule", "size": [wire, 0.04, 0], "xyz": [-0.022, 0, Z],
              "rpy": [half_pi, 0, 0]}],
         "reference": stadium(0.02, 0.022)},
    ]


def main():
    path = os.path.join(ROOT, "objects.json")
    with open(path) as f:
        catalogue = json.load(f)
    new = objects()
    names = {o["name"] for o in new}
    catalogue["objects"] = [o for o in catalogue["objects"] if o["name"] not in names] + new
    with open(path, "w") as f:
        json.dump(catalogue, f, indent=1)
        f.write("\n")
    with open(os.path.join(ROOT, "specs", "ring_grip_torus.json")) as f:
        ring = json.load(f)
    for o in new:
        spec = dict(ring)
        spec["name"] = "ring_grip_" + o["name"]
        spec["object"] = o["name"]
        spec["description"] = ("ring grip of ring_grip_torus on the " + o["name"] +
                               ": index finger closed through the hole, thumb opposed")
        with open(os.path.join(ROOT, "specs", spec["name"] + ".json"), "w") as f:
            json.dump(spec, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
