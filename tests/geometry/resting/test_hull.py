"""The plane convex hull against scipy's Qhull, and its small helpers."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.spatial import ConvexHull

from onefold_cad.geometry.numeric import polygon_area
from onefold_cad.geometry.resting.hull import convex_hull_2d, edge_distances

#: coordinates 0 or of magnitude 1e-30 .. 1e6 (the lengths a design may have:
#: below that, areas underflow in double precision and no hull is defined)
COORDS = st.one_of(st.just(0.0), st.floats(1e-30, 1e6), st.floats(-1e6, -1e-30))
POINTS = arrays(np.float64, st.tuples(st.integers(3, 300), st.just(2)), elements=COORDS)


@settings(max_examples=200, deadline=None)
@given(points=POINTS)
def test_hull_corners_and_area_match_qhull(points: np.ndarray) -> None:
    span = float(np.ptp(points, axis=0).max())
    try:
        qhull = ConvexHull(points)
    except Exception:  # Qhull refuses flat inputs: ours has no area then
        idx = convex_hull_2d(points)
        assert abs(polygon_area(points[idx])) <= 1e-9 * span**2
        return
    idx = convex_hull_2d(points)
    # counter-clockwise, the same area, and every point inside
    assert polygon_area(points[idx]) > 0.0
    assert abs(polygon_area(points[idx]) - qhull.volume) <= 1e-9 * span**2
    inside = np.array([edge_distances(p, points[idx]).min() for p in points])
    assert np.all(inside >= -1e-9 * span)
    # each hull's corners lie on the other's boundary (coincident points are
    # interchangeable, and a corner within rounding of a line may be either's)
    qv = points[qhull.vertices]
    for a, b in ((points[idx], qv), (qv, points[idx])):
        for p in a:
            assert abs(edge_distances(p, b).min()) <= 1e-9 * span


def test_degenerate_inputs() -> None:
    assert len(convex_hull_2d(np.zeros((0, 2)))) == 0
    assert list(convex_hull_2d([[1.0, 2.0], [1.0, 2.0]])) == [0]
    line = np.array([[0.0, 0.0], [2.0, 2.0], [1.0, 1.0], [3.0, 3.0]])
    assert sorted(convex_hull_2d(line)) == [0, 3]
    # a near-collinear point is dropped only within the tolerance
    square = np.array([[0, 0], [1, 0], [1, 1], [0.5, 1.0 + 1e-6], [0, 1]], dtype=float)
    assert len(convex_hull_2d(square)) == 5
    assert len(convex_hull_2d(square, tol=1e-5)) == 4


def test_area_and_edge_distances_of_a_unit_square() -> None:
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert polygon_area(square) == 1.0
    assert polygon_area(square[::-1]) == -1.0
    np.testing.assert_allclose(edge_distances([0.25, 0.5], square), [0.5, 0.75, 0.5, 0.25])
    assert edge_distances([2.0, 0.5], square)[1] == -1.0
