"""Points of the frame curve (geometry/frame.py), against the paper's formula in mpmath."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad import FrameCurve, InvalidParameterError
from onefold_cad.geometry.arc import ArcSpacing, division_points, end_relative
from onefold_cad.geometry.frame_curve import arc_geometry

EPS = 2.0**-52


@given(
    alpha=st.floats(0.01, 89.99),
    hc_frac=st.floats(-0.999, 0.999),
    n=st.integers(1, 64),
)
def test_division_points_match_the_paper_formula_to_rounding_near_the_ends(
    alpha: float, hc_frac: float, n: int
) -> None:
    radius = 100.0
    h_c = hc_frac * radius * float(mp.cos(mp.radians(alpha)))
    frame = FrameCurve(alpha, 45.0, h_c, radius, n)
    g = arc_geometry(frame)
    x, d = division_points(g, n)
    with mp.workdps(40):
        a = mp.radians(mp.mpf(alpha))
        hc = mp.mpf(h_c) / radius
        for k in range(n + 1):
            # paper 3.2: x = cos(phi) - h_c / R, d = sin(alpha) + sin(phi), phi equally spaced
            phi = -a + (mp.pi + 2 * a) * k / n
            xe, de = mp.cos(phi) - hc, mp.sin(a) + mp.sin(phi)
            # each point to a few rounding errors of its arc distance from the
            # nearer end, plus (x) the error of that end's distance L from H:
            # a rounding error of L below R/16 (decimal), of R above
            end = float(min(k, n - k) * (mp.pi + 2 * a) / n)
            ell = g.l_plus if 2 * k <= n else g.l_minus
            ell_err = ell if ell < 1.0 / 16.0 else 2.0
            assert abs(float(x[k] - xe)) <= 4 * EPS * (ell_err + end) + 1e-30
            assert abs(float(d[k] - de)) <= 6 * EPS * end + 1e-30  # (mp rounding at the ends)


def test_end_relative_for_one_end_equals_the_per_point_choice() -> None:
    g = arc_geometry(FrameCurve(37.0, 45.0, 12.0, 100.0, 10))
    s = np.linspace(0.0, 2.0, 41)
    for plus in (True, False):
        x1, d1 = end_relative(g, s, plus)
        x2, d2 = end_relative(g, s, np.full(s.shape, plus))
        assert np.array_equal(x1, x2) and np.array_equal(d1, d2)


@given(n=st.integers(1, 200))
def test_uniform_spacing_gives_the_paper_points_to_the_bit(n: int) -> None:
    g = arc_geometry(FrameCurve(37.0, 45.0, 12.0, 100.0, n))
    assert np.array_equal(division_points(g, n, ArcSpacing.uniform(n)), division_points(g, n))


def _widths(sp: ArcSpacing) -> np.ndarray:
    """The wedges' widths as fractions of the span, from the steps."""
    s = np.asarray(sp.steps)
    t = np.concatenate((s[: sp.front], sp.per_span - s[sp.front :])) / sp.per_span
    return np.diff(t)


@pytest.mark.parametrize(
    ("n", "first", "ratio", "want"),
    [
        # 0.01 x 3^i from each end, capped at c: 2 (0.01 + 0.03 + 0.09) + 4 c = 1
        (10, (0.01, 0.01), 3.0, [0.01, 0.03, 0.09] + [0.185] * 4 + [0.09, 0.03, 0.01]),
        # 2 (0.02 + 0.04 + 0.08 + 0.16) < 1: the ratio is raised to 2.5, then
        # 2 (0.02 + 0.05 + 0.125) + 2 c = 1
        (8, (0.02, 0.02), 2.0, [0.02, 0.05, 0.125, 0.305, 0.305, 0.125, 0.05, 0.02]),
        # from the -x end 0.002 r^k: r = 3 and its raises by 1.25 leave the sum
        # under 1 until r = 3 x 1.25^4 (0.5 + 0.002 (r^3 + r^2 + r + 1) < 1 before);
        # then the two widest share what is left, c = (1 - 0.002 (r^2 + r + 1)) / 2,
        # under the +x end's 0.5
        (5, (0.5, 0.002), 3.0, "raised"),
    ],
)
def test_graded_widths_worked_by_hand(n, first, ratio, want) -> None:
    w = _widths(ArcSpacing.graded(n, first, ratio))
    if want == "raised":
        r = 3.0 * 1.25**4
        c = (1.0 - 0.002 * (r * r + r + 1.0)) / 2.0
        want = [c, c, 0.002 * r * r, 0.002 * r, 0.002]
    np.testing.assert_allclose(w, want, rtol=1e-12, atol=1e-15)


@given(
    n=st.integers(3, 40),
    first=st.tuples(st.floats(1e-4, 0.5), st.floats(1e-4, 0.5)),
    ratio=st.floats(1.1, 5.0),
)
def test_graded_widths_add_up_to_the_span_and_rise_to_a_plateau(n, first, ratio) -> None:
    """Positive widths adding up to the span, the end ones at most f+ and f-,
    rising from each end (by at least ``ratio`` until the cap) to one even
    width between."""
    sp = ArcSpacing.graded(n, first, ratio)
    assert sp.divisions == n and sp.steps[0] == 0.0 and sp.steps[-1] == 0.0
    w = _widths(sp)
    assert np.all(w > 0.0)
    assert float(np.sum(w)) == pytest.approx(1.0, rel=1e-12)
    assert w[0] <= first[0] * (1 + 1e-9) and w[-1] <= first[1] * (1 + 1e-9)
    c = w.max()
    top = np.flatnonzero(w >= c * (1 - 1e-9))
    assert np.all(np.diff(top) == 1)  # one plateau
    for i in range(1, top[0] + 1):
        assert w[i] >= min(ratio * w[i - 1], c) * (1 - 1e-9)
    for i in range(top[-1], n - 1):
        assert w[i] >= min(ratio * w[i + 1], c) * (1 - 1e-9)


def test_graded_spacing_of_two_wedges_keeps_their_ratio() -> None:
    sp = ArcSpacing.graded(2, (0.01, 0.03), 3.0)
    assert sp.steps.tolist() == [0.0, 0.01, 0.0] and sp.per_span == pytest.approx(0.04)


def test_graded_spacing_refuses_bad_input_naming_spacing() -> None:
    for args in ((4, (0.0, 0.1), 2.0), (4, (0.1, 0.1), 1.0), (0, (0.1, 0.1), 2.0)):
        with pytest.raises(InvalidParameterError) as err:
            ArcSpacing.graded(*args)
        assert err.value.parameter == "spacing"
