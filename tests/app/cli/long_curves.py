#!/usr/bin/env python3
"""long_curves.py OUT_DIR N: writes the two components of the (2, 6) torus link (linking number
-3 in topoplan's orientation), N segments each, closed, as OUT_DIR/torus_N_a.csv and _b.csv; and
an open copy of the first (OUT_DIR/open_N_a.csv)."""
import math
import pathlib
import sys


def component(j, n, k=3, big_r=2.0, small_r=0.7):
    pts = []
    for i in range(n):
        t = 2 * math.pi * i / n
        psi = k * t + j * math.pi
        rr = big_r + small_r * math.cos(psi)
        pts.append((rr * math.cos(t), rr * math.sin(t), small_r * math.sin(psi)))
    return pts + [pts[0]]


def write(path, pts):
    path.write_text("".join("%.17g,%.17g,%.17g\n" % p for p in pts))


out, n = pathlib.Path(sys.argv[1]), int(sys.argv[2])
out.mkdir(parents=True, exist_ok=True)
a = component(0, n)
write(out / f"torus_{n}_a.csv", a)
write(out / f"torus_{n}_b.csv", component(1, n))
write(out / f"open_{n}_a.csv", a[:-1])
