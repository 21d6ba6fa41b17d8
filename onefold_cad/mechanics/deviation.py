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

import weakref
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.geometry.cone.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = ["RigidFit", "best_fit", "surface_distance"]

_MIRROR = np.array([1.0, -1.0, 1.0])
#: Flat angles sampled per side before the closest ruling is refined.
_GRID = 361
#: Illinois steps that refine it (superlinear: from a grid step of 0.5 deg
#: to rounding in about six).
_STEPS = 8


@dataclass(frozen=True, eq=False)
class _Rulings:
    """A designed surface's sampled rulings, the same for every call on it.

    Attributes:
        grid: ``(m,)`` the samples' parameters: the exact cone's arc
            parameters (its frames there need no flat angle inverted), else
            the flat angles themselves.
        u, e: ``(m, 3)`` the rulings' directions and in-surface normals there.
        reach: ``(2, m)`` the sheet's extent along them on the +y and -y sides.
        frames: ``u`` and ``e`` at parameters; ``theta``: their flat angles.
    """

    grid: Array
    u: Array
    e: Array
    reach: Array
    frames: Callable[[Array], tuple[Array, Array]]
    theta: Callable[[Array], Array]


_RULINGS: weakref.WeakKeyDictionary[FoldedSheet, _Rulings] = weakref.WeakKeyDictionary()


def _rulings(folded: FoldedSheet) -> _Rulings:
    """``folded``'s sampled rulings, made on its first measure and kept with it."""
    cached = _RULINGS.get(folded)
    if cached is None:
        surface = folded.solution.surface
        angles = np.linspace(0.0, surface.total_angle, _GRID)
        u, e = surface.frames(angles)
        reach = np.stack([folded.sheet.ray_lengths(angles), folded.sheet.ray_lengths(-angles)])
        if isinstance(surface, ExactCone):
            phi = surface.phi_of_theta(angles)
            cached = _Rulings(phi, u, e, reach, surface.frames_at_arc, surface.theta_of_phi)
        else:
            cached = _Rulings(angles, u, e, reach, surface.frames, lambda t: t)
        _RULINGS[folded] = cached
    return cached


def _side_distance(folded: FoldedSheet, w: Array, lower: bool, hole_radius: float) -> Array:
    """``(k,)`` distance of the points ``w`` (relative to the apex, ``(k, 3)``,
    mirrored already for the -y side) from one side's cone patch."""
    rulings, sheet = _rulings(folded), folded.sheet
    sign = -1.0 if lower else 1.0
    grid = rulings.grid
    reach_grid = rulings.reach[int(lower)]
    along = w @ rulings.u.T  # (k, m): each point's distance along each sampled ruling
    r = np.clip(along, hole_radius, reach_grid[None, :])
    d2 = (
        np.einsum("ij,ij->i", w, w)[:, None] - 2.0 * r * along + r**2  # |w - r u|^2 with |u| = 1
    )
    j = np.argmin(d2, axis=1)
    best = np.sqrt(np.maximum(d2[np.arange(len(w)), j], 0.0))
    # the closest ruling lies where g = w . e changes sign (w in the plane of u
    # and the normal), in one of the grid intervals beside the best sample:
    # take the one with the sign change and close in on it (Illinois' method)
    g_grid = w @ rulings.e.T
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
        g_mid = np.einsum("ij,ij->i", w, rulings.frames(mid)[1])
        same = np.sign(g_mid) == np.sign(g_hi)
        # Illinois: halve the end that stays, so the interval keeps shrinking
        g_lo = np.where(same, g_lo * 0.5, g_hi)
        lo = np.where(same, lo, hi)
        hi, g_hi = mid, g_mid
    u = rulings.frames(hi)[0]
    reach = sheet.ray_lengths(sign * rulings.theta(hi))
    r_foot = np.clip(np.einsum("ij,ij->i", w, u), hole_radius, reach)
    refined = np.linalg.norm(w - r_foot[:, None] * u, axis=1)
    return np.minimum(best, refined)


def surface_distance(folded: FoldedSheet, points: ArrayLike, hole_radius: float = 0.0) -> Array:
    """``(k,)`` the distance of each point ``(k, 3)`` (fold frame) from the
    designed surface of ``folded`` (exact model): the nearest point on either
    side's cone patch, between the relief hole (``hole_radius``) and the
    sheet's edge.

    The closest ruling is bracketed on a grid of flat angles (sampled once per
    ``folded`` and kept with it) and refined by Illinois' method on
    ``(p - A) . e = 0`` (the foot of the perpendicular), in the exact cone's
    arc parameter; where the foot falls beyond the hole or the edge, the
    distance is to that end of the ruling (an upper bound within the sampled
    rulings' spacing of the boundary's true nearest point).
    """
    p = np.atleast_2d(np.asarray(points, dtype=float))
    w = p - folded.apex
    upper = _side_distance(folded, w, False, hole_radius)
    lower = _side_distance(folded, w * _MIRROR, True, hole_radius)
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
