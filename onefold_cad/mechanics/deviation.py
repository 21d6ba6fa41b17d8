"""How far a simulated sheet lies from the designed form.

The designed form is the fold's exact surface: on each side of the crease the
cone ``A + r u(theta)`` over the flat angles theta in [0, pi] (the -y side is
the mirror image of the +y side in the xz-plane), r from the relief hole's
radius to the sheet's boundary along the ray. :func:`surface_distance` is the
distance of points from that surface (the closest point on it, found on the
exact cone); :func:`best_fit` is the rigid motion that brings one point set
closest to another (weighted least squares, Kabsch's method), for comparing a
released form, which has no place of its own, with the design.

Lengths are in the fold's unit (whatever the points are in).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = ["RigidFit", "best_fit", "surface_distance"]

_MIRROR = np.array([1.0, -1.0, 1.0])
#: Flat angles sampled per side before the closest ruling is refined.
_GRID = 361
#: Illinois steps that refine it (superlinear: from a grid step of 0.5 deg
#: to rounding in about six).
_STEPS = 8


def _side_distance(
    folded: FoldedSheet, w: Array, lower: bool, hole_radius: float, grid: Array
) -> Array:
    """``(k,)`` distance of the points ``w`` (relative to the apex, ``(k, 3)``,
    mirrored already for the -y side) from one side's cone patch."""
    surface, sheet = folded.solution.surface, folded.sheet
    sign = -1.0 if lower else 1.0

    def foot(theta: Array, u: Array) -> Array:
        reach = sheet.ray_lengths(sign * theta)
        r = np.clip(np.einsum("ij,ij->i", w, u), hole_radius, reach)
        return np.linalg.norm(w - r[:, None] * u, axis=1)

    u_grid, e_grid = surface.frames(grid)
    reach_grid = sheet.ray_lengths(sign * grid)
    along = w @ u_grid.T  # (k, m): each point's distance along each sampled ruling
    r = np.clip(along, hole_radius, reach_grid[None, :])
    d2 = (
        np.einsum("ij,ij->i", w, w)[:, None] - 2.0 * r * along + r**2  # |w - r u|^2 with |u| = 1
    )
    j = np.argmin(d2, axis=1)
    best = np.sqrt(np.maximum(d2[np.arange(len(w)), j], 0.0))
    # the closest ruling lies where g = w . e changes sign (w in the plane of u
    # and the normal), in one of the grid intervals beside the best sample:
    # take the one with the sign change and close in on it (Illinois' method)
    g_grid = w @ e_grid.T
    rows = np.arange(len(w))
    left = np.maximum(j - 1, 0)
    right = np.minimum(j + 1, len(grid) - 1)
    upper = np.sign(g_grid[rows, j]) != np.sign(g_grid[rows, right])
    a = np.where(upper, j, left)
    b = np.where(upper, right, j)
    lo, hi = grid[a], grid[b]
    g_lo, g_hi = g_grid[rows, a], g_grid[rows, b]
    for _ in range(_STEPS):
        den = g_hi - g_lo
        mid = np.where(den != 0.0, hi - g_hi * (hi - lo) / np.where(den != 0.0, den, 1.0), lo)
        mid = np.clip(mid, np.minimum(lo, hi), np.maximum(lo, hi))
        g_mid = np.einsum("ij,ij->i", w, surface.frames(mid)[1])
        same = np.sign(g_mid) == np.sign(g_hi)
        # Illinois: halve the end that stays, so the interval keeps shrinking
        g_lo = np.where(same, g_lo * 0.5, g_hi)
        lo = np.where(same, lo, hi)
        hi, g_hi = mid, g_mid
    theta = hi
    refined = foot(theta, surface.frames(theta)[0])
    return np.minimum(best, refined)


def surface_distance(folded: FoldedSheet, points: ArrayLike, hole_radius: float = 0.0) -> Array:
    """``(k,)`` the distance of each point ``(k, 3)`` (fold frame) from the
    designed surface of ``folded`` (exact model): the nearest point on either
    side's cone patch, between the relief hole (``hole_radius``) and the
    sheet's edge.

    The closest ruling is bracketed on a grid of flat angles and refined by
    bisection of ``(p - A) . e(theta) = 0`` (the foot of the perpendicular);
    where the foot falls beyond the hole or the edge, the distance is to that
    end of the ruling (an upper bound within the sampled rulings' spacing of
    the boundary's true nearest point).
    """
    p = np.atleast_2d(np.asarray(points, dtype=float))
    w = p - folded.apex
    grid = np.linspace(0.0, folded.solution.surface.total_angle, _GRID)
    upper = _side_distance(folded, w, False, hole_radius, grid)
    lower = _side_distance(folded, w * _MIRROR, True, hole_radius, grid)
    return np.minimum(upper, lower)


@dataclass(frozen=True)
class RigidFit:
    """A rigid motion ``p -> rotation @ p + translation``.

    Attributes:
        rotation: ``(3, 3)`` proper rotation.
        translation: ``(3,)`` (length).
        rms: the weighted root-mean-square distance left between the moved
            points and their targets (length).
    """

    rotation: Array
    translation: Array
    rms: float

    def apply(self, points: ArrayLike) -> Array:
        """``(k, 3)`` the points moved."""
        return np.asarray(points, dtype=float) @ self.rotation.T + self.translation


def best_fit(points: ArrayLike, targets: ArrayLike, weights: ArrayLike | None = None) -> RigidFit:
    """The rigid motion that brings ``points`` ``(k, 3)`` closest to ``targets``
    ``(k, 3)`` in the weighted least-squares sense (Kabsch's method; a
    reflection is never chosen). ``weights`` ``(k,)`` >= 0, default equal."""
    p = np.asarray(points, dtype=float)
    q = np.asarray(targets, dtype=float)
    wt = np.ones(len(p)) if weights is None else np.asarray(weights, dtype=float)
    wt = wt / wt.sum()
    pc, qc = wt @ p, wt @ q
    h = (p - pc).T @ ((q - qc) * wt[:, None])
    u, _, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(vt.T @ u.T)) or 1.0
    rot = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    t = qc - rot @ pc
    moved = p @ rot.T + t
    rms = float(np.sqrt(wt @ np.einsum("ij,ij->i", moved - q, moved - q)))
    return RigidFit(rot, t, rms)
