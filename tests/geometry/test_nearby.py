"""near_any against the dense (n, m, 2) computation it replaces, and its
memory at the size of the largest paper fan a design takes."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad.geometry.frame_curve import MAX_DESIGN_DIVISIONS
from onefold_cad.geometry.nearby import near_any


def dense(points: np.ndarray, targets: np.ndarray, tol: float) -> np.ndarray:
    """The old computation (flat_pattern before it was linear in memory): every
    difference at once."""
    if not len(targets):
        return np.zeros(len(points), dtype=bool)
    gap = np.linalg.norm(points[:, None, :] - targets[None, :, :], axis=2)
    return np.any(gap <= tol, axis=1)


coord = st.integers(-40, 40)


@settings(max_examples=300, deadline=None)
@given(
    st.lists(st.tuples(coord, coord), max_size=30),
    st.lists(st.tuples(coord, coord), max_size=30),
    st.sampled_from([1.0, 2.5, 3.0, 5.0]),
    st.sampled_from([1e-12, 1.0, 3e9]),
)
def test_equals_the_dense_test_on_small_sets(pts, tgts, tol, scale):
    """Integer grids put many pairs exactly at the tolerance (3-4-5 triangles,
    axis steps) and in neighbouring cells: the boundary cases of the grid."""
    p = np.array(pts, dtype=float).reshape(-1, 2) * scale
    t = np.array(tgts, dtype=float).reshape(-1, 2) * scale
    np.testing.assert_array_equal(near_any(p, t, tol * scale), dense(p, t, tol * scale))


def test_equals_the_dense_test_on_crowded_random_points():
    rng = np.random.default_rng(38)
    for tol in (1e-3, 1e-2, 0.05):
        p = rng.uniform(-1, 1, (400, 2))
        t = np.vstack([rng.uniform(-1, 1, (300, 2)), p[:50] + rng.normal(0, tol, (50, 2))])
        got = near_any(p, t, tol)
        np.testing.assert_array_equal(got, dense(p, t, tol))
        assert got.any() and not got.all()


def test_a_tolerance_that_is_not_positive_is_refused():
    with pytest.raises(ValueError, match="tol"):
        near_any(np.zeros((1, 2)), np.zeros((1, 2)), 0.0)


def test_the_largest_fan_runs_in_memory_linear_in_its_points():
    """A 10 000-division fan has about 20 000 ruling ends and as many folds:
    the dense test needed 2 x 20 000 x 20 000 x 8 bytes = 6.4 GB. Here the
    peak (tracemalloc, which sees numpy's buffers) must stay within 1 KB a
    point: a few dozen bytes for the grid, the candidate pairs batched."""
    n = 2 * MAX_DESIGN_DIVISIONS
    theta = np.linspace(0.0, np.pi, n)
    rho = 1.0 + 0.3 * np.sin(5 * theta)
    ends = np.column_stack([np.cos(theta), np.sin(theta)]) * rho[:, None]
    folds = ends[1:-1:2]  # every other end is a fold
    tracemalloc.start()
    try:
        got = near_any(ends, folds, 1e-12)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    expected = np.zeros(n, dtype=bool)
    expected[1:-1:2] = True
    np.testing.assert_array_equal(got, expected)
    assert peak < 1024 * (len(ends) + len(folds)), peak
