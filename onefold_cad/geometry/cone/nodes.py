"""The exact cone's developed angle from its node table: the cheap evaluations
a body's many points need.

After the apex is set, the cone knows theta at every node of its verified
quadrature rule (:meth:`onefold_cad.geometry.cone.cone.ExactCone.node_table`: per
half of the arc, theta, the distance s from that half's end and |u'| =
dtheta/ds, ascending in s). Two things follow from it cheaply:

* :func:`theta_from_nodes`: theta at any s, integrated from the *nearest*
  node with a 4-point Gauss-Legendre rule instead of from its panel's start
  with 20 points. The nodes of a 20-point rule lie at most 0.16 of a panel's
  half-width apart and the panels keep the integrand's complex singularities
  at least 2.5 half-widths away (``REACH`` 0.4), so that short integral (at
  most 1/60 of the distance to a singularity across) is exact to rounding:
  the same values as ``theta_of_phi`` to a few units in the last place (held
  in tests/geometry/resting/test_lowest_search.py; 3 points already are), at a fifth
  of the work.
* :func:`hermite_s`: s at a given theta by cubic Hermite interpolation of the
  table (slopes ds/dtheta = 1 / |u'|): the first guess of the cone's Newton
  inversion, good to about 1e-10 rad, and all a sample's place needs.

Numpy only; s and theta in radians.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.arc import end_relative
from onefold_cad.geometry.cone.rule import speed_at
from onefold_cad.geometry.frame_curve import ArcGeometry
from onefold_cad.geometry.numeric import Array, gauss_legendre

__all__ = ["NEAR_NODES", "hermite_s", "theta_from_both", "theta_from_nodes"]

#: Gauss-Legendre points of the integral from the nearest node.
NEAR_NODES = 4

Table = tuple[Array, Array, Array]


def theta_from_nodes(table: Table, g: ArcGeometry, plus: bool, height: float, s: Array) -> Array:
    """theta from one half's end (``plus``: the +x end) at distances ``s``
    ``(k,)`` from it, for the apex at ``height`` (units of R): the table's theta
    at the nearest node plus the integral of |u'| from there (see the module
    docstring)."""
    th_tab, s_tab, _ = table
    j = s_tab.searchsorted(s)
    np.maximum(j, 1, out=j)  # np.clip's work without its Python wrapper
    np.minimum(j, len(s_tab) - 1, out=j)
    left = s_tab.take(j - 1)
    right = s_tab.take(j)
    j -= s - left <= right - s  # the nearer of the two
    a = s_tab.take(j)
    half = 0.5 * (s - a)
    x, w = gauss_legendre(NEAR_NODES)
    flat = ((a + half)[:, None] + half[:, None] * x).ravel()
    px, pd = end_relative(g, flat, plus)
    ang = flat - g.alpha
    cphi = np.cos(ang)
    if not plus:
        np.negative(cphi, out=cphi)
    speed = speed_at(g, px, pd, cphi, np.sin(ang), height).reshape(len(s), NEAR_NODES)
    return th_tab.take(j) + half * (speed @ w)


def theta_from_both(
    tables: tuple[Table, Table], g: ArcGeometry, height: float, s: Array, plus: NDArray[np.bool_]
) -> Array:
    """:func:`theta_from_nodes` of points on either half in one pass: theta
    from each one's own end (``plus``: the +x half's, table 0) at distances
    ``s`` ``(k,)`` from it, the same arithmetic per point."""
    (th0, s0, _), (th1, s1, _) = tables
    n0 = len(s0)
    th_tab, s_tab = np.concatenate((th0, th1)), np.concatenate((s0, s1))
    j = np.empty(len(s), dtype=np.int64)
    minus = ~plus
    j[plus] = s0.searchsorted(s[plus])
    j[minus] = s1.searchsorted(s[minus])
    lo = np.where(plus, 1, n0 + 1)
    np.maximum(j + np.where(plus, 0, n0), lo, out=j)
    np.minimum(j, lo + np.where(plus, n0 - 2, len(s1) - 2), out=j)
    left = s_tab.take(j - 1)
    right = s_tab.take(j)
    j -= s - left <= right - s  # the nearer of the two
    a = s_tab.take(j)
    half = 0.5 * (s - a)
    x, w = gauss_legendre(NEAR_NODES)
    flat = ((a + half)[:, None] + half[:, None] * x).ravel()
    each = np.repeat(plus, NEAR_NODES)
    px, pd = end_relative(g, flat, each)
    ang = flat - g.alpha
    cphi = np.cos(ang)
    np.negative(cphi, out=cphi, where=~each)
    speed = speed_at(g, px, pd, cphi, np.sin(ang), height).reshape(len(s), NEAR_NODES)
    return th_tab.take(j) + half * (speed @ w)


def hermite_s(table: Table, theta: Array) -> tuple[Array, Array]:
    """s at developed angles ``theta`` ``(k,)`` (from the half's end) by cubic
    Hermite interpolation of the table, kept between its neighbouring
    points; and |u''| / |u'| across their interval (how far the cone's Newton
    step must go, :meth:`onefold_cad.geometry.cone.cone.ExactCone.phi_of_theta`)."""
    th_tab, s_tab, sp_tab = table
    j = th_tab.searchsorted(theta, side="right")
    j -= 1
    np.maximum(j, 0, out=j)
    np.minimum(j, len(th_tab) - 2, out=j)
    t0, t1 = th_tab.take(j), th_tab.take(j + 1)
    s0, s1 = s_tab.take(j), s_tab.take(j + 1)
    dt, ds = t1 - t0, s1 - s0
    sp0, sp1 = sp_tab.take(j), sp_tab.take(j + 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(dt > 0.0, (theta - t0) / dt, 0.0)
        m0, m1 = dt / sp0, dt / sp1
        bend = np.where(ds > 0.0, np.abs(sp1 - sp0) / (ds * np.minimum(sp0, sp1)), 0.0)
    x2 = x * x
    h01 = x2 * (3.0 - 2.0 * x)
    s = s0 + h01 * ds + (x2 * x - 2.0 * x2 + x) * m0 + (x2 * x - x2) * m1
    s = np.where(np.isfinite(s), s, s0 + x * ds)
    np.maximum(s, s0, out=s)
    np.minimum(s, s1, out=s)
    return s, bend
