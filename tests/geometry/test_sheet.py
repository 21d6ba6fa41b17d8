"""The sheet's validation: simplicity against an exact oracle, the caps and
magnitude bounds at their exact edges, and no numpy warning on any input."""

from __future__ import annotations

import math
import re
import warnings
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import InvalidParameterError, InvalidSheetError, Sheet
from onefold_cad.geometry.checks import MAX_LENGTH, MIN_LENGTH
from onefold_cad.geometry.polygon import check_simple
from onefold_cad.geometry.sheet import MAX_VERTICES, MIN_FEATURE

UP, DOWN = math.inf, -math.inf


# -- an exact oracle: rational arithmetic on integer coordinates ----------------
def _orient(a: tuple, b: tuple, c: tuple) -> Fraction:
    return (Fraction(b[0]) - a[0]) * (Fraction(c[1]) - a[1]) - (Fraction(b[1]) - a[1]) * (
        Fraction(c[0]) - a[0]
    )


def _on_segment(a: tuple, b: tuple, p: tuple) -> bool:
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def segments_meet(a: tuple, b: tuple, c: tuple, d: tuple) -> bool:
    """Whether the closed segments ab and cd share a point (exactly)."""
    o1, o2, o3, o4 = _orient(a, b, c), _orient(a, b, d), _orient(c, d, a), _orient(c, d, b)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    return (
        (o1 == 0 and _on_segment(a, b, c))
        or (o2 == 0 and _on_segment(a, b, d))
        or (o3 == 0 and _on_segment(c, d, a))
        or (o4 == 0 and _on_segment(c, d, b))
    )


def meeting_pairs(pts: list[tuple[int, int]]) -> set[tuple[int, int]]:
    """Every pair (i < k) of non-adjacent edges of the closed polygon that meet."""
    n = len(pts)
    out = set()
    for i in range(n):
        for k in range(i + 1, n):
            if k == i + 1 or (i == 0 and k == n - 1):
                continue
            if segments_meet(pts[i], pts[(i + 1) % n], pts[k], pts[(k + 1) % n]):
                out.add((i, k))
    return out


@st.composite
def integer_polygons(draw: st.DrawFn) -> list[tuple[int, int]]:
    """Closed polygons of 4-9 vertices on a small integer grid, no two
    consecutive vertices equal: many touch, cross or overlap themselves."""
    n = draw(st.integers(4, 9))
    coord = st.integers(-5, 5)
    pts = draw(st.lists(st.tuples(coord, coord), min_size=n, max_size=n))
    if any(pts[i] == pts[(i + 1) % n] for i in range(n)):
        pts = list(dict.fromkeys(pts))  # drop repeats (keeps the order)
    if len(pts) < 4:
        pts = [(0, 0), (3, 0), (3, 3), (0, 3)]
    return pts


@settings(max_examples=400, deadline=None)
@given(integer_polygons(), st.sampled_from([1.0, 1e-30 / 5, 1e30 / 5]))
def test_check_simple_agrees_with_an_exact_oracle(pts: list, scale: float) -> None:
    # Integer coordinates (times a power-of-two-free scale): a near miss is at
    # least 1/100 of the grid away, far beyond the 1e-12 touching tolerance.
    bad = meeting_pairs(pts)
    p = np.array(pts, dtype=float) * scale
    if not bad:
        check_simple(p, "polygon")
        return
    with pytest.raises(InvalidSheetError, match="self-intersects") as err:
        check_simple(p, "polygon")
    named = tuple(int(x) for x in re.findall(r"edge (\d+)", str(err.value)))
    assert named in bad  # the two edges it names do meet


def test_the_bow_tie_self_intersects() -> None:
    with pytest.raises(InvalidSheetError, match="polygon self-intersects: edge 0 .* edge 2"):
        Sheet.polygon([(1, 1), (-1, -1), (1, -1), (-1, 1)])


def _star(n: int, scale: float = 1.0, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    ang = np.sort(rng.uniform(0.0, 2 * math.pi, n))
    ang[0] = 0.0
    gaps = np.diff(np.concatenate([ang, [2 * math.pi]]))
    assert gaps.max() < math.pi
    r = rng.uniform(0.3, 1.0, n)
    return np.stack([r * np.cos(ang), r * np.sin(ang)], axis=-1) * scale


def test_a_large_self_intersecting_polygon_names_two_edges_that_meet() -> None:
    p = _star(MAX_VERTICES)
    p[[10, 5000]] = p[[5000, 10]]  # two far apart vertices swapped: their edges cross
    with pytest.raises(InvalidSheetError, match="self-intersects") as err:
        Sheet.polygon(p)
    i, k = (int(x) for x in re.findall(r"edge (\d+)", str(err.value)))
    q = [tuple(Fraction(c) for c in v) for v in p.tolist()]
    n = len(q)
    assert segments_meet(q[i], q[(i + 1) % n], q[k], q[(k + 1) % n])


@settings(max_examples=60, deadline=None)
@given(st.integers(3, 400), st.floats(-30.0, 30.0), st.integers(0, 2**32 - 1))
def test_star_polygons_over_the_whole_scale_range_are_accepted(
    n: int, exponent: float, seed: int
) -> None:
    scale = min(max(10.0**exponent, MIN_LENGTH), MAX_LENGTH)
    rng = np.random.default_rng(seed)
    gaps = rng.uniform(0.2, 1.0, n)
    gaps = gaps / gaps.sum() * 2 * math.pi
    if gaps.max() >= math.pi:
        gaps = np.full(n, 2 * math.pi / n)
    ang = rng.uniform(0, 2 * math.pi) + np.concatenate([[0.0], np.cumsum(gaps)[:-1]])
    r = rng.uniform(0.1, 1.0, n)
    pts = np.stack([r * np.cos(ang), r * np.sin(ang)], axis=-1) * scale
    pts /= np.max(np.abs(pts)) / scale  # the largest coordinate magnitude is `scale`
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = Sheet.polygon(pts[::-1] if seed % 2 else pts)  # either orientation
    x, y = pts[:, 0], pts[:, 1]
    shoelace = 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
    assert s.area == pytest.approx(shoelace, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(allow_nan=True, allow_infinity=True),
            st.floats(allow_nan=True, allow_infinity=True),
        ),
        min_size=0,
        max_size=12,
    )
)
def test_any_coordinates_give_a_sheet_or_a_named_error_without_warnings(pts: list) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            Sheet.polygon(pts)
        except InvalidSheetError as err:
            assert err.parameter == "polygon"


# -- caps and bounds at their exact edges ---------------------------------------
def test_vertex_cap_boundary() -> None:
    assert len(Sheet.polygon(_star(MAX_VERTICES)).vertices) >= MAX_VERTICES
    with pytest.raises(InvalidSheetError, match=r"^polygon: must have at most 10000 vertices"):
        Sheet.polygon(_star(MAX_VERTICES + 1))


@pytest.mark.parametrize(
    ("scale", "ok"),
    [
        (MAX_LENGTH, True),
        (np.nextafter(MAX_LENGTH, UP), False),
        (MIN_LENGTH, True),
        (np.nextafter(MIN_LENGTH, DOWN), False),
        (1e308, False),
        (1e-300, False),
    ],
)
def test_polygon_magnitude_boundary(scale: float, ok: bool) -> None:
    pts = np.array([(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]) * scale
    if ok:
        assert Sheet.polygon(pts).size == scale
    else:
        with pytest.raises(InvalidSheetError, match=r"magnitude must be in \[1e-30, 1e\+30\]"):
            Sheet.polygon(pts)


@pytest.mark.parametrize("key", ["x_plus", "x_minus", "y_plus", "y_minus"])
def test_quadrilateral_sliver_boundary(key: str) -> None:
    sides = dict.fromkeys(("x_plus", "x_minus", "y_plus", "y_minus"), 1.0)
    Sheet.quadrilateral(**{**sides, key: MIN_FEATURE})
    with pytest.raises(InvalidParameterError, match=f"^{key}: must be at least 1e-09 times"):
        Sheet.quadrilateral(**{**sides, key: np.nextafter(MIN_FEATURE, DOWN)})
    assert Sheet.quadrilateral(*[MAX_LENGTH] * 4).size == MAX_LENGTH
    with pytest.raises(InvalidParameterError, match=f"^{key}: must be .*in \\[1e-30, 1e\\+30\\]"):
        Sheet.quadrilateral(**{**sides, key: np.nextafter(MAX_LENGTH, UP)})


def test_rectangle_bounds() -> None:
    Sheet.rectangle(1.0, MIN_FEATURE)
    with pytest.raises(
        InvalidParameterError, match="^height: must be at least 1e-09 times the width"
    ):
        Sheet.rectangle(1.0, np.nextafter(MIN_FEATURE, DOWN))
    with pytest.raises(InvalidParameterError, match="^width: must be at least 1e-09 times"):
        Sheet.rectangle(np.nextafter(MIN_FEATURE, DOWN), 1.0)
    Sheet.rectangle(MAX_LENGTH, MAX_LENGTH)
    with pytest.raises(InvalidParameterError, match=r"^width: must be in \[1e-30, 1e\+30\]"):
        Sheet.rectangle(np.nextafter(MAX_LENGTH, UP), 1.0)
    with pytest.raises(InvalidParameterError, match=r"^height: must be in \[1e-30, 1e\+30\]"):
        Sheet.rectangle(1.0, 1e-300)
    for f in (MIN_FEATURE, 1.0 - MIN_FEATURE):
        Sheet.rectangle(3.0, 2.0, f)
    for f in (np.nextafter(MIN_FEATURE, DOWN), np.nextafter(1.0 - MIN_FEATURE, UP), 0.0, 1.0):
        with pytest.raises(InvalidParameterError, match=r"^apex_fraction: must be in \[1e-09"):
            Sheet.rectangle(3.0, 2.0, f)


def test_a_rectangle_is_made_once_for_the_same_arguments() -> None:
    a = Sheet.rectangle(3.0, 7.0, 0.25)
    assert Sheet.rectangle(3.0, 7.0, 0.25) is a
    other = Sheet.rectangle(3.0, 7.0, 0.5)
    assert other is not a
    assert not np.array_equal(other.vertices, a.vertices)
    assert not a.vertices.flags.writeable  # shared, so never written
