"""The frame curve of paper section 3.2: its frozen, validated inputs and the
scalars every point of it is computed from (:class:`ArcGeometry`).

Angles are in degrees at this edge of the API (radians in :class:`ArcGeometry`);
lengths are in the design's unit.

Accuracy near the ends. H may lie arbitrarily close to an end of the f-line,
and the apex then sits about as close above it, so the arc near that end must
be placed to a small fraction of that distance, not to a rounding error of R:
the end distances L+ and L- are evaluated in 40-digit decimal arithmetic when
they are small (:func:`end_distances`); :mod:`onefold_cad.geometry.arc` places
the points from the nearer end.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, replace
from decimal import Decimal, localcontext
from functools import cached_property
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.checks import finite, integer_at_least, length, open_interval, shown

__all__ = [
    "ArcGeometry",
    "FrameCurve",
    "MAX_DESIGN_DIVISIONS",
    "MAX_DIVISIONS",
    "MIN_ANGLE_DEG",
    "arc_geometry",
    "check_design_divisions",
    "end_distances",
    "half_chord",
]

#: Smallest alpha and beta (deg). The construction squares them in radians
#: (sin^2, 1 - cos); from 1e-100 deg those squares stay normal doubles
#: (3e-204 > 2.2e-308), below it they underflow and the angle is 0 in effect
#: (beta = 5e-324 deg is exactly 0 in radians).
MIN_ANGLE_DEG = 1e-100

#: Upper limit on ``divisions`` of a :class:`FrameCurve` (what ``solve`` and
#: ``fold`` accept: both stay well under a second there; the solver's own
#: convergence studies use it). A :class:`~onefold_cad.design.Design` (the
#: CLI, templates and every file) takes at most :data:`MAX_DESIGN_DIVISIONS`.
MAX_DIVISIONS = 100_000
#: Upper limit on ``divisions`` in a design. The fan's triangles span at most
#: 360/10 000 deg of the arc each, so its chords stay within
#: R (1 - cos(pi / 10 000)) < 5e-8 R of the arc: past 10 000 the paper model
#: is the exact cone to within the 1e-7 tolerance (use ``model='exact'`` for
#: the limit), while the flat pattern, DXF and STEP grow with every division
#: (at the cap solve + fold + flat pattern + DXF take about a second,
#: docs/reliability.md).
MAX_DESIGN_DIVISIONS = 10_000


def half_chord(alpha: float, radius: float) -> float:
    """Half the f-line length, R cos(alpha) (``alpha`` in deg, length as
    ``radius``), to a relative rounding error: above 45 deg as sin(90 -
    alpha), the difference being exact."""
    c = math.cos(math.radians(alpha)) if alpha <= 45.0 else math.sin(math.radians(90.0 - alpha))
    return radius * c


@dataclass(frozen=True)
class FrameCurve:
    """The frame curve of paper section 3.2 (one side; the other is its mirror).

    A circular arc of radius ``radius`` and central angle 180 + 2*alpha whose
    chord (the f-line, length 2 R cos(alpha)) lies on the x axis, tilted about
    the x axis so that its plane makes the angle ``beta`` with the y axis.

    Attributes:
        alpha: arc opening in degrees, in (0, 90), at least
            :data:`MIN_ANGLE_DEG` (1e-100).
        beta: tilt of the arc's plane from the y axis in degrees, in (0, 90),
            at least :data:`MIN_ANGLE_DEG`.
        h_c: offset of H from the f-line midpoint (length); positive puts H on
            the +x side of the midpoint. |h_c| < radius * cos(alpha).
        radius: arc radius R (length), in [1e-30, 1e30] (see
            :data:`onefold_cad.geometry.checks.MAX_LENGTH`). The paper's
            H_c values assume 100.
        divisions: number of triangles of the paper model's fan, in
            [1, :data:`MAX_DIVISIONS`] = [1, 100 000]; a design takes at
            most :data:`MAX_DESIGN_DIVISIONS` = 10 000.
    """

    alpha: float
    beta: float
    h_c: float = 0.0
    radius: float = 100.0
    divisions: int = 90

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "alpha", _angle("alpha", self.alpha))
        set_(self, "beta", _angle("beta", self.beta))
        set_(self, "radius", length("radius", self.radius))
        set_(self, "h_c", finite("h_c", self.h_c))
        set_(self, "divisions", _divisions(self.divisions))
        # H strictly inside the f-line, decided on the end distances the solver
        # folds with, R cos(alpha) -+ h_c, each to a rounding error of itself
        # (40 digits near an end): a double cos(alpha) is off by up to 8 % within
        # 1e-14 deg of 90, which let through h_c the solver then refused.
        g = self.geometry
        if not min(g.l_plus, g.l_minus) > 0.0:
            half = 0.5 * (g.l_plus + g.l_minus) * self.radius
            raise InvalidParameterError(
                "h_c",
                f"H must lie strictly inside the f-line: |h_c| < radius*cos(alpha) = "
                f"{half:.6g}, i.e. h_c in ({-half:.6g}, {half:.6g}), got {shown(self.h_c)}",
            )

    @cached_property
    def geometry(self) -> ArcGeometry:
        """The arc's scalars (:func:`arc_geometry`), computed once: validation
        needs them, and every direction-surface starts from them."""
        return arc_geometry(self)

    @property
    def half_chord(self) -> float:
        """Half the f-line length, R cos(alpha) (length): :func:`half_chord`."""
        return half_chord(self.alpha, self.radius)

    @property
    def paper_lower_bound(self) -> float:
        """The paper's lower bisection bound l = (R + R sin alpha) sin beta (length)."""
        a, b = math.radians(self.alpha), math.radians(self.beta)
        return (self.radius + self.radius * math.sin(a)) * math.sin(b)

    def with_changes(self, **changes: Any) -> FrameCurve:
        """Return a copy with some fields replaced (validated again)."""
        return replace(self, **changes)


def _divisions(value: object) -> int:
    """``divisions`` checked against [1, MAX_DIVISIONS], with the cap's reason."""
    n = integer_at_least("divisions", value, 1, None if _over_cap(value) else MAX_DIVISIONS)
    if n > MAX_DIVISIONS:
        raise InvalidParameterError(
            "divisions",
            f"must be an integer in [1, {MAX_DIVISIONS}], got {n} (a design takes at most "
            f"{MAX_DESIGN_DIVISIONS}: there the fan is within 5e-8 R of the exact cone; use "
            "the exact model for finer)",
        )
    return n


def _over_cap(value: object) -> bool:
    """Whether ``value`` is a number above MAX_DIVISIONS (to explain the cap)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    number = float(value)
    return math.isfinite(number) and number > MAX_DIVISIONS


def _angle(name: str, value: object) -> float:
    """alpha or beta checked against (0, 90) deg and the underflow floor."""
    x = open_interval(name, value, 0.0, 90.0, " deg")
    if x < MIN_ANGLE_DEG:
        raise InvalidParameterError(
            name,
            f"must be in (0, 90) deg and at least {MIN_ANGLE_DEG:g} deg (its square in radians "
            f"must not underflow), got {shown(x)}",
        )
    return x


def check_design_divisions(frame: FrameCurve) -> None:
    """Raise unless ``frame.divisions`` <= MAX_DESIGN_DIVISIONS (called by
    :class:`~onefold_cad.design.Design`; names 'frame.divisions')."""
    if frame.divisions > MAX_DESIGN_DIVISIONS:
        raise InvalidParameterError(
            "frame.divisions",
            f"must be an integer in [1, {MAX_DESIGN_DIVISIONS}] in a design, got "
            f"{frame.divisions} (at {MAX_DESIGN_DIVISIONS} the fan is within 5e-8 R of the "
            "exact cone, and the flat pattern and STEP grow with every division; use the "
            "exact model for finer)",
        )


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
    evaluation of L when H is within R/16 of an end; :attr:`FrameCurve.geometry`
    keeps the one its validation computed)."""
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


def end_distances(frame: FrameCurve) -> tuple[float, float]:
    """Distances ``(L+, L-)`` from H to the f-line's +x and -x ends (length),
    R cos(alpha) - h_c and R cos(alpha) + h_c, each to a rounding error of
    itself below R/16 (however close H is to an end), of R above."""
    g = frame.geometry
    return g.l_plus * frame.radius, g.l_minus * frame.radius
