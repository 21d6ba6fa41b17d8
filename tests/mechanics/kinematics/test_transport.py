"""Transported directors (mechanics/kinematics/transport.py) against finite differences and
hand values."""

from __future__ import annotations

from functools import partial

import numpy as np

from onefold_cad.mechanics.kinematics.transport import transported_director
from tests.mechanics.helpers import central_difference

RNG = np.random.default_rng(7)


def _close(a, b):
    np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-7 * np.abs(b).max())


def _frames(k):
    t0 = RNG.normal(size=(k, 3))
    t0 /= np.linalg.norm(t0, axis=1)[:, None]
    r0 = RNG.normal(size=(k, 3))
    r0 -= np.einsum("ij,ij->i", r0, t0)[:, None] * t0
    return t0, r0 / np.linalg.norm(r0, axis=1)[:, None]


def _director(t0, r0, e, theta, e_id, order, y):
    ee, tt = e.copy(), theta.copy()
    ee[e_id], tt[e_id] = y[:3], y[3]
    return transported_director(t0, r0, ee, tt, order)[order][e_id]


def test_transported_director():
    k = 15
    t0, r0 = _frames(k)
    e = 2 * t0 + 0.5 * RNG.normal(size=(k, 3))
    theta = RNG.normal(size=k)
    d, dd, d2d = transported_director(t0, r0, e, theta)
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1, atol=1e-15)
    assert np.abs(np.einsum("ij,ij->i", d, e)).max() < 1e-14, "normal to its edge"
    same = transported_director(t0, r0, 3 * t0, np.zeros(k), 0)[0]
    np.testing.assert_allclose(same, r0, atol=1e-15), "no transport along t0"
    # Transport along a great circle: r0 turns with t if r0 is normal to both.
    axis = np.cross(t0, r0)
    turned = np.cos(0.8) * t0 + np.sin(0.8) * r0  # t0 rotated about axis by 0.8
    moved = transported_director(t0, r0, turned, np.zeros(k), 0)[0]
    np.testing.assert_allclose(moved, np.cos(0.8) * r0 - np.sin(0.8) * t0, atol=1e-14)
    assert np.abs(np.einsum("ij,ij->i", moved, axis)).max() < 1e-14
    for i in range(k):
        y = np.concatenate([e[i], [theta[i]]])
        g = central_difference(partial(_director, t0, r0, e, theta, i, 0), y, 1e-4)
        h = central_difference(partial(_director, t0, r0, e, theta, i, 1), y, 1e-4)
        _close(g.T, dd[i])
        _close(np.moveaxis(h, 0, -1), d2d[i])
