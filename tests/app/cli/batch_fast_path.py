#!/usr/bin/env python3
"""batch_fast_path.py TOPOPLAN: `linking --batch` reads plain lines with its fast scanner and
everything else with the general JSON parser; both must give the same doubles and the same output.

Each pair is written twice: plainly (fast path) and with its id spelled with a \\u escape, which
only the general parser reads (same id after decoding). The coordinates include the spellings
where parsers differ: -0 (an integer zero, +0.0 for nlohmann), -0.0, exponents, 17 digits,
integers, whitespace. The outputs must be equal byte for byte. Then malformed lines must fail
with the general parser's message (exit 2, naming the line).
"""
import json
import random
import subprocess
import sys


def number_text(rng, x):
    form = rng.randrange(6)
    if form == 0:
        return repr(x)
    if form == 1:
        return "%.17g" % x
    if form == 2:
        return "%.6e" % x
    if form == 3:
        return "%.3E" % x
    if form == 4:
        return str(int(round(x)))  # integers, -0 included
    return "%.9f" % x


def chain_text(rng, pts):
    """pts closed (last = first): the closing point is spelled as the first, so it stays equal."""
    sep = rng.choice([",", ", ", " ,\t"])
    texts = ["[" + sep.join(number_text(rng, c) for c in p) + "]" for p in pts[:-1]]
    return "[" + sep.join(texts + texts[:1]) + "]"


def loop(rng, n, shift, plane):
    import math
    pts = []
    for i in range(n):
        t = 2 * math.pi * i / n + rng.uniform(-0.1, 0.1)
        u, v = math.cos(t) + rng.uniform(-0.05, 0.05), math.sin(t) + rng.uniform(-0.05, 0.05)
        pts.append([u + shift, v, 0.0] if plane == 0 else [u + shift, -0.0, v])
    return pts + [pts[0]]


def run(exe, text):
    p = subprocess.run([exe, "linking", "--batch", "-"], input=text, capture_output=True,
                       text=True)
    return p.returncode, p.stdout, p.stderr


def main():
    exe = sys.argv[1]
    rng = random.Random(7)
    plain, general = [], []
    for i in range(60):
        a = loop(rng, rng.randrange(3, 40), 0.0, 0)
        b = loop(rng, rng.randrange(3, 40), rng.choice([0.0, 0.4, 1.0, 2.5, 4.0]), 1)
        body = [f'"a": {chain_text(rng, a)}', f'"b": {chain_text(rng, b)}']
        rng.shuffle(body)
        ws = rng.choice(["", " ", "\t"])
        plain.append("{" + ws + f'"id": "p{i}", ' + ", ".join(body) + ws + "}")
        # "\u0070" is "p": the same id, but only the general parser reads escapes.
        general.append("{" + ws + f'"id": "\\u0070{i}", ' + ", ".join(body) + ws + "}")
    # Other ids (numbers, null, true) and the keys in another order.
    hopf_a = "[[1,0,0],[0,1,0],[-1,0,0],[0,-1,0],[1,0,0]]"
    hopf_b = "[[0,0,0],[1,0,-1],[2,0,0],[1,0,1],[0,0,0]]"
    for ident in ["7", "-1.50", "null", "true", "1e2"]:
        plain.append(f'{{"b": {hopf_b}, "id": {ident}, "a": {hopf_a}}}')
        general.append(f'{{"b": {hopf_b}, "id": {ident}, "a": {hopf_a}, "b": {hopf_b}}}')
    rc1, out1, err1 = run(exe, "\n".join(plain) + "\n")
    rc2, out2, err2 = run(exe, "\n".join(general) + "\n")
    if rc1 not in (0, 1) or rc1 != rc2:
        sys.exit(f"exit codes {rc1} / {rc2}: {err1} {err2}")
    lines1, lines2 = out1.splitlines(), out2.splitlines()
    if len(lines1) != len(plain) or lines1 != lines2:
        for k, (x, y) in enumerate(zip(lines1, lines2)):
            if x != y:
                sys.exit(f"line {k + 1} differs:\n  fast:    {x}\n  general: {y}")
        sys.exit(f"{len(lines1)} / {len(lines2)} result lines for {len(plain)} inputs")
    linked = sum(1 for x in lines1 if json.loads(x)["linking_number"] not in (0, None))
    if not 0 < linked < len(lines1):
        sys.exit(f"expected linked and unlinked pairs, got {linked} of {len(lines1)} linked")
    # Malformed lines: the general parser's message, naming the line.
    bad = {
        '{"id": 1, "a": [[01,0,0]], "b": []}': "invalid JSON",
        '{"id": 1, "a": [[1,0,0],[2,0,0],[3,0,0],[1,0,0]], "b": 5}': '"b": expected an array',
        '{"id": 1, "a": [[1,0]], "b": []}': '"a"[0]: expected [x,y,z] numbers',
        '{"id": 1, "a": [], "b": [], "c": 0}': "unknown key 'c'",
        '{"id": 1, "a": [[1e999,0,0]], "b": []}': "",
    }
    for line, message in bad.items():
        rc, out, err = run(exe, plain[0] + "\n" + line + "\n")
        if rc != 2 or ":2: " not in err or message not in err or len(out.splitlines()) != 1:
            sys.exit(f"{line!r}: exit {rc}, stderr {err!r}, expected {message!r} on line 2")
    print(f"{len(plain)} lines equal on both paths ({linked} linked); {len(bad)} refusals")


if __name__ == "__main__":
    main()
