"""Toppling on samples: a body set down on its sample points tips about its
lowest points (one, then an edge) towards its centre of mass until the centre
of mass lies over the convex hull of three or more of them (quasi-static
toppling on the convex hull of the samples, each step lowering the centre of
mass: :func:`roll`). The exact ground plane is made afterwards
(:mod:`onefold_cad.geometry.resting.ground`).

Points are in the body's frame (relative to the apex); lengths in the design
unit.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.numeric import Array, cross3
from onefold_cad.geometry.resting.hull import convex_hull_2d, edge_distances

__all__ = ["basis", "com_depth", "com_outside", "roll"]


def basis(g: Array) -> tuple[Array, Array]:
    """Two unit vectors completing ``g`` to a right-handed orthonormal frame."""
    a = np.array([1.0, 0.0, 0.0]) if abs(g[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = a - (a @ g) * g
    e1 /= math.sqrt(float(e1 @ e1))  # np.linalg.norm's arithmetic, without its wrapper
    return e1, cross3(g, e1)


def _nearest_on_polygon(corners: Array) -> tuple[int, int, float]:
    """The point of a convex polygon's boundary (or segment, or point)
    ``(m, 2)`` nearest the origin: (i, j, distance), with i == j for a corner
    and (i, j) the edge's corners otherwise."""
    m = len(corners)
    if m == 1:
        return 0, 0, float(np.hypot(*corners[0]))
    best = (0, 0, math.inf)
    for i in range(m if m > 2 else 1):
        j = (i + 1) % m
        a, b = corners[i], corners[j]
        d = b - a
        t = min(max(-float(a @ d) / max(float(d @ d), 1e-300), 0.0), 1.0)
        dist = float(np.hypot(*(a + t * d)))
        if dist < best[2]:
            best = (i, i, dist) if t <= 0.0 else (j, j, dist) if t >= 1.0 else (i, j, dist)
    return best


def roll(points: Array, com: Array, g: Array, tol: float) -> tuple[Array, NDArray[np.int64]]:
    """:func:`_topple`, and if that goes on for long (rolling along a curved edge
    goes sample by sample) on every 16th point from where it got, then on all
    again; a form that balances falls to the side nearer the fold frame's
    upright. It stops as soon as a topple ends: at a rest, with the centre of
    mass below the lowest point (outside the points' hull: no rest exists,
    :func:`com_depth` says by how much) or when the centre of mass no longer
    comes down (rounding decides the steps); at most 8200 steps in all."""

    def roll(pts: Array, g: Array, steps: int) -> tuple[Array, NDArray[np.int64], bool]:
        g, on, state = _topple(pts, com, g, tol, steps=steps)
        if state == "balanced":
            ways = [_topple(pts, com, g, tol, push, steps) for push in (1.0, -1.0)]
            g, on, state = ways[1] if ways[1][0][2] > ways[0][0][2] + 1e-12 else ways[0]
        return g, on, state in _DONE

    g, on, done = roll(points, g, 200)
    if not done and len(points) > 256:
        g, _, _ = roll(points[::16], g, 4000)
    if not done:
        g, on, _ = roll(points, g, 4000)
    return g, on


#: how a topple may end without 'rolling' on: no further step would be honest
_DONE = ("rests", "outside", "stalled")
#: steps without a new lowest centre of mass after which a topple has stalled
_STALL_STEPS = 64


def com_depth(points: Array, com: Array, g: Array) -> float:
    """How far (length) the centre of mass ``com`` lies below the lowest of
    ``points`` ``(N, 3)`` along the upward normal ``g``: positive only when it
    lies outside their convex hull, where no rest on them can hold it."""
    return float((points @ g).min() - com @ g)


def com_outside(points: Array, com: Array) -> float:
    """A lower bound (length) on how far ``com`` lies outside the convex hull
    of ``points`` ``(N, 3)``: its largest :func:`com_depth` along the points'
    principal axes (both ways) and the way from their centroid to it; 0 when
    none of these shows it outside (a needle's few nanometres across are its
    two thin axes)."""
    mean = points.mean(axis=0)
    # the principal axes (directions to look along: any gives a lower bound)
    # from at most about 2048 of the points
    _, _, vt = np.linalg.svd(points[:: max(1, len(points) // 2048)] - mean, full_matrices=False)
    off = com - mean
    ways = np.vstack([vt, off / max(float(np.linalg.norm(off)), 1e-300)]).T  # (3, 4)
    h, c = np.ascontiguousarray((points @ ways).T), com @ ways  # (4, N): rows reduce fast
    # com_depth along each way and against it, from one product
    return max(0.0, float(np.max(h.min(axis=1) - c)), float(np.max(c - h.max(axis=1))))


def _topple(
    points: Array, com: Array, g: Array, tol: float, push: float = 0.0, steps: int = 4000
) -> tuple[Array, NDArray[np.int64], str]:
    """Tip the point set about its lowest points until the centre of mass
    ``com`` lies over their hull. ``g`` is the ground's upward normal in the
    body's frame. Returns the final normal, the indices of the contacts, and
    how it ended: 'rests', 'balanced' (exactly above an edge or a point: an
    unstable equilibrium, as symmetric forms meet it; a ``push`` of +1 or -1
    then tips it to one side or the other), 'outside' (the centre of mass
    lies more than ``tol`` below the lowest point: outside the points' hull,
    which no tipping mends), 'stalled' (the centre of mass came no lower in
    :data:`_STALL_STEPS` steps: each step lowers it, so rounding, not the
    body, decides them) or 'rolling' (after ``steps``)."""
    on = np.zeros(0, dtype=np.int64)
    lowest, since = math.inf, 0
    for _ in range(steps):
        h = points @ g
        floor = float(h.min())
        on = (h <= floor + tol).nonzero()[0]
        height = float(com @ g) - floor
        if height < -tol:
            return g, on, "outside"
        if height < lowest:
            lowest, since = height, 0
        else:
            since += 1
            if since >= _STALL_STEPS:
                return g, on, "stalled"
        e1, e2 = basis(g)
        rel = points[on] - com
        q = np.column_stack([rel @ e1, rel @ e2])
        hull = convex_hull_2d(q, tol)
        corners = q[hull]
        if len(hull) >= 3 and float(edge_distances([0.0, 0.0], corners).min()) > tol:
            return g, on, "rests"  # the centre of mass is over the support polygon
        i, j, _ = _nearest_on_polygon(corners)
        p0 = points[on[hull[i]]]
        w = com - p0
        w -= (w @ g) * g
        if i != j:  # tip about an edge: the horizontal offset across it
            e = points[on[hull[j]]] - p0
            e /= math.sqrt(float(e @ e))
            w -= (w @ e) * e
        wn = math.sqrt(float(w @ w))
        if wn <= tol:  # balanced exactly above a contact or an edge
            if push == 0.0:
                return g, on, "balanced"
            axis = points[on[hull[j]]] - p0 if i != j else e1
            w = push * cross3(g, axis)
            push, wn = 0.0, math.sqrt(float(w @ w))
        w /= wn
        rel = points - p0
        a = rel @ g
        b = rel @ w
        # the contacts are on the ground: one lumped in by the tolerance can
        # lie a little below p0 and just across the edge (a support polygon
        # a few tolerances wide, a needle's), and would tip the body back
        toward = b > tol
        toward[on] = False
        if not toward.any():
            return g, on, "rests"
        # the first point the tilt meets: the least angle atan2(a, b), b > 0,
        # which grows with a / b (one arctangent, at the least ratio)
        at, bt = a[toward], b[toward]
        i = int((at / bt).argmin())
        phi = max(math.atan2(float(at[i]), float(bt[i])), 0.0)
        g = math.cos(phi) * g - math.sin(phi) * w
        g /= math.sqrt(float(g @ g))
    return g, on, "rolling"
