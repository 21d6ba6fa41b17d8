"""B-spline fitting with OCC: curves interpolated through points at nodes
spread by arc length and refined where a probe between nodes misses the
tolerance (the sheet's edges mapped onto the cone, the solid's edge curves).

Lengths are in the design unit.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from OCP.collections import (
    HArray1_double,
    HArray1_gp_Pnt,
    HArray1_gp_Pnt2d,
)
from OCP.Geom import (
    Geom_BSplineCurve,
)
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.Geom2dAPI import Geom2dAPI_Interpolate
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.gp import gp_Pnt, gp_Pnt2d

from onefold_cad.errors import ExportError
from onefold_cad.geometry.numeric import Array

__all__ = [
    "DENSE",
    "MAX_NODES",
    "PROBES",
    "CachedSamples",
    "arc_length_nodes",
    "curve_values",
    "fit_curve",
    "interpolate",
    "probe_points",
    "refine",
]


def interpolate(points: Array, params: Array, what: str) -> Geom_BSplineCurve | Geom2d_BSplineCurve:
    """The B-spline through ``points`` ``(k, 2)`` (a pcurve) or ``(k, 3)`` at the
    parameters ``params`` ``(k,)``, by OCC's interpolation.

    Raises:
        ExportError: the interpolation failed (``what`` names the curve).
    """
    pts = np.asarray(points, dtype=float)
    plane = pts.shape[1] == 2
    arr = (HArray1_gp_Pnt2d if plane else HArray1_gp_Pnt)(1, len(pts))
    par = HArray1_double(1, len(pts))
    point = gp_Pnt2d if plane else gp_Pnt
    for i, (p, t) in enumerate(zip(pts, params, strict=True)):
        arr.SetValue(i + 1, point(*map(float, p)))
        par.SetValue(i + 1, float(t))
    interp = (Geom2dAPI_Interpolate if plane else GeomAPI_Interpolate)(arr, par, False, 1e-12)
    interp.Perform()
    if not interp.IsDone():
        raise ExportError(f"could not interpolate {what}")
    return interp.Curve()


#: Relative parameters of the dense sample that places a curve's nodes:
#: uniform, and graded towards both ends.
DENSE = np.unique(
    np.concatenate(
        [np.linspace(0.0, 1.0, 257), np.geomspace(1e-9, 0.1, 64), 1.0 - np.geomspace(1e-9, 0.1, 64)]
    )
)


#: The most nodes a fitted curve may have.
MAX_NODES = 4000


#: Where a fitted curve is checked between two neighbouring nodes, as fractions
#: of the interval's length: at its quarters, not only its middle (a curve
#: whose parameterisation has a kink, as the rational arc's C1 knots give the
#: cone's pcurves, can meet the tolerance at an interval's middle and miss it
#: beside it).
PROBES = np.array([0.25, 0.5, 0.75])


def probe_points(t: Array, at_length, length_at) -> Array:
    """``(len(t) - 1, len(PROBES))`` parameters inside each interval of the
    nodes ``t`` at the :data:`PROBES` fractions of its length (of its
    parameter range where the length cannot place them inside)."""
    lo, hi = length_at(t[:-1]), length_at(t[1:])
    probe = at_length(lo[:, None] + (hi - lo)[:, None] * PROBES)
    even = t[:-1, None] + (t[1:] - t[:-1])[:, None] * PROBES
    inside = (probe > t[:-1, None]) & (probe < t[1:, None])
    return np.where(inside, probe, even)


def refine(probe: Array, err: Array, tol: float) -> tuple[Array, float]:
    """The nodes to add (the worst probe of each interval that misses ``tol``)
    and the largest deviation, from ``err`` at ``probe`` (both ``(n, p)``)."""
    worst = np.argmax(err, axis=1)
    rows = np.arange(len(err))
    bad = err[rows, worst] > tol
    return probe[rows[bad], worst[bad]], float(np.max(err))


def arc_length_nodes(
    points: Array, params: Array, count: int
) -> tuple[Array, Callable[[Array], Array], Callable[[Array], Array]]:
    """``count`` parameters evenly spread along the polyline ``points`` ``(k, 3)``
    sampled at ``params`` ``(k,)``, and the maps length -> parameter and
    parameter -> length."""
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    length = float(cum[-1])

    def at_length(x: Array) -> Array:
        return np.interp(x, cum, params)

    def length_at(t: Array) -> Array:
        return np.interp(t, params, cum)

    t = (
        at_length(np.linspace(0.0, length, count))
        if length > 0.0
        else np.linspace(params[0], params[-1], count)
    )
    t[0], t[-1] = params[0], params[-1]
    return t, at_length, length_at


def curve_values(curve: Geom_BSplineCurve, t: Array) -> Array:
    out = np.empty((len(t), 3))
    for i, ti in enumerate(t.tolist()):
        p = curve.Value(ti)
        out[i] = (p.X(), p.Y(), p.Z())
    return out


def fit_curve(
    fn, a: float, b: float, tol: float, what: str, nodes: Array | None = None
) -> tuple[Geom_BSplineCurve, float]:
    """A B-spline through ``fn(theta)`` ``(k, 3)`` with theta as its parameter
    on [a, b] (so that ruled faces pair equal theta), interpolating it at
    nodes spread evenly along its length and exactly at ``nodes`` (where other
    curves end on it); an interval whose worst point of
    :data:`PROBES` (fractions of its length) deviates
    by more than ``tol`` (length) is split there until none does. Each theta
    is evaluated once (:class:`CachedSamples`).

    Returns:
        ``(curve, deviation reached)``.

    Raises:
        ExportError: the tolerance needs more than 4000 nodes.
    """
    fn = CachedSamples(fn)
    dense = a + (b - a) * DENSE
    dense[-1] = b
    pts = fn(dense)
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    length = float(cum[-1])

    def at_length(x: Array) -> Array:
        return np.interp(x, cum, dense)

    def length_at(t: Array) -> Array:
        return np.interp(t, dense, cum)

    t = at_length(np.linspace(0.0, length, 17)) if length > 0.0 else np.linspace(a, b, 17)
    t[0], t[-1] = a, b
    if nodes is not None and len(nodes):
        keep = np.unique(np.clip(nodes, a, b))
        gap = np.min(np.abs(length_at(t)[:, None] - length_at(keep)[None, :]), axis=1)
        t = np.unique(np.concatenate([t[gap > 1e-3 * length / 16.0], keep]))
    while True:
        curve = interpolate(fn(t), t, what)
        probe = probe_points(t, at_length, length_at).ravel()
        err = np.linalg.norm(curve_values(curve, probe) - fn(probe), axis=1)
        new, worst = refine(probe.reshape(-1, len(PROBES)), err.reshape(-1, len(PROBES)), tol)
        if not len(new):
            return curve, worst
        if len(t) + len(new) > 4000:
            raise ExportError(
                f"{what} misses the tolerance {tol:.3g} (by {worst:.3g}) with {len(t)} points"
            )
        t = np.sort(np.concatenate([t, new]))


class CachedSamples:
    """``fn(theta)`` ``(k, 3)`` that evaluates each theta once: the points it
    gave are kept by parameter (a fit reads its nodes again, which were
    probes before, and the probes of the intervals it did not split)."""

    def __init__(self, fn: Callable[[Array], Array]) -> None:
        self.fn = fn
        self.t = np.empty(0)  # sorted
        self.points = np.empty((0, 3))

    def __call__(self, t: Array) -> Array:
        t = np.asarray(t, dtype=float)
        out = np.empty((len(t), 3))
        known = np.zeros(len(t), dtype=bool)
        if len(self.t):
            i = np.minimum(np.searchsorted(self.t, t), len(self.t) - 1)
            known = self.t[i] == t
            out[known] = self.points[i[known]]
        if not known.all():
            fresh = t[~known]
            out[~known] = got = self.fn(fresh)
            order = np.argsort(np.concatenate([self.t, fresh]), kind="stable")
            self.t = np.concatenate([self.t, fresh])[order]
            self.points = np.concatenate([self.points, got])[order]
        return out
