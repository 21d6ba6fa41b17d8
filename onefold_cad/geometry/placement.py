"""Stand a folded form on the ground: the stable resting placement.

The form rests on a face of its convex hull whose plane, taken as the ground,
has the surface's centre of mass above the hull's contact polygon. Of the
stable faces we take the one needing the smallest tilt from the fold frame
(apex above H), rotate it onto z = 0 and report the points that touch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import ConvexHull, QhullError

from onefold_cad.geometry.validate import cross3

__all__ = ["RestingPlacement", "rest_on_ground"]

Array = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class RestingPlacement:
    """A rigid motion ``p' = rotation @ p + translation`` that rests a form on z = 0.

    Attributes:
        rotation: ``(3, 3)`` rotation matrix.
        translation: ``(3,)`` translation (length).
        touching: indices of the input points that lie on the ground.
        tilt_deg: angle between the fold frame's z axis and the ground's
            normal (deg); 0 when the form stands as it was solved.
        stable: whether the centre of mass lies over the contact polygon.
    """

    rotation: Array
    translation: Array
    touching: NDArray[np.int64]
    tilt_deg: float
    stable: bool

    def apply(self, points: ArrayLike) -> Array:
        """Move fold-frame points ``(k, 3)`` into the resting placement."""
        return np.asarray(points, dtype=float) @ self.rotation.T + self.translation


def _rotation_to_down(n: Array) -> Array:
    """The smallest rotation taking unit vector ``n`` to (0, 0, -1)."""
    target = np.array([0.0, 0.0, -1.0])
    axis = cross3(n, target)
    s = float(np.linalg.norm(axis))
    c = float(np.dot(n, target))
    if s < 1e-15:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = axis / s
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + s * kx + (1 - c) * (kx @ kx)


def _inside_convex(point2: Array, poly2: Array) -> bool:
    """Whether ``point2`` lies in the convex hull of the 2D points ``poly2``."""
    if len(poly2) < 3:
        return False
    try:
        hull = ConvexHull(poly2)
    except QhullError:
        return False
    eq = hull.equations
    return bool(np.all(eq[:, :2] @ point2 + eq[:, 2] <= 1e-9 * (1 + np.abs(eq[:, 2]).max())))


def rest_on_ground(
    points: ArrayLike, centre_of_mass: ArrayLike, candidates: int | None = None
) -> RestingPlacement:
    """Find how the form made of ``points`` ``(k, 3)`` rests on the ground.

    Args:
        points: the form's boundary points and apex (fold frame).
        centre_of_mass: ``(3,)`` the surface's area centroid.
        candidates: if given and exceeded, only about this many evenly spaced
            points (and the last point, the apex) are considered as contacts;
            the rest are moved with the placement all the same.
    """
    allp = np.asarray(points, dtype=float)
    idx = np.arange(len(allp))
    if candidates is not None and len(allp) > candidates:
        step = int(np.ceil(len(allp) / candidates))
        idx = np.unique(np.concatenate([idx[:-1:step], idx[-1:]]))
    p = allp[idx]
    com = np.asarray(centre_of_mass, dtype=float)
    scale = float(np.ptp(p, axis=0).max())
    tol = 1e-9 * scale
    best: tuple[float, Array, NDArray[np.int64], bool] | None = None
    try:
        hull = ConvexHull(p)
        planes = np.unique(np.round(hull.equations, 12), axis=0)
    except QhullError:
        planes = np.empty((0, 4))
    planes = planes[np.argsort(planes[:, 2])]  # most downward-facing first
    for eq in planes:
        n = eq[:3] / np.linalg.norm(eq[:3])
        dist = p @ n + eq[3] / np.linalg.norm(eq[:3])
        on = np.flatnonzero(np.abs(dist) <= max(tol, 1e-7 * scale))
        rot = _rotation_to_down(n)
        stable = _inside_convex((com @ rot.T)[:2], (p[on] @ rot.T)[:, :2])
        tilt = math.degrees(math.acos(float(np.clip(-n[2], -1.0, 1.0))))
        if best is None:
            best = (tilt, rot, on, stable)
        if stable:  # planes are sorted by tilt, so the first stable one is best
            best = (tilt, rot, on, stable)
            break
    if best is None:  # degenerate (flat) form: keep the fold frame orientation
        rot = np.eye(3)
        zmin = float(p[:, 2].min())
        on = np.flatnonzero(p[:, 2] <= zmin + tol)
        return RestingPlacement(rot, np.array([0.0, 0.0, -zmin]), idx[on], 0.0, False)
    tilt, rot, on, stable = best
    moved = p @ rot.T
    zmin = float(moved[on, 2].mean())
    return RestingPlacement(
        rot, np.array([0.0, 0.0, -zmin]), idx[on].astype(np.int64), tilt, stable
    )
