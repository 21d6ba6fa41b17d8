"""How a body meets the ground: the exact plane after toppling on samples.

The body (:class:`onefold_cad.geometry.body.FoldedBody`) is set down with the
ground's upward normal ``g`` given in its own frame and let go: it tips about
its lowest points (one, then an edge) towards its centre of mass until the
centre of mass lies over the convex hull of three or more of them
(quasi-static toppling on the convex hull of the samples, each step lowering
the centre of mass: :func:`onefold_cad.geometry.topple.roll`). Then the ground is made exact: each
contact is moved to the exact lowest point of its piece near it (a tangency
of a boundary curve, a corner, the apex, a mitre vertex) and the plane is put
through three of them, alternately, until it no longer moves (the points move
along their curves, in the plane to first order: the plane converges
quadratically; :func:`settle`; the features' zooms run together,
:meth:`FoldedBody.lowest_many`). On two contacts, one of them a curved edge, the
body rocks: the plane is then the one on which they balance the centre of
mass (:func:`rock`). The exact lowest points of every piece that may come
near the ground check the plane (:func:`onefold_cad.geometry.lows.exact_lows`,
which zooms only where the samples leave it open; :func:`lowest_points`
zooms every piece within a band); a point below it (the apex, met while the
body rocks along two curved edges towards their balance) joins the features
and the plane is settled again (:func:`exact_features`,
:func:`onefold_cad.geometry.placement.rest_form`).

Points are in the body's frame (relative to the apex); lengths in the design
unit.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from itertools import combinations

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.hull import convex_hull_2d, edge_distances
from onefold_cad.geometry.numeric import Array, cross3, polygon_area, sorted_unique
from onefold_cad.geometry.topple import basis

__all__ = [
    "CONTACT_TOLERANCE",
    "Samples",
    "exact_features",
    "features",
    "holds",
    "lowest_points",
    "rock",
    "sample_spacing",
    "settle",
    "touching",
]

#: Heights within this fraction of the sheet's size count as touching the ground.
CONTACT_TOLERANCE = 1e-9


@dataclass
class _Feature:
    """A contact being made exact: a fixed point, or a piece and a bracket."""

    piece: int
    lo: float
    hi: float
    point: Array


@dataclass(frozen=True)
class Samples:
    """Points ``(N, 3)`` with the piece each lies on (-1: a fixed point) and
    its parameter there."""

    points: Array
    owner: NDArray[np.int64]
    param: Array

    def plus(self, more: list[tuple[int, float, Array]]) -> Samples:
        """These samples and more (piece, parameter, point)."""
        if not more:
            return self
        return Samples(
            np.vstack([self.points, np.array([p for _, _, p in more])]),
            np.concatenate([self.owner, np.array([k for k, _, _ in more], dtype=np.int64)]),
            np.concatenate([self.param, np.array([t for _, t, _ in more])]),
        )


def features(body: FoldedBody, samples: Samples, on: NDArray[np.int64]) -> list[_Feature]:
    """Group the sampled contacts ``on``: neighbouring samples of one piece are one."""
    owner, param = samples.owner[on], samples.param[on]
    out = [_Feature(-1, 0.0, 0.0, samples.points[i].copy()) for i in on[owner < 0]]
    for k in sorted_unique(owner[owner >= 0]):
        piece = body.pieces[int(k)]
        ts = sorted_unique(param[owner == k])
        idx = np.searchsorted(piece.grid, ts)
        for grp in np.split(ts, (np.diff(idx) > 2).nonzero()[0] + 1):
            lo, hi = piece.bracket(float(grp[0]), float(grp[-1]))
            out.append(_Feature(int(k), lo, hi, np.zeros(3)))
    return out


def exact_features(body: FoldedBody, lows: list[tuple[int, float, Array]]) -> list[_Feature]:
    """Features for exact lowest points (piece, parameter, point), as
    :func:`lowest_points` finds them: a fixed point as it is, a piece's
    point by the grid bracket around its parameter."""
    out = []
    for k, t, p in lows:
        if k < 0:
            out.append(_Feature(-1, 0.0, 0.0, p.copy()))
        else:
            lo, hi = body.pieces[k].bracket(t, t)
            out.append(_Feature(k, lo, hi, p.copy()))
    return out


def _locate(body: FoldedBody, features: list[_Feature], g: Array) -> list[Array]:
    """Move each feature to the exact lowest point of its bracket along ``g``,
    widening a bracket while the lowest point sits on an end of it (the
    features' zooms run together, :meth:`FoldedBody.lowest_many`)."""
    todo = [f for f in features if f.piece >= 0]
    for _ in range(8):
        if not todo:
            break
        found = body.lowest_many([(f.piece, f.lo, f.hi, g) for f in todo])
        wider = []
        for f, (t, p) in zip(todo, found, strict=True):
            piece = body.pieces[f.piece]
            width = f.hi - f.lo
            at_lo = t <= f.lo + 1e-3 * width and f.lo > piece.t0
            at_hi = t >= f.hi - 1e-3 * width and f.hi < piece.t1
            f.point = p
            if at_lo or at_hi:
                f.lo = max(piece.t0, t - width)
                f.hi = min(piece.t1, t + width)
                wider.append(f)
        todo = wider
    return [f.point for f in features]


#: above this many points, the candidate triangles are the lower facets of
#: their convex hull (Qhull) instead of every triple (O(k^4) work)
_ALL_TRIPLES_MAX = 12


def _plane_through(pts: Array, com: Array, g: Array, tol: float) -> Array | None:
    """The upward normal of the plane through three of ``pts`` ``(k, 3)`` that
    has every point on or above it, preferring a triangle under the centre
    of mass; None when there is no such plane.

    Points that all lie in one plane within ``tol`` (a side lying flat on the
    ground: hundreds of ruling ends) give that plane directly; many others
    are searched among the lower facets of their convex hull."""
    if len(pts) > 3:
        common = _common_plane(pts, g, tol)
        if common is not None:
            return common
    triples: Iterable[tuple[int, int, int]]
    if len(pts) > _ALL_TRIPLES_MAX:
        triples = _lower_facets(pts, g)
    else:
        triples = combinations(range(len(pts)), 3)
    best: tuple[float, Array] | None = None
    for i, j, k in triples:
        n = cross3(pts[j] - pts[i], pts[k] - pts[i])
        nn = float(np.linalg.norm(n))
        if nn <= tol * tol:
            continue
        n = n / nn if n @ g > 0.0 else -n / nn
        if float(np.min((pts - pts[i]) @ n)) < -tol:
            continue
        e1, e2 = basis(n)
        tri = np.column_stack([(pts[[i, j, k]] - com) @ e1, (pts[[i, j, k]] - com) @ e2])
        if polygon_area(tri) < 0.0:
            tri = tri[::-1]
        score = float(edge_distances([0.0, 0.0], tri).min())
        if best is None or score > best[0]:
            best = (score, n)
    return None if best is None else best[1]


def _common_plane(pts: Array, g: Array, tol: float) -> Array | None:
    """The upward unit normal of the plane that holds every point ``(k, 3)``
    within ``tol`` (least squares through their centroid), or None."""
    centred = pts - pts.mean(axis=0)
    _, sv, vt = np.linalg.svd(centred, full_matrices=False)
    if sv[1] <= tol:  # collinear: no plane
        return None
    n = vt[2]
    if float(np.max(np.abs(centred @ n))) > tol:
        return None
    return n if float(n @ g) > 0.0 else -n


def _lower_facets(pts: Array, g: Array) -> list[tuple[int, int, int]]:
    """The triangles of the convex hull of ``pts`` ``(k, 3)`` that face down
    along ``g`` (Qhull, imported here: only a form resting on many points
    needs it); every triple when Qhull cannot build the hull."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(pts, qhull_options="Qt")
    except QhullError:
        return list(combinations(range(len(pts)), 3))
    down = hull.equations[:, :3] @ g < 0.0
    return [(int(a), int(b), int(c)) for a, b, c in hull.simplices[down]]


def touching(
    samples: Samples, lows: list[tuple[int, float, Array]], g: Array, level: float, tol: float
) -> Array:
    """The points ``(k, 3)`` that touch the ground at ``level`` along ``g``
    within ``tol``: the exact lowest points, and samples of an edge that lies
    along the ground."""
    exact = [p for _, _, p in lows if float(p @ g) <= level + tol]
    near = samples.points[samples.points @ g <= level + tol]
    pts = np.vstack([np.array(exact).reshape(-1, 3), near])
    if len(pts) > 8:  # many along an edge: its hull's corners say as much
        e1, e2 = basis(g)
        pts = pts[convex_hull_2d(np.column_stack([pts @ e1, pts @ e2]), tol)]
    return _distinct(list(pts), tol)


def _distinct(pts: list[Array], tol: float) -> Array:
    out: list[Array] = []
    for p in pts:
        if all(math.sqrt(float((p - q) @ (p - q))) > tol for q in out):
            out.append(p)
    return np.array(out).reshape(-1, 3)


def settle(
    body: FoldedBody, features: list[_Feature], com: Array, g: Array
) -> tuple[Array, float, bool]:
    """Make the ground plane through the features exact (see the module doc):
    its upward normal, the features' lowest height along it, and whether it
    rests on two features only (a curved edge touching along with a point or
    another edge: the plane on which they balance the centre of mass,
    :func:`rock`)."""
    tol = CONTACT_TOLERANCE * body.size
    rocks = False
    least, stale = math.inf, 0
    for _ in range(40):
        pts = _distinct(_locate(body, features, g), tol)
        if len(pts) == 2:
            g, rocks = rock(body, features, com, g)
            break
        if len(pts) < 3:
            break
        n = _plane_through(pts, com, g, tol)
        if n is None:
            break
        moved = math.sqrt(float((n - g) @ (n - g)))
        g = n
        if moved <= 1e-15:
            break
        # it converges quadratically; a plane that stops closing in (it hops
        # between triangles of a body lying almost flat, whose lowest points
        # jump along nearly straight edges) is left to the caller's check
        least, stale = (moved, 0) if moved < 0.5 * least else (least, stale + 1)
        if stale >= 4:
            break
    pts = np.array(_locate(body, features, g))
    return g, float(np.min(pts @ g)), rocks


def rock(body: FoldedBody, features: list[_Feature], com: Array, g: Array) -> tuple[Array, bool]:
    """The ground normal near ``g`` on which the body rests on two features
    (one of them a curve it could rock on), with the centre of mass above the
    line through their lowest points: Newton's method on the two conditions
    (equal heights; centre of mass in the vertical plane through the line),
    with a finite-difference Jacobian. Returns the normal and whether that
    converged with the centre of mass between the two points (else ``g``
    unchanged)."""
    tol = CONTACT_TOLERANCE * body.size
    pts = _locate(body, features, g)
    first = pts[0]
    far = max(range(len(pts)), key=lambda i: float(np.linalg.norm(pts[i] - first)))
    pair = [features[0], features[far]]

    def residual(gg: Array) -> Array:
        q1, q2 = _locate(body, pair, gg)
        e = q2 - q1
        e /= max(float(np.linalg.norm(e)), 1e-300)
        return np.array([gg @ (q2 - q1), (com - q1) @ cross3(gg, e)])

    def balanced(gg: Array) -> tuple[Array, bool]:
        q1, q2 = _locate(body, pair, gg)
        span2 = float((q2 - q1) @ (q2 - q1))
        along = float((com - q1) @ (q2 - q1)) / span2 if span2 > tol * tol else -1.0
        return (gg, True) if 0.0 < along < 1.0 else (start, False)

    start = g
    # the heights are flat at a tangency, so the point's place along the curve,
    # and with it the balance, is known to about 1e-8 of the size only: aim
    # for the contact tolerance, settle for the best within 1e-6 of the size
    eps = 1e-4
    best: tuple[float, Array] | None = None
    for _ in range(30):
        f0 = residual(g)
        if abs(f0[0]) <= 1e-3 * tol:
            if abs(f0[1]) <= tol:
                return balanced(g)
            if abs(f0[1]) <= 1e-6 * body.size and (best is None or abs(f0[1]) < best[0]):
                best = (abs(f0[1]), g)
        e1, e2 = basis(g)
        jac = np.empty((2, 2))
        for j, d in enumerate((e1, e2)):
            gd = g + eps * d
            jac[:, j] = (residual(gd / np.linalg.norm(gd)) - f0) / eps
        try:
            step = np.linalg.solve(jac, -f0)
        except np.linalg.LinAlgError:
            break
        length = float(np.linalg.norm(step))
        if length > 0.02:  # stay near the samples' rest (the residual jumps elsewhere)
            step *= 0.02 / length
        g = g + step[0] * e1 + step[1] * e2
        g /= np.linalg.norm(g)
        if float(np.linalg.norm(g - start)) > 0.1:
            break
    return balanced(best[1]) if best is not None else (start, False)


def lowest_points(
    body: FoldedBody, samples: Samples, g: Array, band: float
) -> list[tuple[int, float, Array]]:
    """The exact lowest point along ``g`` of every fixed point whose height
    lies within ``band`` (length) of the lowest sample, and of every piece
    whose samples come within ``band`` or twice its own sample spacing
    (:attr:`FoldedBody.spacings`), the smaller, of it (no point of a piece lies
    lower than its samples by more than that spacing): a list of (piece,
    parameter, point), the lowest first.

    A piece's own spacing, not the body's largest, keeps the work small on a
    sheet of many vertices, where a long edge's samples lie far apart and
    every other edge would come within the body's band."""
    found, asks = _candidates(body, samples, g, band)
    for (k, _, _, _), (tb, p) in zip(asks, body.lowest_many(asks), strict=True):
        found.append((k, tb, p))
    found.sort(key=lambda item: float(item[2] @ g))
    return found


def _candidates(
    body: FoldedBody, samples: Samples, g: Array, band: float
) -> tuple[list[tuple[int, float, Array]], list[tuple[int, float, float, Array]]]:
    """The fixed points within ``band`` of the lowest sample along ``g`` (as
    (piece -1, 0, point)), and the zooms :func:`lowest_points` needs (piece,
    bracket, direction)."""
    h = samples.points @ g
    floor = float(h.min())
    fixed = samples.owner < 0
    found = [(-1, 0.0, samples.points[i]) for i in (fixed & (h <= floor + band)).nonzero()[0]]
    reach = np.minimum(band, 2.0 * body.spacings + 1e-10 * body.size)
    near = np.zeros(len(h), dtype=bool)
    if len(reach):  # the paper shell without a hole has fixed points only
        near[~fixed] = h[~fixed] <= floor + reach[samples.owner[~fixed]]
    asks: list[tuple[int, float, float, Array]] = []
    for k in sorted_unique(samples.owner[near]):
        piece = body.pieces[int(k)]
        corners = body.sections[int(k)]
        hk = np.where(np.isnan(corners[..., 0]), np.inf, corners @ g).min(axis=1)
        # the piece's sampled local minima within reach (a plateau counts once)
        left = np.concatenate([[True], hk[1:] < hk[:-1]])
        right = np.concatenate([hk[:-1] <= hk[1:], [True]])
        for tj in piece.grid[(hk <= floor + reach[int(k)]) & left & right]:
            lo, hi = piece.bracket(float(tj), float(tj))
            asks.append((int(k), lo, hi, g))
    return found, asks


def sample_spacing(body: FoldedBody) -> float:
    """The largest of the pieces' sample spacings (:attr:`FoldedBody.spacings`;
    length): no point of a piece lies further than that from its nearest
    sample; the thickness when there are no pieces."""
    return float(body.spacings.max()) if len(body.spacings) else body.thickness


def holds(contacts: Array, com: Array, g: Array, tol: float) -> bool:
    """Whether the centre of mass lies over the hull of ``contacts`` ``(k, 3)``
    by more than ``tol`` (length), seen along ``g``."""
    e1, e2 = basis(g)
    q = np.column_stack([(contacts - com) @ e1, (contacts - com) @ e2])
    hull = convex_hull_2d(q, tol)
    return len(hull) >= 3 and float(edge_distances([0.0, 0.0], q[hull]).min()) > tol
