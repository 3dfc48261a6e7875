#!/usr/bin/env python3
"""Reference: a vectorised numpy writhe matrix (Klenin-Langowski asin form), for the throughput
comparison in the README ("≥ 20x numpy"). Not part of the build; needs Debian's python3-numpy.

Usage: /usr/bin/python3 tests/bench/numpy_writhe.py [N]   (N segments per chain, default 1000)
Prints seconds per matrix and ns per segment pair, and the total of the pinned Hopf link (-1).
"""
import sys
import time

import numpy as np


def writhe_matrix(a, b):
    """a: (..., n+1, 3), b: (..., m+1, 3) -> (..., n, m) signed, normalised by 4*pi (leading
    dimensions broadcast: a batch of pairs in one call)."""
    p1, p2 = a[..., :-1, None, :], a[..., 1:, None, :]
    p3, p4 = b[..., None, :-1, :], b[..., None, 1:, :]
    r13, r14, r23, r24 = p3 - p1, p4 - p1, p3 - p2, p4 - p2

    def unit(v):
        n = np.linalg.norm(v, axis=-1, keepdims=True)
        return v / np.where(n > 0, n, 1)

    n1 = unit(np.cross(r13, r14))
    n2 = unit(np.cross(r14, r24))
    n3 = unit(np.cross(r24, r23))
    n4 = unit(np.cross(r23, r13))
    dot = lambda u, v: np.clip(np.sum(u * v, axis=-1), -1.0, 1.0)
    omega = (np.arcsin(dot(n1, n2)) + np.arcsin(dot(n2, n3)) + np.arcsin(dot(n3, n4)) +
             np.arcsin(dot(n4, n1)))
    sign = np.sign(np.sum(np.cross(p4 - p3, p2 - p1) * r13, axis=-1))
    return sign * omega / (4 * np.pi)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    rng = np.random.default_rng(1)
    a = np.cumsum(0.1 * rng.standard_normal((n + 1, 3)), axis=0)
    b = np.cumsum(0.1 * rng.standard_normal((n + 1, 3)), axis=0) + [0.05, 0, 0]
    writhe_matrix(a[:50], b[:50])  # warm up
    reps = max(1, int(2e6 // (n * n)))
    t0 = time.perf_counter()
    for _ in range(reps):
        writhe_matrix(a, b)
    dt = (time.perf_counter() - t0) / reps
    t = np.linspace(0, 2 * np.pi, 65)
    hopf = writhe_matrix(np.c_[np.cos(t), np.sin(t), 0 * t], np.c_[1 + np.cos(t), 0 * t, np.sin(t)])
    print(f"numpy {n}x{n}: {dt * 1e3:.1f} ms per matrix, {dt / (n * n) * 1e9:.1f} ns per pair; "
          f"Hopf total {hopf.sum():+.9f}")


if __name__ == "__main__":
    main()
