"""Newton's method (mechanics/newton.py): no unconverged result, progress, shifts."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from onefold_cad.errors import ConvergenceError, OneFoldError
from onefold_cad.mechanics import minimize, solve_equilibrium
from onefold_cad.mechanics.newton import FactorReuse, SymmetricFactor
from tests.mechanics.helpers import cantilever, rectangle
from tests.mechanics.test_equilibrium import STEEL0, _gravity_for, _start


def test_unconverged_newton_raises_with_its_residual():
    mesh = rectangle(1.0, 0.1, 0.05)
    shell, fixed = cantilever(mesh, STEEL0, _gravity_for(2.0))
    seen = []
    with pytest.raises(ConvergenceError) as info:
        solve_equilibrium(
            shell, _start(mesh), fixed=fixed, max_iter=1, callback=lambda *a: seen.append(a)
        )
    err = info.value
    assert isinstance(err, OneFoldError) and isinstance(err, RuntimeError)
    assert err.iterations == 1 and err.residual > 0
    assert "1 iterations" in str(err) and f"{err.residual:.3g}" in str(err)
    assert [s[0] for s in seen] == [0, 1], "progress before every step and at the end"
    assert seen[-1][1] == err.residual


def _rosenbrock(q, order):
    x, y = q
    e = (1 - x) ** 2 + 100 * (y - x**2) ** 2
    if order == 0:
        return e, None, None
    g = np.array([-2 * (1 - x) - 400 * x * (y - x**2), 200 * (y - x**2)])
    h = np.array([[2 - 400 * (y - x**2) + 800 * x**2, -400 * x], [-400 * x, 200.0]])
    full = sp.csc_matrix(np.ones((2, 2)))  # a fixed structure, as minimize requires
    full.data[:] = h.T.ravel()
    return e, g, full


def test_indefinite_start_and_a_fixed_unknown():
    # At (0, 1) Rosenbrock's Hessian is indefinite: the shifted steps still descend.
    result = minimize(_rosenbrock, [0.0, 1.0], np.zeros(2, bool), rtol=0, atol=1e-10, max_iter=100)
    np.testing.assert_allclose(result.q, [1.0, 1.0], atol=1e-8)
    # Holding y = 4: a minimiser over x alone, dE/dx = 0 there.
    held = minimize(_rosenbrock, [0.5, 4.0], np.array([False, True]), rtol=0, atol=1e-10)
    assert held.q[1] == 4.0
    assert abs(held.gradient[0]) < 1e-10 and held.gradient[1] != 0


def test_a_predicted_start_does_not_loosen_the_tolerance():
    """The tolerance is rtol times the larger of force_scale and the start's
    residual; with ``start_scales=False`` (a start predicted along a load path)
    force_scale's alone, however far the start."""
    start = [-2.0, 5.0]  # Rosenbrock's gradient there: (794, 200)
    res0 = float(np.abs(_rosenbrock(np.array(start), 1)[1]).max())
    assert res0 == 794.0
    loose = minimize(_rosenbrock, start, np.zeros(2, bool), force_scale=1.0, rtol=1e-6,
                     max_iter=100)  # fmt: skip
    assert loose.tolerance == pytest.approx(1e-6 * res0)
    strict = minimize(_rosenbrock, start, np.zeros(2, bool), force_scale=1.0, rtol=1e-6,
                      max_iter=100, start_scales=False)  # fmt: skip
    assert strict.tolerance == 1e-6
    assert strict.residual <= 1e-6


def _spd(seed: int, n: int = 40) -> sp.csc_matrix:
    """A random sparse symmetric matrix, diagonally dominant, of one fixed structure."""
    rng = np.random.default_rng(0)
    mask = rng.random((n, n)) < 0.1
    mask = mask | mask.T | np.eye(n, dtype=bool)
    values = np.random.default_rng(seed).standard_normal((n, n))
    a = np.where(mask, values + values.T, 0.0)
    a[np.diag_indices(n)] = np.abs(a).sum(axis=1) + 1.0
    m = sp.csc_matrix(mask.astype(float))
    m.data[:] = a[mask.T].ravel()  # CSC stores column by column: a[mask.T] in that order
    assert np.array_equal(m.toarray(), a)
    return m


def test_a_refilled_factor_is_a_fresh_one():
    """Each factorisation refills one upper-triangle matrix: after other
    matrices, a shifted one and an indefinite one, its solution is bit for bit
    that of a factor made for the matrix alone, and the matrices are untouched."""
    a, b = _spd(1), _spd(2)
    n = a.shape[0]
    rhs = np.arange(1.0, n + 1)
    fresh = SymmetricFactor(a)
    assert fresh.factor(a)
    expected = fresh.solve(rhs)
    np.testing.assert_allclose(a @ expected, rhs, rtol=1e-12)
    a_data = a.data.copy()
    reused = SymmetricFactor(a)
    assert reused.factor(b)
    assert reused.factor(a, np.full(n, 5.0))
    assert not np.array_equal(reused.solve(rhs), expected)  # the shift is in this one
    indefinite = a.copy()
    indefinite.data = -indefinite.data
    assert not reused.factor(indefinite)
    assert reused.factor(a)
    assert np.array_equal(reused.solve(rhs), expected)
    assert np.array_equal(a.data, a_data), "the shift went into the caller's matrix"


def test_an_imposed_state_needs_no_hessian():
    """Every unknown fixed (a form imposed whole): the energy and gradient
    there, at 0 iterations with the tolerance the loop would give, and no
    Hessian evaluated."""
    orders: list[int] = []

    def fun(q, order):
        orders.append(order)
        return _rosenbrock(q, order)

    seen: list[tuple] = []
    result = minimize(fun, [0.5, 4.0], np.ones(2, bool), force_scale=3.0, rtol=1e-6,
                      atol=1e-9, callback=lambda *a: seen.append(a))  # fmt: skip
    energy, gradient, _ = _rosenbrock(np.array([0.5, 4.0]), 1)
    assert orders == [1]
    assert result.iterations == 0 and result.residual == 0.0
    assert result.energy == energy and np.array_equal(result.gradient, gradient)
    assert np.array_equal(result.q, [0.5, 4.0]) and result.tolerance == 3e-6
    assert seen == [(0, 0.0, energy)]


def test_factor_reuse_keeps_one_factor_per_structure():
    """A structure met before gets its factor back (numeric refactorisation
    only), bit for bit the answer of a fresh one; another structure a new
    factor; at most ``size`` structures are kept, the most recent."""
    a, b = _spd(1), _spd(2)  # one structure, two matrices
    other = _spd(3, n=41)
    rhs = np.arange(1.0, a.shape[0] + 1)
    reuse = FactorReuse(size=2)
    first = reuse.factor_for(a)
    assert first.factor(a)
    assert reuse.factor_for(b) is first
    assert first.factor(b)
    fresh = SymmetricFactor(b)
    assert fresh.factor(b)
    assert np.array_equal(first.solve(rhs), fresh.solve(rhs))
    assert reuse.factor_for(other) is not first
    assert reuse.factor_for(a.copy()) is first, "equal structures, not the same object"
    third = _spd(4, n=42)
    reuse.factor_for(third)  # the oldest, ``other``'s, goes
    assert reuse.factor_for(a) is first
    assert reuse.factor_for(other) is not reuse.factor_for(third)
