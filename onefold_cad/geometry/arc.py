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

The paper's fan divides the arc into equal steps of arc parameter; an
:class:`ArcSpacing` places a fan's division points elsewhere on the same
arc (a graded fan, narrow beside the ends: :meth:`ArcSpacing.graded`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.frame_curve import ArcGeometry, FrameCurve
from onefold_cad.geometry.numeric import Array, cross3

__all__ = [
    "ArcFrames",
    "ArcSpacing",
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


def division_points(g: ArcGeometry, n: int, spacing: ArcSpacing | None = None) -> Array:
    """In-plane coordinates ``(2, n + 1)`` (rows x and d, units of R) of the
    fan's division points, from the +x end to the -x end: the first half
    measured from the +x end, the rest from the -x end (the same arc
    parameters, k (pi + 2 alpha) / n, each from its nearer end); with a
    ``spacing`` (of ``n`` divisions), at its arc parameters instead."""
    if spacing is None:
        steps, front = _end_steps(n)
        per_span = float(n)
    else:
        steps, front, per_span = spacing.steps, spacing.front, spacing.per_span
    m = steps * (0.5 * g.span / per_span)  # half the distance from the nearer end
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


@dataclass(frozen=True, eq=False)
class ArcSpacing:
    """Where a paper fan's ``divisions + 1`` division points lie on the frame
    arc: point k at ``steps[k] * span / per_span`` of arc parameter from its
    nearer end (span = pi + 2 alpha, the whole arc), the first ``front``
    points from the +x end, the others from the -x end (see the module notes:
    each point exact to a rounding error of its own distance from its end).

    Attributes:
        steps: ``(divisions + 1,)`` read-only floats, 0 at both ends,
            increasing over the first ``front`` points and decreasing after.
        front: how many points are measured from the +x end.
        per_span: the span in the units of ``steps``.
    """

    steps: Array
    front: int
    per_span: float

    @property
    def divisions(self) -> int:
        """The number of triangles (wedges) of the fan."""
        return len(self.steps) - 1

    @classmethod
    def uniform(cls, n: int) -> ArcSpacing:
        """The paper's equal steps: :class:`PaperFan` without a spacing, to the bit."""
        steps, front = _end_steps(n)
        return cls(steps, front, float(n))

    @classmethod
    def from_widths(cls, widths: ArrayLike) -> ArcSpacing:
        """The spacing whose wedges have the arc-parameter ``widths`` ``(n,)``
        (positive, any unit: scaled to the span), each point placed by summing
        the widths from its nearer end (the uniform split of :meth:`uniform`)."""
        w = np.asarray(widths, dtype=float)
        if w.ndim != 1 or len(w) < 1 or not np.all(w > 0.0) or not np.all(np.isfinite(w)):
            raise InvalidParameterError("spacing", "the wedge widths must be positive and finite")
        n = len(w)
        back = (n + 1) // 2
        front = n + 1 - back
        head = np.concatenate(([0.0], np.cumsum(w[: front - 1])))
        tail = np.concatenate(([0.0], np.cumsum(w[::-1][: back - 1])))[::-1]
        steps = np.concatenate((head, tail))
        steps.setflags(write=False)
        return cls(steps, front, float(np.add.reduce(w)))

    @classmethod
    def graded(cls, n: int, first: tuple[float, float], ratio: float) -> ArcSpacing:
        """A fan of ``n`` wedges narrow beside the arc's ends and even between:
        wedge i (from the +x end) has the width min(f+ r^i, f- r^(n-1-i), c)
        (fractions of the span), with ``first`` = (f+, f-) the widths beside
        the +x and the -x end, r = ``ratio`` > 1 their growth, and the cap c
        the width that makes the widths add up to the span. Where the growth
        cannot fill the span (f r^i too small), r is raised until it can (a
        fan of two wedges has them in the ratio f+ : f-).
        A first width above the cap is the cap (the fan is then even there)."""
        fp, fm = first
        if n < 1 or not (fp > 0.0 and fm > 0.0) or not ratio > 1.0:
            raise InvalidParameterError(
                "spacing", "a graded spacing needs n >= 1, first widths > 0 and a ratio > 1"
            )
        if n <= 2:  # no wedge between the two ends: their widths in the ratio f+ : f-
            return cls.from_widths([fp, fm][:n] if n == 2 else [1.0])
        i = np.arange(n, dtype=float)

        def growth(r: float) -> Array:
            return np.minimum(fp * r**i, fm * r ** (n - 1.0 - i))

        g = growth(ratio)
        while float(np.add.reduce(g)) < 1.0:
            ratio *= 1.25
            g = growth(ratio)
        return cls.from_widths(np.minimum(g, _cap(g, 1.0)))


def _cap(g: Array, total: float) -> float:
    """The c with sum(min(g_i, c)) = ``total`` (<= sum g)."""
    gs = np.sort(g)
    below = np.concatenate(([0.0], np.cumsum(gs)[:-1]))  # sum of the k smallest
    k = np.arange(len(gs))
    c = (total - below) / (len(gs) - k)  # the cap if the k smallest stay below it
    ok = (c >= np.concatenate(([0.0], gs[:-1]))) & (c <= gs)
    return float(c[np.flatnonzero(ok)[0]])


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
