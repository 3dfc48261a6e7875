"""Writhe and winding numbers: known linking numbers, the CLI, finite differences."""

import numpy as np
import pytest

import topoplan


def circle(n, center=(0, 0, 0), radius=1.0, plane="xy"):
    t = np.linspace(0.0, 2 * np.pi, n + 1)
    c, s = radius * np.cos(t), radius * np.sin(t)
    z = np.zeros_like(t)
    pts = {"xy": (c, s, z), "xz": (c, z, s)}[plane]
    return np.stack(pts, axis=1) + np.asarray(center, dtype=float)


def torus_knot(p, q, n, R=2.0, r=0.8, phase=0.0):
    """Closed curve on a torus winding p times around the hole, q times around the tube
    (`phase` shifts the angle around the tube)."""
    t = np.linspace(0.0, 2 * np.pi, n + 1)
    phi, theta = p * t, q * t + phase
    return np.stack(
        [(R + r * np.cos(theta)) * np.cos(phi), (R + r * np.cos(theta)) * np.sin(phi), r * np.sin(theta)],
        axis=1,
    )


def test_hopf_link_writhe_is_plus_minus_one():
    a = circle(200)
    b = circle(200, center=(1.0, 0.0, 0.0), plane="xz")
    w = topoplan.writhe_matrix(a, b)
    assert w.shape == (200, 200)
    assert abs(abs(w.sum()) - 1.0) < 1e-9
    # Reversing one orientation flips the sign.
    assert abs(topoplan.writhe_matrix(a, b[::-1]).sum() + w.sum()) < 1e-9


def test_unlinked_circles_have_zero_linking():
    a = circle(100)
    b = circle(100, center=(5.0, 0.0, 0.0), plane="xz")
    assert abs(topoplan.writhe_matrix(a, b).sum()) < 1e-9


def test_torus_link_linking_number():
    # Two disjoint parallel (1, 2) curves on a torus: the T(2, 4) torus link, linking number
    # p * q = 2.
    a = torus_knot(1, 2, 400)
    b = torus_knot(1, 2, 400, phase=np.pi)
    total = topoplan.writhe_matrix(a, b).sum()
    assert abs(abs(total) - 2.0) < 1e-6


def test_writhe_matches_cli_on_random_chains(cli_json, tmp_path):
    rng = np.random.default_rng(7)
    for k in range(5):
        a = rng.normal(size=(rng.integers(2, 12), 3))
        b = rng.normal(size=(rng.integers(2, 12), 3))
        pa, pb = tmp_path / f"a{k}.csv", tmp_path / f"b{k}.csv"
        np.savetxt(pa, a, delimiter=",", fmt="%.17g")
        np.savetxt(pb, b, delimiter=",", fmt="%.17g")
        j = cli_json("writhe", pa, pb, "--json")
        w = topoplan.writhe_matrix(a, b)
        assert w.shape == (j["rows"], j["cols"])
        assert np.max(np.abs(w - np.array(j["matrix"]))) <= 1e-12
        assert abs(w.sum() - j["total"]) <= 1e-12


def test_unsigned_variant_is_nonnegative():
    rng = np.random.default_rng(1)
    w = topoplan.writhe_matrix(rng.normal(size=(6, 3)), rng.normal(size=(5, 3)), unsigned=True)
    assert (w >= 0).all()


def test_writhe_jacobian_matches_finite_differences():
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(5, 3)), rng.normal(size=(4, 3))
    w, da, db = topoplan.writhe_jacobian(a, b)
    assert np.allclose(w, topoplan.writhe_matrix(a, b), atol=1e-14)
    assert da.shape == (4, 3, 5, 3) and db.shape == (4, 3, 4, 3)
    h = 1e-6
    for pts, d, first in ((a, da, True), (b, db, False)):
        for p in range(pts.shape[0]):
            for k in range(3):
                plus, minus = pts.copy(), pts.copy()
                plus[p, k] += h
                minus[p, k] -= h
                if first:
                    fd = (topoplan.writhe_matrix(plus, b) - topoplan.writhe_matrix(minus, b)) / (2 * h)
                else:
                    fd = (topoplan.writhe_matrix(a, plus) - topoplan.writhe_matrix(a, minus)) / (2 * h)
                assert np.max(np.abs(fd - d[:, :, p, k])) < 1e-6


def test_winding_of_a_helix_and_its_gradient():
    t = np.linspace(0, 3 * 2 * np.pi, 300)
    helix = np.stack([np.cos(t), np.sin(t), 0.1 * t], axis=1)
    assert abs(topoplan.winding(helix, [0, 0, 0], [0, 0, 1]) - 3.0) < 1e-9
    assert abs(topoplan.winding(helix, [0, 0, 0], [0, 0, -1]) + 3.0) < 1e-9
    rng = np.random.default_rng(5)
    chain = rng.normal(size=(6, 3))
    w, g = topoplan.winding(chain, [0.1, 0.2, 0], [0.3, 0.1, 1.0], gradient=True)
    assert g.shape == (6, 3)
    h = 1e-6
    for p in range(6):
        for k in range(3):
            plus, minus = chain.copy(), chain.copy()
            plus[p, k] += h
            minus[p, k] -= h
            fd = (
                topoplan.winding(plus, [0.1, 0.2, 0], [0.3, 0.1, 1.0])
                - topoplan.winding(minus, [0.1, 0.2, 0], [0.3, 0.1, 1.0])
            ) / (2 * h)
            assert abs(fd - g[p, k]) < 1e-6
