"""Points of the frame curve (paper section 3.2) in the fold frame.

The arc is parametrised by its polar angle phi about the arc's centre,
phi in [-alpha, 180 + alpha] (radians inside the package): phi = -alpha is the
f-line's +x end, phi = 180 + alpha its -x end. A point at distance d from the
chord maps to (x, d cos(beta), d sin(beta)).

Accuracy near the ends. H may lie arbitrarily close to an end of the f-line,
and the apex then sits about as close above it, so the arc near that end must
be placed to a small fraction of that distance, not to a rounding error of R.
Points are therefore computed from the nearer end: with s the arc parameter's
distance from that end (s = phi + alpha from the +x end, s = 180 + alpha - phi
from the -x end) and L the end's distance from H,

    x = +-(L - 2 R sin(s/2) sin(s/2 - alpha)),   d = 2 R sin(s/2) cos(s/2 - alpha),

(an identity for cos(phi) -/+ cos(alpha) and sin(phi) + sin(alpha)), and L
itself is evaluated in 40-digit decimal arithmetic when it is small. Each point
is then exact to a rounding error of its own distance from the end.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from decimal import Decimal, localcontext

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.params import FrameCurve

__all__ = [
    "ArcGeometry",
    "arc_geometry",
    "arc_range",
    "arc_points",
    "arc_tangents",
    "division_angles",
    "division_points",
    "end_distances",
    "end_relative",
]

Array = NDArray[np.float64]

#: Below this distance from an end (in units of R) the end distance L is
#: evaluated in decimal arithmetic (double precision gives it only to ~3e-16 R).
_PRECISE_END = 1.0 / 16.0
_PI_40 = Decimal("3.1415926535897932384626433832795028841971693993751")


def _sin_cos_deg(deg: float) -> tuple[float, float]:
    """sin and cos of an angle in (0, 90) deg, each to a relative rounding error
    (the smaller one from the complement, 90 - deg, which is exact)."""
    if deg <= 45.0:
        r = math.radians(deg)
        return math.sin(r), math.cos(r)
    r = math.radians(90.0 - deg)
    return math.cos(r), math.sin(r)


def _cos_deg_decimal(deg: float) -> Decimal:
    """cos(deg) for deg in (0, 90), to about 40 digits (Taylor series of the
    sine or cosine of whichever of deg and 90 - deg is at most 45 deg)."""
    with localcontext() as ctx:
        ctx.prec = 45
        d = Decimal(deg)
        use_sin = d > 45
        x = (Decimal(90) - d if use_sin else d) * _PI_40 / 180
        x2 = x * x
        term = x if use_sin else Decimal(1)
        total = term
        k = 1 if use_sin else 0
        while abs(term) > Decimal("1e-44") * abs(total):
            term = -term * x2 / ((k + 1) * (k + 2))
            total += term
            k += 2
        return +total


def end_distances(frame: FrameCurve) -> tuple[float, float]:
    """Distances ``(L+, L-)`` from H to the f-line's +x and -x ends (length),
    R cos(alpha) - h_c and R cos(alpha) + h_c, each to a rounding error of
    itself below R/16 (however close H is to an end), of R above."""
    g = arc_geometry(frame)
    return g.l_plus * frame.radius, g.l_minus * frame.radius


@dataclass(frozen=True)
class ArcGeometry:
    """The frame curve's scalars, lengths in units of the radius R.

    Attributes:
        radius: R (length).
        alpha: alpha (radians).
        sin_alpha, cos_alpha, sin_beta, cos_beta: each to a relative rounding error.
        hc: h_c / R.
        l_plus, l_minus: the end distances L+ / R and L- / R (see :func:`end_distances`).
        span: the arc's central angle, pi + 2 alpha (radians).
    """

    radius: float
    alpha: float
    sin_alpha: float
    cos_alpha: float
    sin_beta: float
    cos_beta: float
    hc: float
    l_plus: float
    l_minus: float
    span: float


def arc_geometry(frame: FrameCurve) -> ArcGeometry:
    """The :class:`ArcGeometry` of ``frame`` (a few microseconds; a decimal
    evaluation of L when H is within R/16 of an end). A validated
    :class:`FrameCurve` keeps the one its validation computed."""
    kept = frame.__dict__.get("_geometry")
    if kept is not None:
        return kept
    sa, ca = _sin_cos_deg(frame.alpha)
    sb, cb = _sin_cos_deg(frame.beta)
    r = frame.radius
    hc = frame.h_c / r
    lp, lm = ca - hc, ca + hc
    if min(lp, lm) < _PRECISE_END:
        with localcontext() as ctx:
            ctx.prec = 45
            c = _cos_deg_decimal(frame.alpha) * Decimal(r)
            lp = float((c - Decimal(frame.h_c)) / Decimal(r))
            lm = float((c + Decimal(frame.h_c)) / Decimal(r))
    a = math.radians(frame.alpha)
    return ArcGeometry(r, a, sa, ca, sb, cb, hc, lp, lm, math.pi + 2.0 * a)


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
    g = arc_geometry(frame)
    s, plus = _end_split(g, ph)
    x, d = end_relative(g, s, plus)
    r = g.radius
    return np.stack([r * x, (r * g.cos_beta) * d, (r * g.sin_beta) * d], axis=-1)


def arc_tangents(frame: FrameCurve, phi: ArrayLike) -> Array:
    """Derivatives ``dP/dphi`` ``(k, 3)`` of the frame curve (length per radian)."""
    ph = np.asarray(phi, dtype=float)
    g = arc_geometry(frame)
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
