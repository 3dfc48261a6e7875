#!/usr/bin/env python3
"""check_report_keys.py REPORT.json SECTION KEY...: fails unless report[SECTION][KEY] is a finite
number >= 0 for every KEY (e.g. the "replanning" rates and times of `plan --moving-object`)."""
import json
import math
import sys


def main():
    path, section, keys = sys.argv[1], sys.argv[2], sys.argv[3:]
    with open(path) as f:
        part = json.load(f).get(section)
    if not isinstance(part, dict):
        sys.exit(f"{path}: no \"{section}\" object")
    bad = [k for k in keys
           if not isinstance(part.get(k), (int, float)) or isinstance(part.get(k), bool)
           or not math.isfinite(part[k]) or part[k] < 0]
    if bad:
        sys.exit(f"{path}: \"{section}\" lacks finite numbers >= 0 for: {', '.join(bad)}")
    print(", ".join(f"{k} {part[k]}" for k in keys))


if __name__ == "__main__":
    main()
