"""A body's exact lowest points along many directions, zooming only where the
samples leave it open.

Along a piece, the lowest corner's height h(t) is continuous: smooth where one
corner stays lowest, with kinks where another takes over, and those kinks
point up (a minimum of smooth functions), never down. Between two samples a
smooth stretch dips below their chord by about h'' dt^2 / 8, an eighth of the
samples' second difference; so no point of a piece's bracket about a sampled
local minimum (its neighbours on the grid, as :func:`~.ground.lowest_points`
zooms it) lies lower than that minimum less twice the largest deviation of a
sample there from its neighbours' chord (the second difference: eight times
the dip, a margin of 8), the lower bound of the bracket.

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
    # each sample's deviation from its neighbours' chord (0 at a piece's ends)
    dev = np.zeros_like(h)
    if inner.any():
        i = np.flatnonzero(inner)
        span = t[i + 1] - t[i - 1]
        with np.errstate(invalid="ignore", divide="ignore"):
            w = np.where(span > 0.0, (t[i + 1] - t[i]) / span, 0.5)[:, None]
            dev[i] = np.abs(h[i] - (w * h[i - 1] + (1.0 - w) * h[i + 1]))
    # beside an empty section (a mitre wall past its block) the piece ends on
    # a fixed point of the body, a sample itself: the piece's largest
    # deviation there
    bad = ~np.isfinite(dev)
    if bad.any():
        dev[bad] = 0.0
        starts = np.flatnonzero(first)
        worst = np.maximum.reduceat(dev, starts, axis=0)[np.cumsum(first) - 1]
        dev = np.where(bad, worst, dev)
    near = dev.copy()
    near[1:] = np.where(first[1:, None], near[1:], np.maximum(near[1:], dev[:-1]))
    near[:-1] = np.where(last[:-1, None], near[:-1], np.maximum(near[:-1], dev[1:]))
    # local minima (a plateau counts once, as lowest_points has it)
    left = np.ones_like(h, dtype=bool)
    right = np.ones_like(h, dtype=bool)
    left[1:] = first[1:, None] | (h[1:] < h[:-1])
    right[:-1] = last[:-1, None] | (h[:-1] <= h[1:])
    row, d = np.nonzero(left & right & np.isfinite(h))
    low = h[row, d] - 2.0 * near[row, d] - 1e-9 * body.size
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
