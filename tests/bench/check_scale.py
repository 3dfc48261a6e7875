#!/usr/bin/env python3
"""Whole-process `topoplan check` time against the number of links (issue 34).

Generates chains of n capsule links (straight, collision-free at q = 0), times
`topoplan check CHAIN.urdf` as a user runs it (process start, URDF reading, set-up, one check,
output; best of --repeat runs) and prints the time per size and the growth exponent between
consecutive sizes (log(t2/t1) / log(n2/n1): 1 is linear, 2 quadratic). With --robot, also times
`topoplan check` of that URDF (e.g. a mobile manipulator of a public collection).

  python3 tests/bench/check_scale.py --topoplan build/app/topoplan
  python3 tests/bench/check_scale.py --topoplan build/app/topoplan \\
      --robot ROBOTS/tiago_description/robots/tiago.urdf --package-path ROBOTS/..
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import time


def chain_urdf(n):
    out = ['<robot name="chain%d">' % n]
    for i in range(n):
        out.append('<link name="l%d"><collision name="capsule"><origin xyz="0 0 0.05"/>'
                   '<geometry><cylinder radius="0.02" length="0.06"/></geometry></collision>'
                   '</link>' % i)
    for i in range(1, n):
        axis = "1 0 0" if i % 2 else "0 1 0"
        out.append('<joint name="j%d" type="revolute"><parent link="l%d"/><child link="l%d"/>'
                   '<origin xyz="0 0 0.1"/><axis xyz="%s"/><limit lower="-3" upper="3" '
                   'effort="1" velocity="1"/></joint>' % (i, i - 1, i, axis))
    out.append('</robot>')
    return "\n".join(out) + "\n"


def time_check(cmd, repeat):
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        result = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        elapsed = time.perf_counter() - start
        if result.returncode not in (0, 1):
            sys.exit("check failed (%d): %s" % (result.returncode, result.stderr.decode()))
        best = min(best, elapsed)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--topoplan", default="build/app/topoplan", help="the binary to time")
    parser.add_argument("--sizes", default="1000,10000,100000", help="chain lengths (links)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per size (best is kept)")
    parser.add_argument("--robot", help="also time `check` of this URDF")
    parser.add_argument("--package-path", action="append", default=[],
                        help="package root for --robot (repeatable)")
    args = parser.parse_args()
    if not os.access(args.topoplan, os.X_OK):
        sys.exit("%s: not an executable (build first, or pass --topoplan)" % args.topoplan)
    sizes = [int(s) for s in args.sizes.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            path = os.path.join(tmp, "chain%d.urdf" % n)
            with open(path, "w") as f:
                f.write(chain_urdf(n))
            t = time_check([args.topoplan, "check", path], 1 if n >= 100000 else args.repeat)
            rows.append((n, t))
    print("%10s %10s %10s" % ("links", "check s", "exponent"))
    for k, (n, t) in enumerate(rows):
        exponent = ""
        if k > 0:
            n0, t0 = rows[k - 1]
            exponent = "%.2f" % (math.log(t / t0) / math.log(n / n0))
        print("%10d %10.3f %10s" % (n, t, exponent))
    if args.robot:
        cmd = [args.topoplan, "check", args.robot]
        for p in args.package_path:
            cmd += ["--package-path", p]
        print("%s: check %.3f s (whole process, best of %d)" %
              (args.robot, time_check(cmd, args.repeat), args.repeat))


if __name__ == "__main__":
    main()
