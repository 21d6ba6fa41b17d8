"""A paper fan of few divisions whose crease folds exactly as a design's.

A fan over division points on the frame curve (its wedges chord planes of
the cone) folds its crease shallower than the cone it approximates: each
wedge beside the crease is turned from the cone's tangent plane there by
about k_g x gamma / 2 (gamma its flat angle at H, k_g the geodesic
curvature of the cone's spherical image). The *tangent-ended* fan keeps the
design's apex and crease rulings and lays each end wedge in the design's
tangent plane along its crease half, so its crease folds as the design's to
rounding, whatever the wedge's width:

* its ruling directions start as the unit directions ``q_k`` from the
  design's apex to the division points (of a given :class:`ArcSpacing`);
* ``d_1`` is ``q_1`` moved onto the great circle that leaves ``q_0`` along
  the design's in-surface direction at the +x crease half (its nearest point
  there), ``d_(n-1)`` likewise at the -x half;
* the directions between, ``d_k = unit(q_k + lam g_k nu_k)`` (``nu_k`` the
  unit tangent of the sphere at ``q_k`` normal to the chord ``q_(k-1)
  q_(k+1)``, away from it; ``g_k`` the product of the two angles from
  ``q_k`` to its neighbours, the local gap between curve and chords going
  as their square), are moved off the inscribed polygon by the one ``lam``
  (brentq, to rounding) for which the apex angles add up to pi a side.

So the fan folds from the flat sheet exactly (the angle condition holds for
it, at the design's apex) and its crease is the design's; it departs from
the cone by about as much as the inscribed fan does. It needs an interior
direction to move: at least 4 divisions.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.optimize import brentq

from onefold_cad.choices import Model
from onefold_cad.geometry.arc import ArcSpacing
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.frame_curve import FrameCurve
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.solver import Solution

__all__ = ["MIN_DIVISIONS", "TangentEndedFan", "crease_tangents", "tangent_ended"]

#: The fewest divisions a tangent-ended fan can have (one direction to move).
MIN_DIVISIONS = 4


class TangentEndedFan(PaperFan):
    """A :class:`PaperFan` whose directions are set by :func:`tangent_ended`
    (not on the frame curve's division points but for the ends). Its
    :attr:`points` are the directions' points at the division points'
    distances from the apex (length)."""

    def __init__(self, frame: FrameCurve, spacing: ArcSpacing | None) -> None:
        super().__init__(frame, spacing)
        self._own_points: Array | None = None

    @property
    def points(self) -> Array:
        """``(divisions + 1, 3)`` the fan's vertices on its rulings (length),
        +x end first: at the frame curve's ends, off it between."""
        return super().points if self._own_points is None else self._own_points


def crease_tangents(solution: Solution) -> tuple[Array, Array]:
    """The unit directions, in the design's tangent plane along each crease
    half, that lead from it into the +y side (``(3,)`` each: +x half, -x half)."""
    surface = solution.surface
    if isinstance(surface, PaperFan):
        (u0, e0), (un, en) = surface.crease_frames()
    else:
        u0, e0 = surface.frame_at(0.0)
        un, en = surface.frame_at(surface.total_angle)
    out = []
    for u, e, sign in ((u0, e0, 1.0), (un, en, -1.0)):  # e runs along theta: into the side at +x
        uu, ee = np.asarray(u, dtype=float), np.asarray(e, dtype=float)
        uu /= np.linalg.norm(uu)
        t = ee - (ee @ uu) * uu
        out.append(sign * t / np.linalg.norm(t))
    return out[0], out[1]


def _angles(d: Array) -> Array:
    """Kahan's angles between consecutive unit rows of ``d`` (radians)."""
    a, b = d[1:], d[:-1]
    return 2.0 * np.arctan2(np.linalg.norm(a - b, axis=1), np.linalg.norm(a + b, axis=1))


def tangent_ended(frame: FrameCurve, spacing: ArcSpacing | None, design: Solution) -> Solution:
    """The tangent-ended fan of ``frame.divisions`` divisions (the
    ``spacing``'s, None: equal) over ``frame``, at ``design``'s apex and with
    its crease tangent planes (see the module notes), as a paper-model
    :class:`Solution` ready to fold.

    Raises:
        ValueError: fewer than :data:`MIN_DIVISIONS` divisions, or no move of
            the directions between makes the angles add up to pi.
    """
    n = frame.divisions
    if n < MIN_DIVISIONS:
        raise ValueError(f"a tangent-ended fan needs at least {MIN_DIVISIONS} divisions, got {n}")
    fan = TangentEndedFan(frame, spacing)
    h = design.apex_height
    fan.set_apex(h)
    assert fan.directions is not None
    q = np.array(fan.directions)
    t0, tn = crease_tangents(design)
    d = q.copy()
    for k, end, t in ((1, 0, t0), (n - 1, n, tn)):
        g = math.atan2(float(q[k] @ t), float(q[k] @ q[end]))
        d[k] = math.cos(g) * q[end] + math.sin(g) * t
    inner = slice(2, n - 1)
    nu = np.cross(q[inner], q[3:n] - q[1 : n - 2])
    nu /= np.linalg.norm(nu, axis=1)[:, None]
    away = q[inner] - 0.5 * (q[1 : n - 2] + q[3:n])
    nu *= np.where(np.einsum("ij,ij->i", nu, away) < 0.0, -1.0, 1.0)[:, None]
    chord = _angles(q)
    nu *= (chord[1 : n - 2] * chord[2 : n - 1])[:, None]  # the local gap, ~ gamma^2

    def place(lam: float) -> Array:
        p = q[inner] + lam * nu
        d[inner] = p / np.linalg.norm(p, axis=1)[:, None]
        return d

    def excess(lam: float) -> float:
        return float(_angles(place(lam)).sum()) - math.pi

    lo, hi = 0.0, 1e-2
    sign = 1.0 if excess(0.0) < 0.0 else -1.0
    while excess(sign * hi) * excess(sign * lo) > 0.0:
        lo, hi = hi, 2.0 * hi
        if hi > 10.0:
            raise ValueError("no tangent-ended fan folds from the flat sheet over this frame")
    a, b = sorted((sign * lo, sign * hi))
    lam = brentq(excess, a, b, xtol=1e-17, rtol=4.0 * np.finfo(float).eps, maxiter=200)
    directions = place(float(lam)).copy()
    gammas = _angles(directions)
    thetas = np.concatenate(([0.0], np.cumsum(gammas)))
    apex = np.array((0.0, 0.0, h))
    reach = np.linalg.norm(super(TangentEndedFan, fan).points - apex, axis=1)
    fan._own_points = apex + reach[:, None] * directions
    fan.directions, fan.gammas, fan.thetas = directions, gammas, thetas
    total = float(gammas.sum())
    fan._apex_state = (total - math.pi, 16.0 * np.finfo(float).eps * n, h / frame.radius, reach)
    return replace(
        design,
        frame=frame,
        model=Model.PAPER,
        surface=fan,
        angle_sum_deg=2.0 * math.degrees(total),
        angle_condition_error_deg=2.0 * math.degrees(abs(total - math.pi)),
        warnings=(),
    )
