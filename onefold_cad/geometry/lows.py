"""A body's exact lowest points along many directions, zooming only where the
samples leave it open.

Along a piece, the lowest corner's height h(t) is continuous and piecewise
smooth. Between two samples dt apart a smooth stretch dips below their chord
by at most h'' dt^2 / 8; the samples' second divided difference c = h'' / 2
(of the parabola through three neighbours, however uneven their spacing)
measures h''. So no point of a piece's bracket about a sampled local
minimum (its neighbours on the grid, as :func:`~.ground.lowest_points`
zooms it) lies lower than that minimum less 2 c L^2, L the longer interval
beside it and c the largest of the three samples' (eight times the dip,
whose 1/8 is c L^2 / 4): the lower bound of the bracket.

Every sample is a point of the body, so the lowest sample (or fixed point)
bounds the lowest point from above. :func:`exact_lows` zooms only the brackets
whose lower bound lies under that, or under a height the caller asks about,
all directions' zooms together (:meth:`Body.lowest_many`): for the default
template's solid, a few brackets per direction out of fifteen.

The sampling's premise is the one :func:`~.ground.lowest_points` makes: the
grid resolves each piece's curvature (an edge passing close to H is sampled
every degree of its flat angle); where it does not (a large second
difference, a corner that comes or goes between the samples: the cut at the
fold's plane of symmetry sweeps a thick section's corners within a fraction
of a degree of the crease) the bracket is zoomed. Lengths in the design unit.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.body import Body
from onefold_cad.geometry.ground import CONTACT_TOLERANCE, Samples
from onefold_cad.geometry.numeric import Array

__all__ = ["exact_lows"]

Low = tuple[int, float, Array]


def _bounded_minima(body: Body, dirs: Array) -> tuple[Array, Array, Array]:
    """Every piece's sampled local minima along each of ``dirs`` ``(D, 3)``:
    their rows in :attr:`Body.stacked` and their directions, and the lower
    bounds of their brackets (see the module docstring); ``(c,)`` each."""
    corners, piece, index = body.stacked
    h = corners @ dirs.T  # (M, V, D)
    h[np.isnan(h)] = np.inf
    h = h.min(axis=1)  # (M, D): the lowest corner's height
    t = body.stacked_params
    first = index == 0
    last = np.append(first[1:], True)
    inner = ~(first | last)
    # the second divided difference at each inner sample (h'' / 2 of the
    # parabola through it and its neighbours: the curvature, however uneven
    # the spacing), 0 at a piece's ends
    curv = np.zeros_like(h)
    if inner.any():
        i = np.flatnonzero(inner)
        with np.errstate(invalid="ignore", divide="ignore"):
            left = (h[i] - h[i - 1]) / (t[i] - t[i - 1])[:, None]
            right = (h[i + 1] - h[i]) / (t[i + 1] - t[i])[:, None]
            curv[i] = np.abs(right - left) / (t[i + 1] - t[i - 1])[:, None]
    # beside an empty section (a mitre wall past its block) or between
    # coincident samples the piece's largest curvature
    bad = ~np.isfinite(curv)
    if bad.any():
        curv[bad] = 0.0
        starts = np.flatnonzero(first)
        worst = np.maximum.reduceat(curv, starts, axis=0)[np.cumsum(first) - 1]
        curv = np.where(bad, worst, curv)
    near = curv.copy()
    near[1:] = np.where(first[1:, None], near[1:], np.maximum(near[1:], curv[:-1]))
    near[:-1] = np.where(last[:-1, None], near[:-1], np.maximum(near[:-1], curv[1:]))
    # the longer of the two intervals beside each sample
    gap = np.zeros(len(t))
    step = np.diff(t)
    gap[:-1] = np.where(last[:-1], 0.0, step)
    gap[1:] = np.maximum(gap[1:], np.where(first[1:], 0.0, step))
    # local minima (a plateau counts once, as lowest_points has it)
    left = np.ones_like(h, dtype=bool)
    right = np.ones_like(h, dtype=bool)
    left[1:] = first[1:, None] | (h[1:] < h[:-1])
    right[:-1] = last[:-1, None] | (h[:-1] <= h[1:])
    row, d = np.nonzero(left & right & np.isfinite(h))
    # the dip of a parabola of that curvature over the interval is c L^2 / 4:
    # eight times it
    low = h[row, d] - 2.0 * near[row, d] * gap[row] ** 2 - 1e-9 * body.size
    # where a corner comes or goes between samples (the cut at y = 0 sweeping
    # a section's corners near the crease, faster than the samples), the
    # samples say nothing of the bracket: zoom it
    gone = np.isnan(corners[..., 0])
    comes = np.zeros(len(first), dtype=bool)
    comes[1:] = np.any(gone[1:] != gone[:-1], axis=1) & ~first[1:]
    moved = comes[row] | np.append(comes[1:], False)[row]
    low = np.where(np.isfinite(low) & ~moved, low, -np.inf)
    # and no point of a piece lies further from the apex than its radius
    radius = np.array([p.radius for p in body.pieces])[piece[row]]
    return row, d, np.maximum(low, -radius * np.linalg.norm(dirs, axis=1)[d])


def exact_lows(
    body: Body, samples: Samples, dirs: Array, above: Array | None = None
) -> list[list[Low]]:
    """Per direction of ``dirs`` ``(D, 3)``: the exact lowest points (piece,
    parameter, point; piece -1 a fixed point) of every fixed point and zoomed
    bracket that may lie within the contact tolerance of the lowest sample or
    below, or at or below ``above`` ``(D,)`` (heights along the direction,
    default -inf), lowest first. The first is the body's lowest point along
    it; every exact point within the contact tolerance of it is among them."""
    dirs = np.atleast_2d(np.asarray(dirs, dtype=float))
    nd = len(dirs)
    ceiling = np.full(nd, -np.inf) if above is None else np.asarray(above, dtype=float)
    hs = samples.points @ dirs.T  # (N, D)
    margin = CONTACT_TOLERANCE * body.size
    known = hs.min(axis=0)  # the lowest sample: the lowest point lies no higher
    zoom_below = np.maximum(ceiling, known) + margin
    fixed = np.flatnonzero(samples.owner < 0)
    out: list[list[Low]] = [
        [(-1, 0.0, samples.points[i]) for i in fixed[hs[fixed, d] <= zoom_below[d]]]
        for d in range(nd)
    ]
    asks: list[tuple[int, float, float, Array]] = []
    whose: list[int] = []
    if body.pieces:
        row, d, low = _bounded_minima(body, dirs)
        zoom = low <= zoom_below[d]
        owner, params = body.stacked[1], body.stacked_params
        for r, dd in zip(row[zoom].tolist(), d[zoom].tolist(), strict=True):
            k = int(owner[r])
            lo, hi = body.pieces[k].bracket(float(params[r]), float(params[r]))
            asks.append((k, lo, hi, dirs[dd]))
            whose.append(dd)
    # only a direction's lowest point matters, and what lies below its ceiling
    found = body.lowest_many(asks, np.array(whose, dtype=np.int64), ceiling + margin, known, margin)
    for dd, (k, _, _, _), (t, p) in zip(whose, asks, found, strict=True):
        out[dd].append((k, t, p))
    for dd in range(nd):
        out[dd].sort(key=lambda item, g=dirs[dd]: float(item[2] @ g))
    return out
