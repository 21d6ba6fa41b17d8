"""Points of the frame curve (paper section 3.2) in the fold frame, and the
exact cone's frames along it.

The arc is parametrised by its polar angle phi about the arc's centre,
phi in [-alpha, 180 + alpha] (radians inside the package): phi = -alpha is the
f-line's +x end, phi = 180 + alpha its -x end. A point at distance d from the
chord maps to (x, d cos(beta), d sin(beta)).

Points are computed from the nearer end: with s the arc parameter's
distance from that end (s = phi + alpha from the +x end, s = 180 + alpha - phi
from the -x end) and L the end's distance from H
(:func:`onefold_cad.geometry.frame_curve.end_distances`),

    x = +-(L - 2 R sin(s/2) sin(s/2 - alpha)),   d = 2 R sin(s/2) cos(s/2 - alpha),

(an identity for cos(phi) -/+ cos(alpha) and sin(phi) + sin(alpha)). Each
point is then exact to a rounding error of its own distance from the end.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.frame_curve import ArcGeometry, FrameCurve
from onefold_cad.geometry.numeric import Array, cross3

__all__ = [
    "ArcFrames",
    "arc_range",
    "arc_points",
    "arc_tangents",
    "division_angles",
    "division_points",
    "end_relative",
]


def end_relative(g: ArcGeometry, s: Array, plus: bool | NDArray[np.bool_]) -> tuple[Array, Array]:
    """In-plane coordinates ``(x, d)`` (units of R) of the arc points at
    distance ``s`` (radians of arc parameter) from the +x end (``plus``) or
    the -x end; x along the f-line from H, d away from it (see the module
    docstring)."""
    half = 0.5 * s
    sn = np.sin(half)
    sn += sn
    ang = half - g.alpha
    r = np.sin(ang)
    r *= sn
    d = np.cos(ang)
    d *= sn
    if plus is True or plus is False:  # one end for all: one branch only
        x = g.l_plus - r if plus else r - g.l_minus
    else:
        x = np.where(plus, g.l_plus - r, r - g.l_minus)
    return x, d


def arc_range(frame: FrameCurve) -> tuple[float, float]:
    """The arc parameter range ``(phi_start, phi_end)`` in radians."""
    a = math.radians(frame.alpha)
    return -a, math.pi + a


def _end_split(g: ArcGeometry, phi: Array) -> tuple[Array, NDArray[np.bool_]]:
    """Distance s of arc parameters ``phi`` from their nearer end, and which."""
    sp = phi + g.alpha
    sm = (math.pi + g.alpha) - phi
    plus = sp <= sm
    return np.where(plus, sp, sm), plus


def arc_points(frame: FrameCurve, phi: ArrayLike) -> Array:
    """Frame-curve points ``(k, 3)`` at arc parameters ``phi`` (radians)."""
    ph = np.asarray(phi, dtype=float)
    g = frame.geometry
    s, plus = _end_split(g, ph)
    x, d = end_relative(g, s, plus)
    r = g.radius
    return np.stack([r * x, (r * g.cos_beta) * d, (r * g.sin_beta) * d], axis=-1)


def arc_tangents(frame: FrameCurve, phi: ArrayLike) -> Array:
    """Derivatives ``dP/dphi`` ``(k, 3)`` of the frame curve (length per radian)."""
    ph = np.asarray(phi, dtype=float)
    g = frame.geometry
    r = frame.radius
    dd = r * np.cos(ph)
    return np.stack([-r * np.sin(ph), dd * g.cos_beta, dd * g.sin_beta], axis=-1)


def division_angles(frame: FrameCurve) -> Array:
    """The ``divisions + 1`` equally spaced arc parameters of the paper's fan."""
    p0, p1 = arc_range(frame)
    n = frame.divisions
    phi = p0 + (p1 - p0) * (np.arange(n + 1) / n)
    phi[-1] = p1
    return phi


def division_points(g: ArcGeometry, n: int) -> Array:
    """In-plane coordinates ``(2, n + 1)`` (rows x and d, units of R) of the
    fan's division points, from the +x end to the -x end: the first half
    measured from the +x end, the rest from the -x end (the same arc
    parameters, k (pi + 2 alpha) / n, each from its nearer end)."""
    steps, front = _end_steps(n)
    m = steps * (0.5 * g.span / n)  # half the distance from the nearer end
    sn = np.sin(m)
    sn += sn
    m -= g.alpha
    p = np.empty((2, n + 1))  # rows r = 2 sin(m) sin(m - alpha), then x; d
    np.sin(m, out=p[0])
    np.cos(m, out=p[1])
    p *= sn
    x = p[0]
    np.subtract(g.l_plus, x[:front], out=x[:front])
    np.subtract(x[front:], g.l_minus, out=x[front:])
    return p


@functools.lru_cache(maxsize=16)
def _end_steps(n: int) -> tuple[Array, int]:
    """Each division point's number of steps from its nearer end of the arc,
    ``(n + 1,)`` floats (read-only; 0, 1, ... from the +x end for the first
    ``front`` points, then ... 1, 0 to the -x end), and ``front``."""
    back = (n + 1) // 2
    front = n + 1 - back
    steps = np.concatenate((np.arange(front), np.arange(back - 1, -1, -1))).astype(float)
    steps.setflags(write=False)
    return steps, front


class ArcFrames:
    """The exact cone's frames as functions of the arc parameter phi (no
    Newton inversion), in the +y side's coordinates: u = (P - A) / |P - A|
    with P the frame arc (:func:`arc_points`), A the apex ``(3,)``."""

    def __init__(self, frame: FrameCurve, apex: Array) -> None:
        self.frame = frame
        self.apex = apex

    def frames(self, phi: Array, curvature: bool = False) -> tuple[Array, ...]:
        """u, e, n ``(k, 3)`` at arc parameters ``phi``; and, if asked, the
        geodesic curvature k = det(v, v', v'') |v|^3 / |v x v'|^3 of u (the k
        of ``r - s k``) and its speed |du/dphi| = |v x v'| / |v|^2 ``(k,)``,
        with v = P - A."""
        # arc_points and arc_tangents, sharing phi's cosine and sine with k
        g = self.frame.geometry
        x, d = end_relative(g, *_end_split(g, phi))
        r = g.radius
        v = np.empty((len(phi), 3))
        np.multiply(x, r, out=v[:, 0])
        np.multiply(d, r * g.cos_beta, out=v[:, 1])
        np.multiply(d, r * g.sin_beta, out=v[:, 2])
        v -= self.apex
        cos, sin = np.cos(phi), np.sin(phi)
        r = self.frame.radius
        dv = np.empty_like(v)
        np.multiply(sin, -r, out=dv[:, 0])
        dd = r * cos
        np.multiply(dd, g.cos_beta, out=dv[:, 1])
        np.multiply(dd, g.sin_beta, out=dv[:, 2])
        w = np.sqrt(np.einsum("ij,ij->i", v, v))
        u = v / w[:, None]
        e = dv - np.einsum("ij,ij->i", dv, u)[:, None] * u
        e /= np.sqrt(np.einsum("ij,ij->i", e, e))[:, None]
        n = cross3(u, e)
        if not curvature:
            return u, e, n
        b = math.radians(self.frame.beta)
        ddv = np.empty_like(v)
        np.multiply(cos, -r, out=ddv[:, 0])
        np.multiply(-r * sin, math.cos(b), out=ddv[:, 1])
        np.multiply(-r * sin, math.sin(b), out=ddv[:, 2])
        vxdv = cross3(v, dv)
        det = np.einsum("ij,ij->i", vxdv, ddv)
        cross = np.sqrt(np.einsum("ij,ij->i", vxdv, vxdv))
        k = det * w**3 / cross**3
        return u, e, n, k, cross / w**2
