"""Local geometric functions (mechanics/kinematics.py) against finite differences and
hand values."""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from onefold_cad.mechanics.kinematics import METRIC_HESSIAN, dihedral, face_heights, face_metric
from tests.mechanics.helpers import central_difference

RNG = np.random.default_rng(7)


def _element(fun, x, e, part, order, y):
    """``fun(x with element e replaced by y)[part][e]`` (y flattened)."""
    z = x.copy()
    z[e] = y.reshape(x.shape[1:])
    return np.atleast_1d(fun(z, order)[part][e])


def _close(a, b):
    np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-7 * np.abs(b).max())


def test_dihedral_derivatives():
    x = RNG.normal(size=(20, 4, 3))
    _, dpsi, d2psi = dihedral(x)
    for e in range(len(x)):
        g = central_difference(partial(_element, dihedral, x, e, 0, 0), x[e].ravel(), 1e-4)
        h = central_difference(partial(_element, dihedral, x, e, 1, 1), x[e].ravel(), 1e-4)
        _close(g[:, 0], dpsi[e])
        _close(h, d2psi[e])


def test_dihedral_sign_and_value():
    # Edge along x, T0 = (a, b, c) with c at +y, T1's d at -y; both lifted: a bowl.
    for angle in (0.3, 1.0, 2.5):
        up = math.tan(angle / 2)
        x = np.array([[[0, 0, 0], [1, 0, 0], [0.3, 1, up], [0.6, -1, up]]], dtype=float)
        assert math.isclose(dihedral(x, 0)[0][0], angle, rel_tol=1e-12)
        x[0, 2:, 2] *= -1
        assert math.isclose(dihedral(x, 0)[0][0], -angle, rel_tol=1e-12)


def test_heights_derivatives_and_values():
    x = RNG.normal(size=(20, 3, 3))
    h, dh, d2h = face_heights(x)
    area = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
    for i in range(3):
        length = np.linalg.norm(x[:, (i + 2) % 3] - x[:, (i + 1) % 3], axis=1)
        np.testing.assert_allclose(h[:, i], 2 * area / length, rtol=1e-13)
    for f in range(len(x)):
        g = central_difference(partial(_element, face_heights, x, f, 0, 0), x[f].ravel(), 1e-4)
        hh = central_difference(partial(_element, face_heights, x, f, 1, 1), x[f].ravel(), 1e-4)
        _close(g.T, dh[f])
        _close(np.moveaxis(hh, 0, -1), d2h[f])


def test_metric_derivatives():
    x = RNG.normal(size=(5, 3, 3))
    _, da = face_metric(x)
    metric = lambda z, order: face_metric(z)  # noqa: E731
    for f in range(len(x)):
        g = central_difference(partial(_element, metric, x, f, 0, 0), x[f].ravel(), 1e-3)
        hh = central_difference(partial(_element, metric, x, f, 1, 0), x[f].ravel(), 1e-3)
        np.testing.assert_allclose(g.T, da[f], atol=1e-9)
        np.testing.assert_allclose(np.moveaxis(hh, 0, -1), METRIC_HESSIAN, atol=1e-9)
