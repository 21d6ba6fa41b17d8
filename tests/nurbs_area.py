"""The area of a .3dm face as rhino3dm reads it back, integrated from its
control net (an independent check of the file's geometry: no onefold_cad
code), shared by the .3dm and Hops tests."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.interpolate import BSpline


def surface_area(surface: Any) -> float:
    """The area of a rhino3dm face (cubic in u, linear in v, non-rational, as
    the .3dm's), integrated from its control net: Gauss-Legendre on each knot
    span of u, and in v."""
    n = surface.ToNurbsSurface()
    assert (n.OrderU, n.OrderV) == (4, 2) and not n.IsRational
    knots = np.array([n.KnotsU[i] for i in range(len(n.KnotsU))])
    knots = np.concatenate([knots[:1], knots, knots[-1:]])  # openNURBS drops the end knots
    net = np.array(
        [[[(q := n.Points[i, j]).X, q.Y, q.Z] for j in range(2)] for i in range(n.Points.CountU)]
    )
    inner, outer = BSpline(knots, net[:, 0], 3), BSpline(knots, net[:, 1], 3)
    d_in, d_out = inner.derivative(), outer.derivative()
    g, w = np.polynomial.legendre.leggauss(8)
    spans = np.unique(knots)
    total = 0.0
    for a, b in zip(spans[:-1], spans[1:], strict=True):
        u = 0.5 * (a + b) + 0.5 * (b - a) * g
        for v, wv in zip(0.5 + 0.5 * g, 0.5 * w, strict=True):
            su = (1 - v) * d_in(u) + v * d_out(u)
            sv = outer(u) - inner(u)
            total += float(
                np.sum(0.5 * (b - a) * w * wv * np.linalg.norm(np.cross(su, sv), axis=1))
            )
    return total
