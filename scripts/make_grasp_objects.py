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
  shackle          D-shackle of 4 mm-radius (8 mm) round bar: a half-ring bow R 25 mm (centre
                   line) centred at y = +15 mm, two straight legs 45 mm long at x = ±25 mm down
                   to y = −30 mm, closed by a pin of radius 5 mm, 70 mm long along x at
                   y = −30 mm (it sticks out 6 mm past each leg); inside 42 × 61 mm; 90 g
  handle_bar       a handle bar under a lip: a bar of radius 6 mm, 92 mm long (capsule, along
                   y) at x = +28 mm, held by two posts of radius 5 mm (along x, at y = ±34 mm)
                   off the edge of a lip plate 30 × 100 × 16 mm (x from −52 to −22 mm) whose top
                   is 6 mm above the bar's; the hole between bar, posts and lip edge is
                   44 × 58 mm; 150 g
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


def d_loop(radius, bow_y, pin_y, segments=12):
    """Closed D loop: a half circle of `radius` about (0, bow_y) towards +y, straight legs at
    x = ±radius down to y = pin_y, and the straight pin between them."""
    pts = []
    for i in range(segments + 1):
        a = math.pi * i / segments
        pts.append([round(radius * math.cos(a), 6), round(bow_y + radius * math.sin(a), 6), Z])
    pts += [[-radius, pin_y, Z], [radius, pin_y, Z], pts[0]]
    return {"type": "loop", "points": pts}


def rectangle(x_plus, x_minus, half_y):
    """Closed rectangle in the hole plane, counter-clockwise about +z like the other loops."""
    pts = [[x_plus, -half_y, Z], [x_plus, half_y, Z], [x_minus, half_y, Z],
           [x_minus, -half_y, Z]]
    return {"type": "loop", "points": pts + [pts[0]]}


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
        {"name": "shackle", "mass": 0.09,
         "description": "D-shackle of 8 mm round bar: bow R 25 mm, legs 45 mm at x = +-25 mm, "
                        "pin r 5 mm x 70 mm across at y = -30 mm (inside 42 x 61 mm), lying "
                        "flat; reference = core loop",
         "primitives": [
             {"type": "torus", "size": [0.025, 0.004, half_pi], "xyz": [0, 0.015, Z],
              "rpy": [0, 0, half_pi]},
             {"type": "capsule", "size": [0.004, 0.045, 0], "xyz": [0.025, -0.0075, Z],
              "rpy": [half_pi, 0, 0]},
             {"type": "capsule", "size": [0.004, 0.045, 0], "xyz": [-0.025, -0.0075, Z],
              "rpy": [half_pi, 0, 0]},
             {"type": "cylinder", "size": [0.005, 0.07, 0], "xyz": [0, -0.03, Z],
              "rpy": [0, half_pi, 0]}],
         "reference": d_loop(0.025, 0.015, -0.03)},
        {"name": "handle_bar", "mass": 0.15,
         "description": "handle bar under a lip: bar r 6 mm x 92 mm along y at x = +28 mm, two "
                        "posts r 5 mm at y = +-34 mm off the edge of a 30 x 100 x 16 mm lip "
                        "plate (x from -52 to -22 mm, top 6 mm above the bar's); hole "
                        "44 x 58 mm, lying flat; reference = loop through bar, posts and lip",
         "primitives": [
             {"type": "capsule", "size": [0.006, 0.08, 0], "xyz": [0.028, 0, Z],
              "rpy": [half_pi, 0, 0]},
             {"type": "capsule", "size": [0.005, 0.058, 0], "xyz": [-0.001, 0.034, Z],
              "rpy": [0, half_pi, 0]},
             {"type": "capsule", "size": [0.005, 0.058, 0], "xyz": [-0.001, -0.034, Z],
              "rpy": [0, half_pi, 0]},
             {"type": "box", "size": [0.03, 0.1, 0.016], "xyz": [-0.037, 0, Z + 0.004]}],
         "reference": rectangle(0.028, -0.03, 0.034)},
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
