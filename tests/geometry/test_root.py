"""The root search's inverse interpolation (geometry/root.py).

The expected values are the constant terms of polynomials chosen here: the
inverse interpolant through points of a polynomial h(f) of degree below the
number of points is that polynomial, so its value at f = 0 is known without
the code under test.
"""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from onefold_cad.geometry.root import neville

_value = st.floats(-1.0, 1.0, allow_nan=False)


@given(
    st.integers(2, 7).flatmap(
        lambda n: st.tuples(
            st.floats(-0.4, 0.4, allow_nan=False),
            st.lists(_value, min_size=n, max_size=n),
        )
    )
)
def test_inverse_interpolation_reproduces_a_polynomial_of_its_degree(case) -> None:
    shift, coeffs = case
    n = len(coeffs)
    # Chebyshev nodes (well conditioned), shifted so that 0 lies anywhere among them
    fs = [math.cos((2 * k + 1) * math.pi / (2 * n)) + shift for k in range(n)]
    hs = [math.fsum(c * f**j for j, c in enumerate(coeffs)) for f in fs]
    scale = math.fsum(abs(c) * 1.4**j for j, c in enumerate(coeffs))
    assert abs(neville(fs, hs) - coeffs[0]) <= 1e-13 * (scale + 1e-300) * 10.0


def test_inverse_interpolation_of_a_straight_line_is_its_root() -> None:
    # h = 2 + 3 f: at f = 0, h = 2, whatever the points (5 and 6 points are
    # the search's own sizes)
    for n in (2, 5, 6, 7):
        fs = [0.25 * k - 0.6 for k in range(n)]
        assert math.isclose(neville(fs, [2.0 + 3.0 * f for f in fs]), 2.0, rel_tol=1e-14)


def test_inverse_interpolation_with_two_equal_values_is_nan() -> None:
    for n in (2, 5, 6, 7):
        fs = [0.1 * k for k in range(n)]
        fs[-1] = fs[0]
        assert math.isnan(neville(fs, [float(k) for k in range(n)]))
