"""The continuation's predicted start (mechanics/predictor.py): Lagrange's
extrapolation against polynomials evaluated directly."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.mechanics.predictor import extrapolate

RNG = np.random.default_rng(35)


@pytest.mark.parametrize("params", [(0.0, 0.125, 0.25, 0.375), (0.0, 0.1, 0.15, 0.35)])
def test_the_polynomial_through_k_plus_1_states_is_exact_to_degree_k(params):
    coef = RNG.normal(size=(4, 7))  # (degree + 1, N): a cubic in s, per unknown

    def q(s: float) -> np.ndarray:
        return sum(c * s**i for i, c in enumerate(coef))

    for k in range(4):
        pts = [(s, q(s)) for s in params[-(k + 1) :]]
        low = coef.copy()
        low[k + 1 :] = 0.0  # the polynomial cut to degree k is reproduced exactly
        exact = [(s, sum(c * s**i for i, c in enumerate(low))) for s in params[-(k + 1) :]]
        np.testing.assert_allclose(
            extrapolate(exact, 0.5), sum(c * 0.5**i for i, c in enumerate(low)), rtol=1e-12
        )
        if k < 3:
            # s^(k+1) through k+1 points errs by the product of (t - s_i) exactly
            mono = [(s, np.full(3, s ** (k + 1))) for s in params[-(k + 1) :]]
            error = 0.5 ** (k + 1) - extrapolate(mono, 0.5)
            np.testing.assert_allclose(error, np.prod([0.5 - s for s in params[-(k + 1) :]]))
        assert extrapolate(pts, params[-1]) == pytest.approx(q(params[-1]))


def test_held_unknowns_keep_the_last_state():
    pts = [(0.0, np.array([0.0, 1.0, 2.0])), (0.5, np.array([1.0, 1.5, 3.0]))]
    out = extrapolate(pts, 1.0, held=np.array([False, True, False]))
    np.testing.assert_array_equal(out, [2.0, 1.5, 4.0])


def test_one_state_is_its_own_prediction_and_bad_paths_are_refused():
    one = [(0.25, np.array([3.0, -1.0]))]
    np.testing.assert_array_equal(extrapolate(one, 0.75), [3.0, -1.0])
    with pytest.raises(ValueError, match="at least one"):
        extrapolate([], 0.5)
    with pytest.raises(ValueError, match="repeat"):
        extrapolate([(0.25, np.zeros(2)), (0.25, np.ones(2))], 0.5)
