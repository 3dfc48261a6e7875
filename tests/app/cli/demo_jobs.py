#!/usr/bin/env python3
"""demo_jobs.py TOPOPLAN TMPDIR: `topoplan demo --jobs 2` (stages in forked processes) writes the
same files as `--jobs 1` (one stage after the other, in-process).

Runs the writhe, ring and viewer stages both ways, then compares every file: the same names,
byte-equal contents except measured times (report.json: keys ending in time_s; index.html: the
date and the measured planning times). Also checks the console shows each stage's block with its
CPU time, and that a bad --only value is refused with exit 2 naming the flag.
"""
import json
import os
import re
import shutil
import subprocess
import sys

STAGES = "writhe,ring,viewer"


def run(exe, out, jobs):
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run([exe, "demo", "-o", out, "--only", STAGES, "--jobs", str(jobs)],
                       capture_output=True, text=True, timeout=900)
    if p.returncode != 0:
        sys.exit(f"demo --jobs {jobs}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p.stdout


def files(root):
    out = set()
    for d, _, names in os.walk(root):
        for n in names:
            out.add(os.path.relpath(os.path.join(d, n), root))
    return out


def without_times(value):
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if not k.endswith("time_s")}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def same_dir(text):
    """The two command lines (in the reports and the page: folder name and --jobs) as one."""
    return re.sub(r"demo_jobs[12]|--jobs [12]", "X", text)


def main():
    exe, tmp = sys.argv[1], sys.argv[2]
    one, two = os.path.join(tmp, "demo_jobs1"), os.path.join(tmp, "demo_jobs2")
    run(exe, one, 1)
    log = run(exe, two, 2)
    a, b = files(one), files(two)
    if a != b:
        sys.exit(f"different files: only --jobs 1 {sorted(a - b)}, only --jobs 2 {sorted(b - a)}")
    if not any(f.startswith("ring/frames/") for f in a) or "viewer.png" not in a:
        sys.exit(f"stages missing from the output: {sorted(a)[:20]}")
    if any(".demo-parts" in f for f in a):
        sys.exit("the stages' scratch files were left in the output folder")
    for f in sorted(a):
        pa, pb = os.path.join(one, f), os.path.join(two, f)
        if f.endswith("report.json"):
            ja, jb = (without_times(json.loads(same_dir(open(p).read()))) for p in (pa, pb))
            if ja != jb:
                sys.exit(f"{f} differs beyond its times")
        elif f == "index.html":
            strip = lambda t: re.sub(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC|[0-9.]+ s<", "",
                                     same_dir(t))
            ta, tb = (strip(open(p, encoding="utf-8").read()) for p in (pa, pb))
            if ta != tb:
                sys.exit("index.html differs beyond dates and times")
        elif f != ".topoplan-outputs.json" and open(pa, "rb").read() != open(pb, "rb").read():
            sys.exit(f"{f} differs between --jobs 1 and --jobs 2")
    for n in (1, 2, 3):  # the stages run, numbered in page order
        if not re.search(rf"^\[{n}\] done \([0-9.]+ s, [0-9.]+ s CPU\)$", log, re.M):
            sys.exit(f"no '[{n}] done (... s CPU)' line in:\n{log}")
    p = subprocess.run([exe, "demo", "-o", os.path.join(tmp, "demo_jobs_bad"), "--only", "nope"],
                       capture_output=True, text=True)
    if p.returncode != 2 or "--only" not in p.stderr:
        sys.exit(f"--only nope: exit {p.returncode}, stderr {p.stderr!r}")
    print(f"{len(a)} files equal with --jobs 1 and --jobs 2")


if __name__ == "__main__":
    main()
