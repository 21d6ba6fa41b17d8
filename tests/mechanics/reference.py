"""Closed-form and ODE references for the mechanics tests (never computed with the model)."""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_bvp


def navier_centre(terms: int = 200) -> float:
    """Centre deflection of a simply supported square plate under uniform load, over
    ``q a^4 / D`` (Navier's double sine series)."""
    m = np.arange(1, 2 * terms, 2, dtype=float)
    mm, nn = np.meshgrid(m, m)
    sign = np.sin(mm * np.pi / 2) * np.sin(nn * np.pi / 2)
    return float(16 / np.pi**6 * np.sum(sign / (mm * nn * (mm**2 + nn**2) ** 2)))


def clamped_centre(terms: int = 60, points: int = 600) -> float:
    """Centre deflection of a clamped square plate under uniform load, over ``q a^4 / D``.

    Timoshenko's superposition (Theory of Plates and Shells, sec. 44): the simply
    supported plate under the load plus the plates bent by edge moments
    ``sum E_m sin(m pi x / a)`` on all four edges, the ``E_m`` solving the zero-slope
    conditions (a = 1, q = 1, D = 1; the series truncated at ``terms`` odd terms).
    """
    c = 0.5
    m = np.arange(1, 2 * terms, 2, dtype=float)
    al = m * np.pi
    ch, sh = np.cosh(al * c), np.sinh(al * c)

    def lin(rhs_y: np.ndarray, rhs_ypp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        # Y = A cosh(al y) + B al y sinh(al y): Y(c) = rhs_y, Y''(c) = rhs_ypp.
        a11, a12 = ch, al * c * sh
        a21, a22 = al**2 * ch, al**2 * (2 * ch + al * c * sh)
        det = a11 * a22 - a12 * a21
        return (rhs_y * a22 - a12 * rhs_ypp) / det, (a11 * rhs_ypp - a21 * rhs_y) / det

    def slope(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return a * al * sh + b * al * (sh + al * c * ch)

    p = 4.0 / (m**5 * np.pi**5)
    a0, b0 = lin(-p, np.zeros_like(p))
    a1, b1 = lin(np.zeros_like(p), -np.ones_like(p))  # unit edge moment: -D Y''(c) = 1
    s0, s1 = slope(a0, b0), slope(a1, b1)
    x, w = np.polynomial.legendre.leggauss(points)
    x, w = (x + 1) / 2, w / 2
    xi = x - c
    y1 = a1[None, :] * np.cosh(al[None, :] * xi[:, None]) + b1[None, :] * al * xi[
        :, None
    ] * np.sinh(al[None, :] * xi[:, None])
    proj = 2 * np.einsum("k,km,kn->mn", w, np.sin(al[None, :] * x[:, None]), y1)
    system = np.diag(s1) - proj * al[None, :]
    e = np.linalg.solve(system, -s0)
    sign = np.sin(m * np.pi / 2)
    return float(np.sum(sign * (p + a0)) + 2 * np.sum(sign * e * a1))


def heavy_elastica_tip(load: float) -> tuple[float, float]:
    """A heavy inextensible cantilever, clamped level, under its own weight.

    ``load = q L^3 / D`` (q: weight per unit length and width). Solves
    ``theta'' = -load (1 - s) cos(theta)``, ``theta(0) = 0``, ``theta'(1) = 0`` (s over L)
    with scipy's solve_bvp. Returns the tip's drop and pull-in over L.
    """

    def rhs(s, y):
        theta, dtheta, drop, pull = y
        return np.vstack(
            [dtheta, -load * (1 - s) * np.cos(theta), np.sin(theta), 1 - np.cos(theta)]
        )

    def bc(ya, yb):
        return np.array([ya[0], yb[1], ya[2], ya[3]])

    s = np.linspace(0, 1, 201)
    guess = np.zeros((4, len(s)))
    guess[0] = load * (s - s**2 + s**3 / 3) / 2
    sol = solve_bvp(rhs, bc, s, guess, tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(sol.message)
    return float(sol.y[2, -1]), float(sol.y[3, -1])


def gardiner_ratio(x: float) -> float:
    """Springback ``R_i / R_f = 4 x^3 - 3 x + 1`` (Gardiner), ``x = R_i sigma_y / (E' t)``."""
    return 4 * x**3 - 3 * x + 1 if x < 0.5 else 0.0


_ = math
