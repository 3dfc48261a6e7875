"""Streamed totals and certified linking numbers from Python (topology/writhe_stream.h)."""

import numpy as np
import pytest

import topoplan


def torus_link_component(k, j, n, R=2.0, r=0.7):
    """Component j of the (2, 2k) torus link; linking number +-k. Sampled at t = 0 ... 2 pi, so
    the last point repeats the first only up to rounding (closed within 1e-9 of the size)."""
    t = np.linspace(0.0, 2 * np.pi, n + 1)
    psi = k * t + j * np.pi
    return np.stack([(R + r * np.cos(psi)) * np.cos(t), (R + r * np.cos(psi)) * np.sin(t),
                     r * np.sin(psi)], axis=1)


def test_linking_number_of_torus_links_is_certified():
    for k in (1, 2, 3):
        a, b = torus_link_component(k, 0, 60 * k), torus_link_component(k, 1, 60 * k)
        r = topoplan.linking_number(a, b, method="gauss")
        assert r["status"] == "certified" and r["method"] == "gauss"
        assert abs(r["linking_number"]) == k
        assert r["distance"] <= r["error_bound"] < 1e-9
        # The same number as the sum of the dense matrix.
        assert abs(r["gauss_integral"] - topoplan.writhe_matrix(a, b).sum()) < 1e-12
        # The default counts signed crossings: the same integer, no Gauss integral.
        c = topoplan.linking_number(a, b)
        assert c["method"] == "crossings" and c["status"] == "certified"
        assert c["linking_number"] == r["linking_number"] and c["gauss_integral"] is None
        assert c["crossings"] >= 2 * k


def test_linking_method_is_checked():
    a, b = torus_link_component(1, 0, 40), torus_link_component(1, 1, 40)
    with pytest.raises(ValueError, match="linking method"):
        topoplan.linking_number(a, b, method="fast")


def test_writhe_total_streams_the_matrix_sum_and_row_sums():
    rng = np.random.default_rng(7)
    a = np.cumsum(rng.normal(size=(300, 3)) * 0.1, axis=0)
    b = np.cumsum(rng.normal(size=(200, 3)) * 0.1, axis=0) + [0.05, 0.0, 0.0]
    w = topoplan.writhe_matrix(a, b)
    total = topoplan.writhe_total(a, b)
    assert abs(total - w.sum()) <= 1e-12 * max(1.0, np.abs(w).sum())
    total2, rows = topoplan.writhe_total(a, b, row_sums=True, threads=2)
    assert total2 == total
    assert rows.shape == (299,)
    assert np.allclose(rows, w.sum(axis=1), rtol=0, atol=1e-12)


def test_open_chain_is_refused_and_touching_is_not_rounded():
    a = torus_link_component(1, 0, 50)
    with pytest.raises(ValueError, match="not closed"):
        topoplan.linking_number(a, a[:-1])
    # Two copies of one ring touch everywhere: no linking number.
    r = topoplan.linking_number(a, a)
    assert r["status"] != "certified" and r["linking_number"] is None
