"""Convex hulls in the plane, numpy only (no scipy.spatial on the solve path).

Up to a few hundred points, Andrew's monotone chain: sort the points, then
one pass for the lower and one for the upper chain, O(n log n), in plain
Python floats. Beyond that (the footprint of a body's thousands of samples,
a thousand of them on its hull), QuickHull with every edge of a level
refined at once in numpy: each edge's farthest point outside it becomes a
corner, the points outside the two new edges stay, the rest drop out. Used
for the support polygon of a resting form and the footprint of its shadow
on the ground.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.numeric import Array, roll_rows, sorted_unique

__all__ = ["convex_hull_2d", "edge_distances"]


def _chain(xs: list[float], ys: list[float], order: list[int], tol: float) -> list[int]:
    """One monotone chain (indices), turning left at every kept corner (plain
    floats: far faster than numpy scalars in this loop)."""
    out: list[int] = []
    for i in order:
        cx, cy = xs[i], ys[i]
        while len(out) >= 2:
            a, b = out[-2], out[-1]
            ax, ay = xs[a], ys[a]
            cross = (xs[b] - ax) * (cy - ay) - (ys[b] - ay) * (cx - ax)
            # b's distance from the line a-c, positive when the chain turns left at b
            if cross > tol * math.hypot(cx - ax, cy - ay):
                break
            out.pop()
        out.append(i)
    return out


def convex_hull_2d(points: ArrayLike, tol: float = 0.0) -> NDArray[np.int64]:
    """The corners of the convex hull of ``points`` ``(n, 2)``.

    Args:
        points: the points (any length unit).
        tol: points within this distance (length) of a hull edge's line are
            left out as corners; 0 keeps every strict corner.

    Returns:
        ``(m,)`` indices into ``points`` of the hull's corners in
        counter-clockwise order, without repeating the first; one index for
        coincident points, two for collinear ones (the ends), and an empty
        array for no points.

    With a tolerance, the monotone chain decides each turn within it, which
    can drop a true corner (points a rounding error apart on a nearly
    vertical edge: the chain's first and second point lie on one line with
    the third, within the tolerance); the hull without tolerance checks it
    and, where it left a corner out, the corners of that hull more than
    ``tol`` from their neighbours' line are taken instead (:func:`_beyond`).
    """
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(p) <= 2:  # no point, one, or two (what the chain makes of them)
        return _pair(p)
    if tol <= 0.0:
        return _strict_corners(p)
    if len(p) <= _SMALL:
        small = _small(p, tol)
        if small is not None:
            return small
    hull = _chained(p, tol)
    if len(p) <= 64:  # a few points (contacts): all of them against the hull
        if _covers(p[hull], p, tol):
            return hull
        exact = _strict_corners(p)
    else:
        exact = _strict_corners(p)
        if _covers(p[hull], p[exact], tol):
            return hull
    return _beyond(p, exact, tol) if len(exact) >= 3 else hull


def _pair(p: Array) -> NDArray[np.int64]:
    """:func:`convex_hull_2d` of at most two points ``p`` (as the chain has it,
    any tolerance): none, the one, one of two equal points (the first), or
    both, the lower x (then y) first."""
    if len(p) < 2:
        return np.arange(len(p), dtype=np.int64)
    (ax, ay), (bx, by) = p.tolist()
    if ax == bx and ay == by:
        return np.zeros(1, dtype=np.int64)
    return np.array([0, 1] if (ax, ay) < (bx, by) else [1, 0], dtype=np.int64)


#: Up to this many points (a body's contacts, as toppling meets them) with a
#: tolerance, the chain and its check in plain floats (:func:`_small`).
_SMALL = 16


def _small(p: Array, tol: float) -> NDArray[np.int64] | None:
    """:func:`convex_hull_2d` of a few points ``p`` with a tolerance, in plain
    floats, when the chain's hull of three or more corners holds every point
    (the same arithmetic as :func:`_chained` and :func:`_covers`); None
    otherwise (the numpy path decides)."""
    xs, ys = p[:, 0].tolist(), p[:, 1].tolist()
    order = sorted(range(len(xs)), key=lambda i: (xs[i], ys[i]))  # np.lexsort's
    hull = _chain(xs, ys, order, tol)[:-1] + _chain(xs, ys, order[::-1], tol)[:-1]
    if len(hull) < 3:
        return None
    hx, hy = [xs[i] for i in hull], [ys[i] for i in hull]
    m = len(hull)
    dx = [hx[(i + 1) % m] - hx[i] for i in range(m)]
    dy = [hy[(i + 1) % m] - hy[i] for i in range(m)]
    length = np.maximum(np.hypot(dx, dy), 1e-300).tolist()
    floor = -2.0 * tol
    for cx, cy in zip(xs, ys, strict=True):
        inside = min((dx[i] * (cy - hy[i]) - dy[i] * (cx - hx[i])) / length[i] for i in range(m))
        if not inside >= floor:
            return None
    return np.asarray(hull, dtype=np.int64)


def _strict_corners(p: Array) -> NDArray[np.int64]:
    """:func:`convex_hull_2d` with no tolerance: every strict corner."""
    if len(p) > _CHAIN_MAX:
        hull = _quickhull(p)
        if hull is not None:
            return hull
    return _chained(p, 0.0)


def _chained(p: Array, tol: float) -> NDArray[np.int64]:
    """The monotone chain's hull of ``p`` with the tolerance ``tol`` in its turns."""
    keep = _outside_octagon(p)
    if len(keep) < len(p):
        return keep[_chained(p[keep], tol)]
    order = np.lexsort((p[:, 1], p[:, 0]))
    first, last = p[order[0]], p[order[-1]]
    if np.array_equal(first, last):
        return order[:1].astype(np.int64)
    xs, ys, idx = p[:, 0].tolist(), p[:, 1].tolist(), order.tolist()
    lower = _chain(xs, ys, idx, tol)
    upper = _chain(xs, ys, idx[::-1], tol)
    hull = lower[:-1] + upper[:-1]
    if len(hull) < 2:  # every point on one line within tol: its two ends
        hull = [int(order[0]), int(order[-1])]
    return np.asarray(hull, dtype=np.int64)


def _covers(poly: Array, corners: Array, tol: float) -> bool:
    """Whether every one of ``corners`` ``(k, 2)`` lies within twice ``tol`` of
    the polygon (or segment, or point) ``poly`` ``(m, 2)``, counter-clockwise."""
    if len(poly) >= 3:
        d = roll_rows(poly, -1) - poly  # (m, 2) edges
        length = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)
        rel = corners[:, None, :] - poly[None, :, :]  # (k, m, 2)
        inside = (d[:, 0] * rel[..., 1] - d[:, 1] * rel[..., 0]) / length
        return bool(np.all(inside.min(axis=1) >= -2.0 * tol))
    a, b = poly[0], poly[-1]
    d = b - a
    t = np.clip((corners - a) @ d / max(float(d @ d), 1e-300), 0.0, 1.0)
    return float(np.max(np.hypot(*(a + t[:, None] * d - corners).T))) <= 2.0 * tol


def _beyond(p: Array, hull: NDArray[np.int64], tol: float) -> NDArray[np.int64]:
    """The corners of ``hull`` (strict corners of ``p``, counter-clockwise)
    more than ``tol`` from the line through their neighbours: the hull of
    the points less what lies within ``tol`` of its edges; the two farthest
    corners when all lie within ``tol`` of one line. Each pass drops every
    other corner of each run of corners that fail (never two neighbours at
    once: each one's neighbours change as the other goes), until none fails."""
    if len(hull) <= 32:  # a few corners (contacts): plain floats, far faster
        kept = _beyond_small(p[hull, 0].tolist(), p[hull, 1].tolist(), tol)
        if len(kept) >= 3:
            return hull[kept]
    idx = hull.copy()
    while len(idx) >= 3:
        q = p[idx]
        a, c = roll_rows(q, 1), roll_rows(q, -1)
        ab, ac = q - a, c - a
        cross = ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0]
        fail = cross <= tol * np.hypot(ac[:, 0], ac[:, 1])
        if not fail.any():
            return idx
        pos = np.arange(len(idx))
        start = np.maximum.accumulate(np.where(fail & ~roll_rows(fail, 1), pos, 0))
        drop = fail & ((pos - start) % 2 == 0)
        if drop[0] and drop[-1]:  # a run across the end: not both
            drop[-1] = False
        if drop.all():
            drop[1:] = False
        idx = idx[~drop]
    q = p[hull]
    d2 = ((q[:, None, :] - q[None, :, :]) ** 2).sum(axis=-1)
    i, j = np.unravel_index(int(np.argmax(d2)), d2.shape)
    ends = sorted((int(hull[i]), int(hull[j])), key=lambda k: (p[k, 0], p[k, 1]))
    return np.asarray(ends, dtype=np.int64)


def _beyond_small(xs: list[float], ys: list[float], tol: float) -> list[int]:
    """:func:`_beyond` on a few corners given as floats: the positions kept
    (fewer than three: all lie within ``tol`` of one line)."""
    idx = list(range(len(xs)))
    while len(idx) >= 3:
        n = len(idx)
        fail = []
        for i in range(n):
            a, b, c = idx[i - 1], idx[i], idx[(i + 1) % n]
            ax, ay = xs[a], ys[a]
            cx, cy = xs[c] - ax, ys[c] - ay
            cross = (xs[b] - ax) * cy - (ys[b] - ay) * cx
            fail.append(cross <= tol * math.hypot(cx, cy))
        if not any(fail):
            return idx
        drop = [False] * n
        run = 0
        for i in range(n):  # every other corner of each run of failures
            run = run + 1 if fail[i] and i > 0 and fail[i - 1] else 0
            drop[i] = fail[i] and run % 2 == 0
        if drop[0] and drop[-1]:
            drop[-1] = False
        if all(drop):
            drop[1:] = [False] * (n - 1)
        idx = [k for k, d in zip(idx, drop, strict=True) if not d]
    return idx


#: Above this many points (and with no tolerance), QuickHull in numpy instead
#: of the chain in Python.
_CHAIN_MAX = 256


def _quickhull(p: Array) -> NDArray[np.int64] | None:
    """:func:`convex_hull_2d` of many points with no tolerance, in numpy: the
    strict corners counter-clockwise from the lowest-then-leftmost point; None
    when the seed polygon is degenerate (the chain then decides).

    Seeded with the extreme points in 8 directions and their centre; the
    points outside the seeds' polygon sorted once by their angle about that
    centre: the points outside an edge are then a run of that order, and so
    are those outside the two edges its farthest point splits it into (they
    lie in the angles between its ends), so each level of QuickHull refines
    every edge at once, on runs, without sorting again."""
    x, y = p[:, 0], p[:, 1]
    s, t = x + y, x - y
    seed = sorted_unique(
        np.array([f(v) for v in (x, y, s, t) for f in (np.argmin, np.argmax)], dtype=np.int64)
    )
    cx, cy = float(x.take(seed).mean()), float(y.take(seed).mean())
    ang = np.arctan2(y - cy, x - cx)
    seed = seed[np.argsort(ang.take(seed))]
    ang -= ang[seed[0]]
    # ang %= 2 pi for ang in [-2 pi, 2 pi], exactly as fmod's (and cheaper)
    np.add(ang, 2.0 * math.pi, out=ang, where=ang < 0.0)
    np.subtract(ang, 2.0 * math.pi, out=ang, where=ang >= 2.0 * math.pi)
    ang[seed[0]] = 0.0
    sx, sy = x.take(seed), y.take(seed)
    ex, ey = roll_rows(sx, -1) - sx, roll_rows(sy, -1) - sy
    if len(seed) < 3 or np.any(ex * (cy - sy) - ey * (cx - sx) <= 0.0):
        return None  # the centre is not strictly inside the seeds' polygon
    k = ang.take(seed).searchsorted(ang, side="right") - 1
    # to the right of its edge (going counter-clockwise): strictly outside
    d = ey.take(k) * (x - sx.take(k)) - ex.take(k) * (y - sy.take(k))
    idx = np.flatnonzero(d > 0.0)
    idx = idx[np.argsort(ang.take(idx))]
    a_end, b_end = seed.take(k.take(idx)), roll_rows(seed, -1).take(k.take(idx))
    d = d.take(idx)
    corners = [seed]
    px, py = x.take(idx), y.take(idx)
    while len(idx):
        # per run (edge): its farthest point (the first of a tie) is a corner
        new = np.empty(len(idx), dtype=bool)
        new[0] = True
        np.not_equal(a_end[1:], a_end[:-1], out=new[1:])
        starts = np.flatnonzero(new)
        run = np.cumsum(new)
        run -= 1
        far = np.flatnonzero(d == np.maximum.reduceat(d, starts).take(run))
        at = far.take(far.searchsorted(starts))
        c = idx.take(at)
        corners.append(c)
        before = np.arange(len(idx)) < at.take(run)
        cc = c.take(run)
        a_end = np.where(before, a_end, cc)
        b_end = np.where(before, cc, b_end)
        ax, ay = x.take(a_end), y.take(a_end)
        d = (y.take(b_end) - ay) * (px - ax) - (x.take(b_end) - ax) * (py - ay)
        out = np.flatnonzero(d > 0.0)
        idx, a_end, b_end, d = idx.take(out), a_end.take(out), b_end.take(out), d.take(out)
        px, py = px.take(out), py.take(out)
    hull = np.concatenate(corners)
    hull = hull[np.argsort(ang.take(hull))]
    while len(hull) >= 3:  # a seed can lie on an edge of the hull: no corner
        ax, ay = x.take(roll_rows(hull, 1)), y.take(roll_rows(hull, 1))
        qx, qy = x.take(roll_rows(hull, -1)), y.take(roll_rows(hull, -1))
        turn = (x.take(hull) - ax) * (qy - ay) - (y.take(hull) - ay) * (qx - ax) > 0.0
        if turn.all():
            break
        # one of neighbours that both fail at a time (two points a rounding
        # error apart: one of them stays, as in the chain)
        hull = hull[turn | roll_rows(~turn, 1)]
    # counter-clockwise from the lowest x, then lowest y, as the chain
    hx, hy = x.take(hull), y.take(hull)
    low = np.flatnonzero(hx == hx.min())
    return roll_rows(hull, -int(low[hy.take(low).argmin()])).astype(np.int64)


def _outside_octagon(p: Array) -> NDArray[np.int64]:
    """Indices of the points not strictly inside the polygon of the extreme
    points in eight directions (Akl and Toussaint): only they can be corners."""
    if len(p) < 64:
        return np.arange(len(p))
    proj = np.column_stack([p[:, 0], p[:, 0] + p[:, 1], p[:, 1], p[:, 1] - p[:, 0]])
    ext = sorted_unique(np.concatenate([proj.argmin(axis=0), proj.argmax(axis=0)]))
    sub = convex_hull_2d(p[ext])
    if len(sub) < 3:
        return np.arange(len(p))
    poly = p[ext][sub]
    d = roll_rows(poly, -1) - poly
    cross = d[None, :, 0] * (p[:, None, 1] - poly[None, :, 1]) - d[None, :, 1] * (
        p[:, None, 0] - poly[None, :, 0]
    )
    return np.flatnonzero(~np.all(cross > 0.0, axis=1))


def edge_distances(point: ArrayLike, polygon: ArrayLike) -> Array:
    """Signed distances ``(m,)`` from ``point`` ``(2,)`` to the lines of the
    edges of a counter-clockwise convex polygon ``(m, 2)`` (edge i from corner
    i to corner i + 1): positive on the polygon's inner side (length)."""
    p = np.asarray(polygon, dtype=float).reshape(-1, 2)
    x = np.asarray(point, dtype=float)
    d = roll_rows(p, -1) - p
    length = np.hypot(d[:, 0], d[:, 1])
    cross = d[:, 0] * (x[1] - p[:, 1]) - d[:, 1] * (x[0] - p[:, 0])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(length > 0.0, cross / np.where(length > 0.0, length, 1.0), 0.0)
