#!/usr/bin/env python3
"""Regenerates the example chains in assets/chains/ (pure Python, no dependencies).

Each file is a chain CSV (topology/polyline.h): one point per line `x,y,z`, `#` comment lines.
Run from the repository root: python3 scripts/make_chains.py
"""
import math
import os

OUT = os.path.join(os.path.dirname(__file__), "..", "assets", "chains")


def write(name, comment, pts):
    with open(os.path.join(OUT, name), "w") as f:
        for line in comment.strip().splitlines():
            f.write("# " + line + "\n")
        for p in pts:
            f.write(",".join(repr(round(v, 15) + 0.0) for v in p) + "\n")


def closed(fn, n):
    return [fn(2 * math.pi * k / n) for k in range(n)] + [fn(0.0)]


os.makedirs(OUT, exist_ok=True)
ring_a = lambda t: (math.cos(t), math.sin(t), 0.0)
ring_b = lambda s: (1 + math.cos(s), 0.0, math.sin(s))
write("hopf_a.csv", "Hopf link, first ring: (cos t, sin t, 0), 64 segments, closed", closed(ring_a, 64))
write("hopf_b.csv", "Hopf link, second ring: (1 + cos s, 0, sin s), 64 segments, closed\n"
      "Total writhe hopf_a x hopf_b = -1 (linking number)", closed(ring_b, 64))
write("unlinked_a.csv", "Unlinked rings, first: unit circle in the xy plane, 48 segments", closed(ring_a, 48))
write("unlinked_b.csv", "Unlinked rings, second: the Hopf second ring moved 3 m along x",
      closed(lambda s: (4 + math.cos(s), 0.0, math.sin(s)), 48))

R, r = 2.0, 0.7
def torus(j):
    def f(t):
        psi = 3 * t + j * math.pi
        return ((R + r * math.cos(psi)) * math.cos(t), (R + r * math.cos(psi)) * math.sin(t),
                r * math.sin(psi))
    return f
write("torus_2_6_a.csv", "(2,6) torus link, component 0 (R 2, r 0.7), 96 segments", closed(torus(0), 96))
write("torus_2_6_b.csv", "(2,6) torus link, component 1; linking number with component 0 = 3",
      closed(torus(1), 96))

turns, n = 3, 120
write("helix_3turns.csv", "Helix of 3 turns, radius 0.3 m, pitch 0.1 m, around the z axis, 120 segments",
      [(0.3 * math.cos(2 * math.pi * turns * k / n), 0.3 * math.sin(2 * math.pi * turns * k / n),
        -0.15 + 0.3 * k / n) for k in range(n + 1)])
write("pole.csv", "Straight pole along z from -5 m to 5 m, 20 segments",
      [(0.0, 0.0, -5 + 10 * k / 20) for k in range(21)])

ring = [(0.5, -0.2, 1.2), (0.5, -0.2, 1.5), (0.5, 0.0, 1.6), (0.5, 0.2, 1.5), (0.5, 0.2, 1.2),
        (0.5, 0.0, 1.1)]
write("ring.csv", "Hexagonal ring in the plane x = 0.5 m around (0.5, 0, 1.35) (the KUKA ring task), closed",
      ring + [ring[0]])
write("arm_through_ring.csv", "An open 5-segment arm passing through the ring along +x",
      [(0.1 + 0.2 * k, 0.02 * k, 1.33 + 0.01 * k) for k in range(6)])
