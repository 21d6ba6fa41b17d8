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
all directions' zooms together (:meth:`FoldedBody.lowest_many`): for the default
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
from numpy.typing import NDArray

from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.body_samples import Rows
from onefold_cad.geometry.ground import CONTACT_TOLERANCE, Samples
from onefold_cad.geometry.numeric import Array

__all__ = ["bound_directions", "exact_bounds", "exact_lows"]

Low = tuple[int, float, Array]


def _window(
    rows: Rows, row: NDArray[np.intp], h: Array, d: NDArray[np.intp]
) -> tuple[Array, Array]:
    """Heights ``h`` ``(M, D)`` and parameters at the five rows about each
    candidate (``row``, direction ``d``; ``(c,)``): ``(c, 5)`` each, NaN past
    the ends of the candidate's piece."""
    off = np.arange(-2, 3)
    rr = np.minimum(np.maximum(row[:, None] + off, 0), len(rows.t) - 1)
    ok = (rows.piece[rr] == rows.piece[row][:, None]) & (row[:, None] + off == rr)
    return np.where(ok, h[rr, d[:, None]], np.nan), np.where(ok, rows.t[rr], np.nan)


def _dip(hw: Array, tw: Array) -> Array:
    """How far ``(c,)`` the heights may dip below their samples in the bracket
    about the middle of each window ``(c, 5)`` (eight times the parabola's
    dip, 2 c L^2: see the module docstring); inf where unknown."""
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = np.diff(hw, axis=1) / np.diff(tw, axis=1)  # (c, 4)
        curv = np.abs(np.diff(slope, axis=1)) / (tw[:, 2:] - tw[:, :-2])  # at -1, 0, +1
    near = np.where(np.isnan(curv), -1.0, curv).max(axis=1)  # absent: no bound
    near = np.where(np.all(np.isnan(curv), axis=1), 0.0, near)
    gap = np.fmax.reduce(np.abs(np.diff(tw[:, 1:4], axis=1)), axis=1)  # NaN: none
    gap = np.where(np.isnan(gap), 0.0, gap)
    bad = np.any(np.isinf(hw[:, 1:4]) & ~np.isnan(hw[:, 1:4]), axis=1) | np.isinf(near)
    return np.where(bad, np.inf, 2.0 * near * gap**2)


def _bounded_minima(
    body: FoldedBody, hs: Array, dirs: Array
) -> tuple[NDArray[np.int64], NDArray[np.int64], Array]:
    """Every piece's sampled local minima along each of ``dirs`` ``(D, 3)``
    (``hs`` ``(D, N)``: the body's samples' heights): their rows
    (:attr:`FoldedBody.rows`) and directions, and the lower bounds of their
    brackets (see the module docstring); ``(c,)`` each."""
    rows = body.rows
    h = np.full((len(dirs), len(rows.t)), np.inf)  # the lowest corner's height
    full = rows.count > 0
    h[:, full] = np.minimum.reduceat(hs, rows.start[full], axis=1)
    h = h.T  # (M, D)
    # local minima (a plateau counts once, as lowest_points has it)
    left = np.ones_like(h, dtype=bool)
    right = np.ones_like(h, dtype=bool)
    left[1:] = rows.first[1:, None] | (h[1:] < h[:-1])
    right[:-1] = rows.last[:-1, None] | (h[:-1] <= h[1:])
    row, d = np.nonzero(left & right & np.isfinite(h))
    slack = 1e-9 * body.size
    hw, tw = _window(rows, row, h, d)
    low = h[row, d] - _dip(hw, tw) - slack
    # where a corner comes or goes between samples (the cut at y = 0 sweeping
    # a section's corners near the crease, faster than the samples) the
    # samples of the cut section say nothing of the bracket; the rectangle
    # before the cut holds it, and its corners move smoothly
    moved = rows.comes[row] | np.append(rows.comes[1:], False)[row]
    if moved.any():
        m = moved.nonzero()[0]
        boxes = np.concatenate(
            [
                np.full((len(c), 4, 3), np.nan) if b is None else b
                for c, b in zip(body.sections, body.boxes, strict=True)
            ]
        )
        off = np.arange(-2, 3)
        rr = np.minimum(np.maximum(row[m][:, None] + off, 0), len(rows.t) - 1)
        ok = (rows.piece[rr] == rows.piece[row[m]][:, None]) & (row[m][:, None] + off == rr)
        bh = np.einsum("cwvj,cj->cwv", boxes[rr], dirs[d[m]]).min(axis=2)
        bh = np.where(ok, bh, np.nan)
        mid = bh[:, 1:4]
        lowest = np.where(np.isnan(mid), np.inf, mid).min(axis=1)
        box = lowest - _dip(bh, np.where(ok, rows.t[rr], np.nan)) - slack
        low[m] = np.where(np.isfinite(box), box, -np.inf)
    low[~np.isfinite(low)] = -np.inf
    # and no point of a piece lies further from the apex than its radius
    radius = np.array([p.radius for p in body.pieces])[rows.piece[row]]
    return row, d, np.maximum(low, -radius * np.linalg.norm(dirs, axis=1)[d])


def exact_lows(
    body: FoldedBody, samples: Samples, dirs: Array, above: Array | None = None
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
    hs = np.ascontiguousarray((samples.points @ dirs.T).T)  # (D, N): rows reduce fast
    margin = CONTACT_TOLERANCE * body.size
    known = hs.min(axis=1)  # the lowest sample: the lowest point lies no higher
    zoom_below = np.maximum(ceiling, known) + margin
    fixed = (samples.owner < 0).nonzero()[0]
    out: list[list[Low]] = [
        [(-1, 0.0, samples.points[i]) for i in fixed[hs[d, fixed] <= zoom_below[d]]]
        for d in range(nd)
    ]
    asks: list[tuple[int, float, float, Array]] = []
    whose: list[int] = []
    if body.pieces:
        nbody = len(body.samples[0])  # the body's own samples (the first rows)
        row, d, low = _bounded_minima(body, hs[:, len(body.fixed) : nbody], dirs)
        zoom = low <= zoom_below[d]
        rows = body.rows
        for r, dd in zip(row[zoom].tolist(), d[zoom].tolist(), strict=True):
            k = int(rows.piece[r])
            lo, hi = body.pieces[k].bracket(float(rows.t[r]), float(rows.t[r]))
            asks.append((k, lo, hi, dirs[dd]))
            whose.append(dd)
    # only a direction's lowest point matters, and what lies below its ceiling
    found = body.lowest_many(asks, np.array(whose, dtype=np.int64), ceiling + margin, known, margin)
    for dd, (k, _, _, _), (t, p) in zip(whose, asks, found, strict=True):
        out[dd].append((k, t, p))
    for dd in range(nd):
        g = dirs[dd]
        out[dd].sort(key=lambda item: float(item[2] @ g))  # noqa: B023 (sorted at once)
    return out


def bound_directions(rot: Array) -> Array:
    """The directions ``(5, 3)`` of :func:`exact_bounds`' searches (fold frame)
    for a resting frame's rotation ``rot`` ``(3, 3)``: its lowest and highest
    x and y, and its highest z."""
    return np.array([rot[0], -rot[0], rot[1], -rot[1], -rot[2]])


def exact_bounds(
    body: FoldedBody,
    samples: Samples,
    rot: Array,
    translation: Array,
    lowest: Array,
    lows: list[list[Low]] | None = None,
) -> Array:
    """The placed body's exact lowest and highest x, y, z ``(2, 3)`` (resting
    frame ``p' = rot p + translation``): the lowest z is that of ``lowest``
    (its lowest point along the ground's normal, the resting frame's z
    axis), the five other searches (:func:`bound_directions`) run together
    (``lows``: their :func:`exact_lows`, found beforehand)."""
    if lows is None:
        lows = exact_lows(body, samples, bound_directions(rot))
    out = np.zeros((2, 3))
    for axis in range(3):
        d = rot[axis]  # the resting frame's axis in the fold frame
        low = lowest if axis == 2 else lows[2 * axis][0][2]
        out[0, axis] = float(low @ d) + translation[axis]
        out[1, axis] = float(lows[2 * axis + 1 if axis < 2 else 4][0][2] @ d) + translation[axis]
    return out
