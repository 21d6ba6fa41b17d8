"""Convex hulls in the plane, numpy only (no scipy.spatial on the solve path).

Andrew's monotone chain: sort the points, then one pass for the lower and one
for the upper chain, O(n log n). Used for the support polygon of a resting
form and the footprint of its shadow on the ground.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.numeric import Array, sorted_unique

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
    """
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(p) == 0:
        return np.zeros(0, dtype=np.int64)
    keep = _outside_octagon(p)
    if len(keep) < len(p):
        return keep[convex_hull_2d(p[keep], tol)]
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
    d = np.roll(poly, -1, axis=0) - poly
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
    d = np.roll(p, -1, axis=0) - p
    length = np.hypot(d[:, 0], d[:, 1])
    cross = d[:, 0] * (x[1] - p[:, 1]) - d[:, 1] * (x[0] - p[:, 0])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(length > 0.0, cross / np.where(length > 0.0, length, 1.0), 0.0)
