"""Points of the frame curve (geometry/frame.py), against the paper's formula in mpmath."""

from __future__ import annotations

import mpmath as mp
import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad import FrameCurve
from onefold_cad.geometry.arc import division_points, end_relative
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
