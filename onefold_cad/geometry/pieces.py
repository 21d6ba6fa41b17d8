"""One-parameter families of points on which a body's extremes lie, and the
search for the lowest of them.

For a fixed ruling a thick sheet's section is a rectangle in (r, s), cut by
one line, on which the point depends affinely: a linear function is extreme
at its corners (:func:`clipped_rectangle`). A :class:`Piece` is such a
family of section corners along a parameter; :func:`zoom_min` finds its
lowest point in a direction. Lengths in the design unit.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.numeric import Array

__all__ = ["ZOOM_GRID", "Family", "Piece", "clipped_rectangle", "end_minimum", "zoom_min"]

#: Points of each zoom's grid over the bracket.
ZOOM_GRID = 33


class Family(Protocol):
    """Pieces evaluated together (:mod:`onefold_cad.geometry.body_families`):
    ``points(members (k,), t (k,))`` gives the corners ``(k, V, 3)`` of piece
    ``members[i]`` of the family at parameter ``t[i]``."""

    def points(self, members: NDArray[np.int64], t: Array) -> Array: ...


@dataclass(frozen=True, eq=False)
class Piece:
    """A one-parameter family of points on which a body's extremes lie.

    Attributes:
        name: what it is (for messages), e.g. 'edge 3'.
        grid: ``(n,)`` increasing sample parameters, the first and last being
            the parameter range's ends.
        points: ``(k,)`` parameters -> ``(k, V, 3)`` corners of the section
            there (NaN for corners that are absent).
        step: the largest length along the piece between neighbouring
            samples, on the flat sheet for the sheet's edges (the fold keeps
            lengths: no point of the folded edge lies further than half of it
            from a sample); 0 to take the samples' 3D distances.
        family: the family that evaluates it together with others (None:
            alone).
        member: its index in the family.
        radius: no point of the piece lies further than this from the apex
            (length; inf: no bound known).
    """

    name: str
    grid: Array
    points: Callable[[Array], Array]
    step: float = 0.0
    family: Family | None = None
    member: int = 0
    radius: float = math.inf

    def heights(self, t: Array, g: Array) -> Array:
        """The lowest corner's height along ``g`` ``(3,)`` at each parameter
        ``(k,)``; +inf where the section is empty."""
        h = self.points(np.asarray(t, dtype=float)) @ g
        return np.where(np.isnan(h), np.inf, h).min(axis=1)

    @property
    def t0(self) -> float:
        """The first parameter."""
        return float(self.grid[0])

    @property
    def t1(self) -> float:
        """The last parameter."""
        return float(self.grid[-1])

    def bracket(self, t_lo: float, t_hi: float) -> tuple[float, float]:
        """The grid's neighbours around [t_lo, t_hi] (one grid step beyond)."""
        g = self.grid
        i = int(np.searchsorted(g, t_lo, side="left"))
        j = int(np.searchsorted(g, t_hi, side="right")) - 1
        return float(g[max(i - 1, 0)]), float(g[min(j + 1, len(g) - 1)])

    def lowest(self, t: float, g: Array) -> Array:
        """The lowest corner ``(3,)`` along ``g`` at parameter ``t``."""
        pts = self.points(np.array([t]))[0]
        h = pts @ g
        return pts[int(np.argmin(np.where(np.isnan(h), np.inf, h)))]


def zoom_min(f: Callable[[Array], Array], lo: float, hi: float) -> tuple[float, float]:
    """The minimum ``(t, f(t))`` of a continuous ``f`` on [lo, hi].

    ``f`` maps ``(k,)`` parameters to ``(k,)`` values. A grid of 33 points is
    laid over the bracket, which shrinks to the best point's neighbours, until
    a parabola through the best point and its neighbours predicts the value
    at its vertex to 1e-3 of the variation there (f is locally quadratic: the
    vertex is the minimum to rounding), or the bracket is 1e-13 of the first
    one (a kink, or a minimum at an end of the bracket, which is a grid point).
    """
    span = hi - lo
    best_t, best_v = lo, math.inf
    at_end = 0
    for rounds in range(20):
        t = np.linspace(lo, hi, ZOOM_GRID)
        v = f(t)
        i = int(v.argmin())
        if v[i] < best_v:
            best_t, best_v = float(t[i]), float(v[i])
        if not math.isfinite(best_v):
            break
        if 0 < i < ZOOM_GRID - 1 and rounds >= 1:
            a, b, c = float(v[i - 1]), float(v[i]), float(v[i + 1])
            curv = a - 2.0 * b + c
            if curv > 0.0:
                tp = float(t[i]) + 0.5 * float(t[1] - t[0]) * (a - c) / curv
                predicted = b - (a - c) ** 2 / (8.0 * curv)
                vp = float(f(np.array([tp]))[0])
                if vp < best_v:
                    best_t, best_v = tp, vp
                if abs(vp - predicted) <= 1e-3 * (max(a, c) - b):
                    break
        at_end = at_end + 1 if i in (0, ZOOM_GRID - 1) else 0
        lo, hi = float(t[max(i - 1, 0)]), float(t[min(i + 1, ZOOM_GRID - 1)])
        if hi - lo <= 1e-13 * span or at_end >= 3:
            break
    return best_t, best_v


def end_minimum(
    grid: Array, corners: Array, lo: float, hi: float, g: Array
) -> tuple[float, Array] | None:
    """The lowest point along ``g`` of a piece's bracket [lo, hi] that starts
    or ends with the piece, when its samples (``grid`` ``(n,)``, ``corners``
    ``(n, V, 3)``) show it at that end: ``(t, point)``; else None (zoom).

    The bracket spans at most the first (last) two sample intervals, and the
    parabola through the first three samples rises from the end with a slope
    of more than twice its curvature times the first interval: with the
    piece's curvature as its samples resolve it (as every bracket search
    here assumes, to a factor of two), nothing of the bracket dips below the
    end; and the three sections have the same corners (near the crease the
    cut at y = 0 sweeps them faster than the samples). Exactly what a zoom
    finds there: the end itself."""
    n = len(grid)
    if n < 3:
        return None
    if lo == grid[0] and grid[1] <= hi <= grid[2]:
        idx = [0, 1, 2]
    elif hi == grid[-1] and grid[-3] <= lo <= grid[-2]:
        idx = [n - 1, n - 2, n - 3]
    else:
        return None
    pts = corners[idx]
    gone = np.isnan(pts[..., 0])
    if (gone != gone[0]).any():  # a corner comes or goes: features finer than the samples
        return None
    h = pts @ g
    h = np.where(np.isnan(h), np.inf, h).min(axis=1)
    if not np.isfinite(h).all():
        return None
    t = grid[idx]
    if t[1] == t[0] or t[2] == t[1]:
        return None
    # the parabola through the three: its slope at the end, into the piece
    s01 = (h[1] - h[0]) / (t[1] - t[0])
    c = ((h[2] - h[1]) / (t[2] - t[1]) - s01) / (t[2] - t[0])
    slope = (s01 - c * (t[1] - t[0])) * np.sign(t[1] - t[0])
    if not (slope > 4.0 * abs(c) * abs(t[1] - t[0]) and h[2] > h[0]):
        return None
    p = pts[0]
    hp = p @ g
    return float(t[0]), p[int(np.argmin(np.where(np.isnan(hp), np.inf, hp)))].copy()


def clipped_rectangle(
    r0: Array, r1: Array, s0: float, s1: float, cr: Array, cs: Array, tol: float
) -> Array:
    """Corners ``(k, 8, 2)`` of the rectangles [r0, r1] x [s0, s1] cut to
    ``cr r + cs s >= 0``: the four corners that satisfy it and the line's
    crossings with the four sides (NaN where absent)."""
    k = len(r0)
    r = np.empty((k, 8))
    s = np.empty((k, 8))
    ok = np.empty((k, 8), dtype=bool)
    r[:, 0], r[:, 1], r[:, 2], r[:, 3] = r0, r1, r1, r0  # the corners
    s[:, :2], s[:, 2:4] = s0, s1
    slack = tol * np.hypot(cr, cs)
    ok[:, :4] = cr[:, None] * r[:, :4] + cs[:, None] * s[:, :4] >= -slack[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        for j, sj in enumerate((s0, s1)):  # sides s = s0, s1: r = -cs s / cr
            r[:, 4 + j] = rj = -cs * sj / cr
            s[:, 4 + j] = sj
            ok[:, 4 + j] = (cr != 0.0) & (rj >= r0) & (rj <= r1)
        for j, rj in enumerate((r0, r1)):  # sides r = r0, r1: s = -cr r / cs
            s[:, 6 + j] = sr = -cr * rj / cs
            r[:, 6 + j] = rj
            ok[:, 6 + j] = (cs != 0.0) & (sr >= s0) & (sr <= s1)
    z = np.full((k, 8, 2), np.nan)
    np.copyto(z[..., 0], r, where=ok)  # z[ok] = (r, s)[ok], without the masks' copies
    np.copyto(z[..., 1], s, where=ok)
    return z
