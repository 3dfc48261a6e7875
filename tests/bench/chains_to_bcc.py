#!/usr/bin/env python3
"""Writes closed polylines to one BCC file, the input of Qu & James' `verifycurves` (the public
linking-number code compared in docs/benchmarks.md).

Usage: chains_to_bcc.py OUT.bcc A.csv B.csv ...

Each CSV holds one closed chain, a point "x,y,z" per line, its last point equal to its first (as
`topoplan linking` reads them). BCC (Binary Curve Collection, Cem Yuksel's format): a 64-byte
header ("BCC", 0x44 = 4-byte signed counts and 4-byte floats, curve type "PL" = polyline, 3
dimensions, up-axis 1, number of curves and of control points as uint64, 40 bytes of padding), then
per curve its point count (negative = closed, the repeated last point dropped) and its points as
little-endian float32 triples. float32 rounds the coordinates; the linking numbers of the
benchmark's curves do not change."""
import os
import struct
import sys


def read_closed_chain(path):
    with open(path) as f:
        points = [tuple(float(v) for v in line.split(",")) for line in f if line.strip()]
    if len(points) < 4 or any(len(p) != 3 for p in points):
        sys.exit("%s: need at least 4 points of 3 coordinates" % path)
    if points[0] == points[-1]:
        points = points[:-1]
    return points


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, inputs = sys.argv[1], sys.argv[2:]
    curves = [read_closed_chain(p) for p in inputs]
    total = sum(len(c) for c in curves)
    with open(out + ".tmp", "wb") as f:
        f.write(struct.pack("<3sBccbbQQ40s", b"BCC", 0x44, b"P", b"L", 3, 1, len(curves), total,
                            b"\0" * 40))
        for c in curves:
            f.write(struct.pack("<i", -len(c)))
            f.write(struct.pack("<%df" % (3 * len(c)), *[v for p in c for v in p]))
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main()
