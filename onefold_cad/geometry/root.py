"""The root search of the angle condition: F(h) = S(h) - pi = 0 past the maximum.

F(0) = 0 and F rises from h = 0 (its slope there is sin(beta) (1/L+ + 1/L-)),
then falls to -pi, so F > 0 below the root and F < 0 above it: every
evaluation is a lower or an upper bound (should F be positive above a negative
value, the larger root is the one sought). Heights are in units of R.

The search evaluates several heights at once (one numpy pass each):

1. a grid of 12 heights around the paper's lower bound l, where the root of
   most designs lies; when it does not, grids further down or up, each
   spanning the square of the last one's ratio (no floor, no ceiling but the
   range of doubles), then grids inside a wide bracket;
2. an inverse interpolation (degree 5) through the three heights on each
   side of the root;
3. 5 heights spaced delta around that estimate, whose quartic inverse
   interpolant is accurate to about (3 delta)^5 times the inverse function's
   fifth derivative (delta = 5e-5 h: far below rounding), repeated until the
   5 heights straddle the root and the estimate stays among them.

An evaluation within 4 rounding bounds of 0 is repeated with the accurate
evaluation (:meth:`DirectionSurface.excess_accurate`); if that too is zero
within its error, the height is a root.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.surface import EPS, DirectionSurface

__all__ = [
    "GRID",
    "GRID_HEIGHTS",
    "SPACING",
    "Search",
    "SearchFailed",
    "find_root",
    "neville",
    "neville5",
    "neville6",
    "slope5",
]

#: First probe, as multiples of the paper's lower bound l: the root lies in
#: [1.09 l, 2 l] for beta >= 30 deg and H not near an end. Twelve heights
#: (ratio 1.084) and a sextic through the six nearest the root put the first
#: estimate within the 5-height probe's reach (1e-4) for every row of the
#: paper's Table 1 and for ~3 designs in 4 (eight heights and a cubic: ~1 in
#: 3), saving a whole probe at the cost of four heights' elementwise work.
GRID = tuple(0.95 * (2.3 / 0.95) ** (j / 11.0) for j in range(12))
#: :data:`GRID` as an array.
GRID_HEIGHTS = np.array(GRID)
#: The 5-height probes' spacing around an estimate (relative).
SPACING = 5e-5
#: Heights (units of R) outside which no root is searched.
_H_MIN, _H_MAX = 1e-280, 1e12


class SearchFailed(Exception):
    """No sign change of S - 180 deg was found (a design beyond double precision)."""


def neville(fs: list[float], hs: list[float]) -> float:
    """The polynomial through (fs[i], hs[i]) evaluated at 0 (inverse interpolation)."""
    if len(fs) == 6:
        return neville6(fs, hs)
    if len(fs) == 5:
        return neville5(fs, hs)
    p = list(hs)
    n = len(fs)
    for k in range(1, n):
        for i in range(n - k):
            den = fs[i + k] - fs[i]
            if den == 0.0:
                return math.nan
            p[i] = (fs[i + k] * p[i] - fs[i] * p[i + 1]) / den
    return p[0]


def neville6(fs: list[float], hs: list[float]) -> float:
    """:func:`neville` for 6 points (the first estimate's), written out."""
    f0, f1, f2, f3, f4, f5 = fs
    p0, p1, p2, p3, p4, p5 = hs
    try:
        p0 = (f1 * p0 - f0 * p1) / (f1 - f0)
        p1 = (f2 * p1 - f1 * p2) / (f2 - f1)
        p2 = (f3 * p2 - f2 * p3) / (f3 - f2)
        p3 = (f4 * p3 - f3 * p4) / (f4 - f3)
        p4 = (f5 * p4 - f4 * p5) / (f5 - f4)
        p0 = (f2 * p0 - f0 * p1) / (f2 - f0)
        p1 = (f3 * p1 - f1 * p2) / (f3 - f1)
        p2 = (f4 * p2 - f2 * p3) / (f4 - f2)
        p3 = (f5 * p3 - f3 * p4) / (f5 - f3)
        p0 = (f3 * p0 - f0 * p1) / (f3 - f0)
        p1 = (f4 * p1 - f1 * p2) / (f4 - f1)
        p2 = (f5 * p2 - f2 * p3) / (f5 - f2)
        p0 = (f4 * p0 - f0 * p1) / (f4 - f0)
        p1 = (f5 * p1 - f1 * p2) / (f5 - f1)
        return (f5 * p0 - f0 * p1) / (f5 - f0)
    except ZeroDivisionError:  # two equal values: no interpolant
        return math.nan


def neville5(fs: list[float], hs: list[float]) -> float:
    """:func:`neville` for 5 points (the final probe's), written out: the same
    operations in the same order, without the loops' indexing."""
    f0, f1, f2, f3, f4 = fs
    p0, p1, p2, p3, p4 = hs
    try:
        p0 = (f1 * p0 - f0 * p1) / (f1 - f0)
        p1 = (f2 * p1 - f1 * p2) / (f2 - f1)
        p2 = (f3 * p2 - f2 * p3) / (f3 - f2)
        p3 = (f4 * p3 - f3 * p4) / (f4 - f3)
        p0 = (f2 * p0 - f0 * p1) / (f2 - f0)
        p1 = (f3 * p1 - f1 * p2) / (f3 - f1)
        p2 = (f4 * p2 - f2 * p3) / (f4 - f2)
        p0 = (f3 * p0 - f0 * p1) / (f3 - f0)
        p1 = (f4 * p1 - f1 * p2) / (f4 - f1)
        return (f4 * p0 - f0 * p1) / (f4 - f0)
    except ZeroDivisionError:  # two equal values: no interpolant
        return math.nan


def slope5(hs: list[float], fs: list[float], x: float) -> float:
    """dF/dh at x from 5 equally spaced heights (finite differences about the
    middle one, to fourth order: x lies within the stencil)."""
    f0, f1, f2, f3, f4 = fs
    step = 0.25 * (hs[4] - hs[0])
    d1 = (f0 - 8.0 * f1 + 8.0 * f3 - f4) / (12.0 * step)
    d2 = (-f0 + 16.0 * f1 - 30.0 * f2 + 16.0 * f3 - f4) / (12.0 * step * step)
    d3 = (-f0 + 2.0 * f1 - 2.0 * f3 + f4) / (2.0 * step**3)
    y = x - hs[2]
    return d1 + y * (d2 + 0.5 * y * d3)


class Search:
    """The evaluations made and the bracket (lo, hi) they give.

    Attributes:
        surface: the direction-surface searched.
        bound: the rounding bound of its fast evaluation (radians).
        values: every evaluated height -> F there, in the order evaluated.
        lo, flo: the largest height with F > 0 and F there (0, 0 when none).
        hi, fhi: the smallest height above lo with F < 0 (inf, -pi when none).
        exact: a height where F is zero within its error, if one was met.
        evals: how many heights were evaluated.
    """

    __slots__ = ("surface", "bound", "values", "lo", "flo", "hi", "fhi", "exact", "evals")

    def __init__(self, surface: DirectionSurface) -> None:
        self.surface = surface
        self.bound = surface.excess_bound()
        self.values: dict[float, float] = {}
        self.lo, self.flo = 0.0, 0.0
        self.hi, self.fhi = math.inf, -math.pi
        self.exact: float | None = None
        self.evals = 0

    def probe(self, heights: list[float] | NDArray[np.float64]) -> list[float]:
        """F at ``heights`` (several at once), recorded; returns the values."""
        n = len(heights)
        if n == 1:
            fs = [self.surface.excess(float(heights[0]))]
        else:
            fs = self.surface.excesses(np.asarray(heights, dtype=float)).tolist()
        if not isinstance(heights, list):
            heights = heights.tolist()
        self.evals += n
        small = 4.0 * self.bound
        lo, flo, hi, fhi = self.lo, self.flo, self.hi, self.fhi
        moved = False
        for i, h in enumerate(heights):
            f = fs[i]
            if not (f > small or f < -small):
                f = fs[i] = self._near_zero(h, f, fs)
            if f > 0.0:
                if h > lo:
                    lo, flo = h, f
                    moved = moved or h >= hi
            elif lo < h < hi:
                hi, fhi = h, f
        values = self.values
        values.update(zip(heights, fs, strict=True))
        if moved:  # a positive value above the old upper bound: the larger root
            hi, fhi = math.inf, -math.pi
            for h, f in values.items():
                if f <= 0.0 and lo < h < hi:
                    hi, fhi = h, f
        if self.exact is not None and self.exact < lo:
            # S above 180 deg higher up: a zero within rounding below that is
            # on the rising branch (near the trivial root h = 0), not the root
            self.exact = None
        self.lo, self.flo, self.hi, self.fhi = lo, flo, hi, fhi
        return fs

    def _near_zero(self, h: float, f: float, probe: list[float]) -> float:
        """F at h when the fast evaluation is within rounding of 0 (or not a number).

        Among values of the same probe a million times larger, h is a root to
        within rounding; otherwise (max S - pi itself tiny) F is evaluated to
        a relative accuracy."""
        if not math.isfinite(f):
            raise SearchFailed(f"S(h) is not finite at h={h!r} R")
        if max(map(abs, probe)) > 4e6 * self.bound:
            if self.exact is None or abs(f) < abs(self.probe_value(self.exact)):
                self.exact = h
            return f
        f, err = self.surface.excess_accurate(h)
        self.evals += 1
        if abs(f) <= err:
            self.exact = h
        return f

    def probe_value(self, h: float) -> float:
        """F at an evaluated height."""
        return self.values.get(h, math.inf)

    def around(self) -> tuple[list[float], list[float]]:
        """The three evaluated heights nearest below the root and above it:
        ``(F values, heights)``."""
        hs = sorted(self.values)
        k = hs.index(self.lo)
        pick = hs[max(k - 2, 0) : k + 4]
        values = self.values
        return [values[h] for h in pick], pick


def find_root(surface: DirectionSurface, l0: float) -> tuple[float, Search, float]:
    """The root (units of R), the search, and dF/dh there (per unit of R).

    Raises:
        SearchFailed: no height with S above or below 180 deg was found.
    """
    s = Search(surface)
    s.probe(GRID_HEIGHTS * l0)
    span = 16.0
    for _ in range(60):
        if s.exact is not None or (s.lo > 0.0 and s.hi < math.inf):
            break
        if s.lo == 0.0:  # the root lies below every height tried
            top = min(s.values)
            if top < _H_MIN:
                raise SearchFailed("no height with S above 180 deg")
            s.probe([max(top * span ** (-j / 8.0), 0.5 * _H_MIN) for j in range(1, 9)])
        else:
            if s.lo > _H_MAX:
                raise SearchFailed("no height with S below 180 deg")
            s.probe([min(s.lo * span ** (j / 8.0), 2.0 * _H_MAX) for j in range(1, 9)])
        span = min(span * span, 1e30)
    else:
        raise SearchFailed("no sign change of S - 180 deg found")
    while s.exact is None and s.hi > 1.2 * s.lo:  # a geometric grid inside a wide bracket
        lo, hi = s.lo, s.hi
        s.probe([lo * (hi / lo) ** (j / 9.0) for j in range(1, 9)])
    if s.exact is not None:
        return s.exact, s, _slope(s, s.exact)
    fs, hs = s.around()
    estimate = neville(fs, hs)
    if not s.lo < estimate < s.hi:
        estimate = 0.5 * (s.lo + s.hi)
    delta = SPACING * estimate
    for _ in range(60):
        delta = max(min(delta, 0.25 * (s.hi - s.lo)), 4.0 * EPS * estimate)
        hs = [estimate + delta * j for j in (-2, -1, 0, 1, 2)]
        fs = s.probe(hs)
        if s.exact is not None:
            return s.exact, s, slope5(hs, fs, s.exact)
        new = neville(fs, hs)
        if not s.lo <= new <= s.hi:
            new = 0.5 * (s.lo + s.hi)
        if fs[0] > 0.0 > fs[4] and abs(new - estimate) <= 2.0 * delta <= 4.0 * SPACING * new:
            return new, s, slope5(hs, fs, new)
        # the root's position is known only to the rounding of F over its slope
        noise = 4.0 * s.bound * abs((hs[4] - hs[0]) / (fs[4] - fs[0]))
        if s.hi - s.lo <= max(8.0 * EPS * estimate, noise):
            return new, s, _slope(s, new)
        delta = min(max(abs(new - estimate), 0.5 * delta), SPACING * new)
        estimate = new
    raise SearchFailed("the root search did not converge")


def _slope(s: Search, h: float) -> float:
    """dF/dh (per unit of R) at h, analytically (one more evaluation)."""
    s.evals += 1
    return s.surface.excess_and_slope(h)[1]
