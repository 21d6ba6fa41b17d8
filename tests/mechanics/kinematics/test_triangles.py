"""Local geometric functions (mechanics/kinematics/triangles.py) against finite differences and
hand values."""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from onefold_cad.mechanics.kinematics.triangles import (
    METRIC_HESSIAN,
    SlopeTerms,
    area_hessian,
    area_jacobian,
    dihedral,
    director_slopes,
    face_heights,
    face_metric,
)
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


def _slopes(x, d, f, i, order, y):
    xx, dd = x.copy(), d.copy()
    xx[f], dd[f, i] = y[:9].reshape(3, 3), y[9:]
    return director_slopes(xx, dd, order)[order][f, i]


def test_director_slopes():
    # its own draws: with the module's RNG the inputs depended on which tests
    # ran before in the same process (pytest-xdist), and one of them was
    # rough enough for the finite differences to miss by 1.3e-6
    rng = np.random.default_rng(8)
    m = 8
    x = rng.normal(size=(m, 3, 3))
    edge = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    d = rng.normal(size=(m, 3, 3))
    d -= (np.einsum("mij,mij->mi", d, edge) / np.einsum("mij,mij->mi", edge, edge))[
        :, :, None
    ] * edge
    u, du, d2u = director_slopes(x, d)
    # u_i = h_i tan(phi_i), phi_i from the face normal towards the face's inside.
    h = face_heights(x, 0)[0]
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    for i in range(3):
        unit = edge[:, i] / np.linalg.norm(edge[:, i], axis=1)[:, None]
        inward = x[:, i] - x[:, (i + 1) % 3]
        inward -= np.einsum("ij,ij->i", inward, unit)[:, None] * unit
        inward /= np.linalg.norm(inward, axis=1)[:, None]
        tan = np.einsum("ij,ij->i", d[:, i], inward) / np.einsum("ij,ij->i", d[:, i], normal)
        np.testing.assert_allclose(u[:, i], h[:, i] * tan, rtol=1e-12, atol=1e-13)
    for f in range(3):
        for i in range(3):
            y = np.concatenate([x[f].ravel(), d[f, i]])
            g = central_difference(partial(_slopes, x, d, f, i, 0), y, 1e-4)
            hh = central_difference(partial(_slopes, x, d, f, i, 1), y, 1e-4)
            _close(g, du[f, i])
            _close(hh, d2u[f, i])


def _weighted_slope_gradient(x, d, w, f, y):
    """The gradient of ``sum_i w_i u_i`` of face ``f`` over its coordinates and its
    three directors (18), at ``y`` (the same 18)."""
    xx, dd = x.copy(), d.copy()
    xx[f], dd[f] = y[:9].reshape(3, 3), y[9:].reshape(3, 3)
    du = director_slopes(xx, dd, 1)[1][f]
    grad = np.zeros(18)
    grad[:9] = w[f] @ du[:, :9]
    grad[9:] = (w[f][:, None] * du[:, 9:]).ravel()
    return grad


def test_weighted_slope_hessians_are_the_derivative_of_the_weighted_gradient():
    """``SlopeTerms.hessian(w)``: the blocks of ``sum_i w_i d2u_i`` over the
    coordinates and each edge's director, against central differences of the
    weighted gradient (each ``d_i`` its own variables: no ``d_i d_j`` block)."""
    m = 6
    x = RNG.normal(size=(m, 3, 3))
    d = RNG.normal(size=(m, 3, 3))
    w = RNG.normal(size=(m, 3))
    hxx, hxd, hdd = SlopeTerms(x, d).hessian(w)
    assert hxx.shape == (m, 9, 9) and hxd.shape == (m, 3, 9, 3) and hdd.shape == (m, 3, 3, 3)
    for f in range(m):
        y = np.concatenate([x[f].ravel(), d[f].ravel()])
        h = central_difference(partial(_weighted_slope_gradient, x, d, w, f), y, 1e-5)
        full = np.zeros((18, 18))
        full[:9, :9] = hxx[f]
        for i in range(3):
            s = slice(9 + 3 * i, 12 + 3 * i)
            full[:9, s] = hxd[f, i]
            full[s, :9] = hxd[f, i].T
            full[s, s] = hdd[f, i]
        _close(h, full)


def _doubled_area(y):
    """|N| of one face's 9 coordinates, as a (1,) array."""
    p = y.reshape(3, 3)
    return np.atleast_1d(np.linalg.norm(np.cross(p[1] - p[0], p[2] - p[0])))


def _faces(rng, m):
    x = rng.normal(size=(m, 3, 3))
    edge = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    nn = np.einsum("ij,ij->i", normal, normal)
    df = (np.cross(normal[:, None, :], edge) / nn[:, None, None]).reshape(m, 9)
    return x, edge, normal, nn, df


def _size_hessian(y):
    """The Hessian of |N| by central differences of central differences."""

    def grad(z):
        return central_difference(_doubled_area, z, 1e-4)[:, 0]

    return central_difference(grad, y, 1e-4)


def test_area_hessian_is_the_weighted_hessian_of_the_doubled_area():
    """``area_hessian``: weight times the Hessian of |N| (twice the face's area)."""
    rng = np.random.default_rng(12)  # its own draws, whatever ran before
    x, edge, normal, nn, df = _faces(rng, 6)
    weight = rng.normal(size=6)
    h = area_hessian(area_jacobian(edge), normal, nn, df, weight)
    for f in range(len(x)):
        expected = weight[f] * _size_hessian(x[f].ravel())
        np.testing.assert_allclose(h[f], expected, atol=1e-7 * np.abs(expected).max())
