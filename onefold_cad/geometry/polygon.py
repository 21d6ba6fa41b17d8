"""Plane polygons: whether one is simple (no two edges touch or cross), and the
largest circle about a point inside one.

Numpy and plain Python floats; lengths in any unit, points ``(n, 2)``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.errors import InvalidSheetError
from onefold_cad.geometry.numeric import Array

__all__ = ["SWEEP_ANGLE", "TOUCH", "boundary_distance", "check_simple", "edges_meet"]


#: Sweep coordinates are turned by this angle (radians, no rational multiple
#: of pi) so that, in practice, no edge is vertical and no two vertices share
#: the sweep coordinate; the sweep's order only decides which edges are
#: compared, every comparison uses the original coordinates.
SWEEP_ANGLE = 0.6180339887498949
#: Two edges closer than this fraction of the polygon's scale (its largest
#: coordinate magnitude) touch.
TOUCH = 1e-12


def edges_meet(p: list[list[float]], i: int, k: int, scale: float) -> bool:
    """Whether edges i and k (vertex i to i + 1, k to k + 1) of the closed polygon
    ``p`` cross or touch: cross properly, or an endpoint of one lies within
    ``TOUCH * scale`` of the other (collinear overlaps included)."""
    n = len(p)
    (ax, ay), (bx, by) = p[i], p[(i + 1) % n]
    (cx, cy), (dx, dy) = p[k], p[(k + 1) % n]
    ex, ey, fx, fy = bx - ax, by - ay, dx - cx, dy - cy
    ee, ff = ex * ex + ey * ey, fx * fx + fy * fy
    if ee == 0.0 or ff == 0.0:
        return False  # a zero-length edge meets nothing (callers remove them)
    # cross products: |e| (resp. |f|) times the signed distance of a point from the line
    d1 = ex * (cy - ay) - ey * (cx - ax)
    d2 = ex * (dy - ay) - ey * (dx - ax)
    d3 = fx * (ay - cy) - fy * (ax - cx)
    d4 = fx * (by - cy) - fy * (bx - cx)
    tol_e, tol_f = TOUCH * scale * math.sqrt(ee), TOUCH * scale * math.sqrt(ff)
    if ((d1 > tol_e and d2 < -tol_e) or (d1 < -tol_e and d2 > tol_e)) and (
        (d3 > tol_f and d4 < -tol_f) or (d3 < -tol_f and d4 > tol_f)
    ):
        return True  # a proper crossing
    lo, hi = -TOUCH, 1.0 + TOUCH
    for d, tol, px, py, ox, oy, ux, uy, uu in (
        (d1, tol_e, cx, cy, ax, ay, ex, ey, ee),
        (d2, tol_e, dx, dy, ax, ay, ex, ey, ee),
        (d3, tol_f, ax, ay, cx, cy, fx, fy, ff),
        (d4, tol_f, bx, by, cx, cy, fx, fy, ff),
    ):
        if abs(d) <= tol and lo <= ((px - ox) * ux + (py - oy) * uy) / uu <= hi:
            return True  # an endpoint on the other edge
    return False


def check_simple(p: Array, name: str) -> None:
    """Raise if two non-adjacent edges of the closed polygon ``p`` touch or cross.

    Args:
        p: ``(n, 2)`` vertices (length), either orientation, no repeats of
            consecutive vertices.
        name: the parameter named in the error.

    Raises:
        InvalidSheetError: 'polygon self-intersects', naming the two edges
            (edge i runs from vertex i to vertex i + 1) and their ends.

    A sweep line (Shamos and Hoey, 1976): the edges crossing the sweep line
    are kept in their order along it; an edge is compared with its
    neighbours when it enters, the two edges beside it with each other when
    it leaves, and at each event every pair of edges through the event's
    point (touching vertices, collinear overlaps: a handful at most). If any
    two edges meet, the leftmost meeting point is found that way, so
    O(n log n) comparisons (sort and binary searches) and O(n) edge tests
    decide. Below :data:`MAX_VERTICES` the list insertions (memmove, O(n)
    each in principle) cost less than the comparisons. Tolerance: points
    within 1e-12 of the polygon's scale of an edge lie on it.
    """
    n = len(p)
    if n < 4:
        return  # every pair of a triangle's edges is adjacent
    scale = float(np.max(np.abs(p)))
    pts = p.tolist()
    c, s = math.cos(SWEEP_ANGLE), math.sin(SWEEP_ANGLE)
    sx = (p[:, 0] * c - p[:, 1] * s).tolist()
    sy = (p[:, 0] * s + p[:, 1] * c).tolist()
    left, right, slope = [0] * n, [0] * n, [0.0] * n
    events = []
    for i in range(n):
        a, b = i, (i + 1) % n
        if (sx[b], sy[b]) < (sx[a], sy[a]):
            a, b = b, a
        left[i], right[i] = a, b
        dx = sx[b] - sx[a]
        slope[i] = (sy[b] - sy[a]) / dx if dx != 0.0 else math.inf
        events.append((sx[a], sy[a], 0, i))  # enters (before any edge leaves at that point)
        events.append((sx[b], sy[b], 1, i))  # leaves
    events.sort()

    def height(e: int, x0: float, y0: float) -> float:
        """Where edge e crosses the sweep line at x0 (y0 on a vertical edge)."""
        a, b = left[e], right[e]
        if slope[e] == math.inf:
            return min(max(y0, sy[a]), sy[b])
        return sy[a] + (x0 - sx[a]) * slope[e]

    def test(i: int, k: int) -> None:
        if k == (i + 1) % n or i == (k + 1) % n or not edges_meet(pts, i, k, scale):
            return
        i, k = min(i, k), max(i, k)
        raise InvalidSheetError(
            name,
            f"polygon self-intersects: edge {i} ({pts[i]} -> {pts[(i + 1) % n]}) "
            f"meets edge {k} ({pts[k]} -> {pts[(k + 1) % n]}); a simple polygon is required",
        )

    tie = TOUCH * scale
    status: list[int] = []  # edges crossing the sweep line, bottom to top

    def through_point(j: int, x0: float, y0: float) -> tuple[int, int]:
        """The run status[lo:hi] around position j of edges through (x0, y0)."""
        lo, hi = j, j + 1
        while lo > 0 and abs(height(status[lo - 1], x0, y0) - y0) <= tie:
            lo -= 1
        while hi < len(status) and abs(height(status[hi], x0, y0) - y0) <= tie:
            hi += 1
        return lo, hi

    def test_run(lo: int, hi: int) -> None:
        """Every pair of edges through one point, and the run's outer neighbours."""
        run = status[max(lo - 1, 0) : hi + 1]
        for a in range(len(run)):
            for b in range(a + 1, len(run)):
                test(run[a], run[b])

    for x0, y0, leaves, e in events:
        if leaves:
            j = status.index(e)
            test_run(*through_point(j, x0, y0))
            del status[j]
            if 0 < j < len(status):
                test(status[j - 1], status[j])
            continue
        lo, hi = 0, len(status)
        while lo < hi:  # binary search: the first edge above e at (x0, y0)
            mid = (lo + hi) // 2
            t = status[mid]
            yt = height(t, x0, y0)
            if yt < y0 or (yt == y0 and slope[t] < slope[e]):
                lo = mid + 1
            else:
                hi = mid
        status.insert(lo, e)
        test_run(*through_point(lo, x0, y0))


def boundary_distance(polygon: ArrayLike, point: ArrayLike = (0.0, 0.0)) -> float:
    """Distance from ``point`` to the boundary of the closed polygon ``(n, 2)``
    (length): the largest circle about ``point`` that stays inside it."""
    v = np.asarray(polygon, dtype=float) - np.asarray(point, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    t = np.clip(-(v * e).sum(axis=1) / (e * e).sum(axis=1), 0.0, 1.0)
    return float(np.min(np.hypot(*(v + t[:, None] * e).T)))
