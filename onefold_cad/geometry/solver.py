"""The apex: the non-trivial root of the angle condition (paper section 3.2).

S(h), the sum of one side's apex angles with the apex at (0, 0, h), equals
180 deg at h = 0 (the flat, trivial solution), rises to a maximum and falls
towards 0 as h grows. The design is the root past the maximum. The paper
bisects on [l, 2R]; that bracket misses the root for large alpha and beta, so
:func:`solve` brackets the root itself and refines it with Brent's method.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import NoSolutionError
from onefold_cad.geometry.cone import DirectionSurface, ExactCone, PaperFan
from onefold_cad.geometry.params import FrameCurve, Model

__all__ = ["Solution", "solve", "make_direction_surface"]

_HALF_TURN = math.pi


@dataclass(frozen=True, eq=False)
class Solution:
    """The solved direction-surface of one design.

    Attributes:
        frame: the frame curve solved for.
        model: PAPER (triangle fan) or EXACT (continuous cone).
        apex_height: h, the apex's height above H (length).
        surface: the direction-surface with its apex fixed (maps flat angles
            to ruling directions); shared by both sides (the -y side is the
            mirror image in the xz-plane).
        angle_sum_deg: the sum of apex angles around the apex, both sides (deg).
        angle_condition_error_deg: |angle_sum_deg - 360| (deg).
        time_direction_surface: wall time spent solving (s).
        bracket: the (lo, hi) heights the root was refined in (length).
        evaluations: how many times S(h) was evaluated.
    """

    frame: FrameCurve
    model: Model
    apex_height: float
    surface: DirectionSurface
    angle_sum_deg: float
    angle_condition_error_deg: float
    time_direction_surface: float
    bracket: tuple[float, float]
    evaluations: int

    @property
    def apex(self) -> NDArray[np.float64]:
        """The apex A = (0, 0, h) ``(3,)``."""
        return np.array([0.0, 0.0, self.apex_height])

    @property
    def direction_vectors(self) -> NDArray[np.float64] | None:
        """Paper model: the ``(divisions + 1, 3)`` unit direction-vectors of the
        +y side, from the +x end of the f-line to the -x end; None for EXACT."""
        return self.surface.directions if isinstance(self.surface, PaperFan) else None

    @property
    def gammas_deg(self) -> NDArray[np.float64] | None:
        """Paper model: the ``(divisions,)`` apex angles gamma_i (deg); None for EXACT."""
        if isinstance(self.surface, PaperFan) and self.surface.gammas is not None:
            return np.degrees(self.surface.gammas)
        return None


def make_direction_surface(frame: FrameCurve, model: Model | str) -> DirectionSurface:
    """The (unsolved) direction-surface of ``frame`` in the chosen model."""
    m = Model.parse(model)
    return PaperFan(frame) if m is Model.PAPER else ExactCone(frame)


# Heights tried at once to bracket the root: l * 2**(k/2), k = -40 .. 16.
_GRID = 2.0 ** (np.arange(-40, 17) / 2.0)
_GRID_ELEMENTS = 60_000  # above this many (heights x triangles), bracket sequentially


def _no_solution(frame: FrameCurve, surface: DirectionSurface) -> NoSolutionError:
    hint = "increase alpha or beta (allowed: (0, 90) deg)"
    if isinstance(surface, PaperFan):
        hint += (
            f" or divisions (the paper model's fan of {frame.divisions} triangles is too coarse)"
        )
    return NoSolutionError(
        "no non-trivial apex: the sum of apex angles never exceeds 180 deg for "
        f"alpha={frame.alpha:g} deg, beta={frame.beta:g} deg, h_c={frame.h_c:g}, "
        f"radius={frame.radius:g}, divisions={frame.divisions}; {hint}"
    )


def _bracket(surface: DirectionSurface, frame: FrameCurve) -> tuple[float, float, int]:
    """Heights (lo, hi) with S(lo) > 180 deg > S(hi), past the maximum of S."""
    l0 = frame.paper_lower_bound
    size = len(getattr(surface, "points", ())) or len(getattr(surface, "_p", ()))
    if size * len(_GRID) <= _GRID_ELEMENTS:
        heights = l0 * _GRID
        above = surface.angle_sums(heights) > _HALF_TURN
        if not above.any():
            raise _no_solution(frame, surface)
        k = int(np.flatnonzero(above)[-1])
        if k + 1 < len(heights):
            return float(heights[k]), float(heights[k + 1]), len(heights)
        lo, evals = float(heights[k]), len(heights)
    else:
        lo, evals = l0, 1
        if not surface.angle_sum(lo) > _HALF_TURN:
            hi = lo
            while hi > 1e-9 * frame.radius:
                lo = hi / 1.5
                evals += 1
                if surface.angle_sum(lo) > _HALF_TURN:
                    return lo, hi, evals
                hi = lo
            raise _no_solution(frame, surface)
    hi = 2.0 * lo
    while surface.angle_sum(hi) > _HALF_TURN:  # S -> 0 as h -> infinity
        evals += 1
        lo, hi = hi, 2.0 * hi
    return lo, hi, evals + 1


def _newton(surface: DirectionSurface, lo: float, hi: float) -> tuple[float, int]:
    """Root of S(h) = 180 deg in [lo, hi]: Newton's method, kept in the bracket."""
    h = 0.5 * (lo + hi)
    for count in range(1, 100):
        f, slope = surface.angle_sum_and_slope(h)
        f -= _HALF_TURN
        if f > 0.0:
            lo = h
        else:
            hi = h
        if f == 0.0:
            return h, count
        new = h - f / slope if slope != 0.0 else h
        if abs(new - h) <= 1e-15 * h and lo <= new <= hi:
            return new, count
        if not lo < new < hi:
            new = 0.5 * (lo + hi)  # Newton left the bracket: bisect instead
        h = new
    return h, 100


def solve(frame: FrameCurve, model: Model | str = Model.EXACT) -> Solution:
    """Find the apex that satisfies the angle condition (360 deg around A).

    Args:
        frame: the validated frame curve.
        model: 'exact' (continuous cone) or 'paper' (triangle fan).

    Returns:
        The :class:`Solution`, with the angle-condition error measured at the
        returned apex.

    Raises:
        NoSolutionError: S(h) never exceeds 180 deg, so only the flat sheet
            satisfies the angle condition.
    """
    m = Model.parse(model)
    t0 = time.perf_counter()
    surface = make_direction_surface(frame, m)
    lo, hi, evals = _bracket(surface, frame)
    h, steps = _newton(surface, lo, hi)
    evals += steps
    surface.set_apex(float(h))
    total = 2.0 * math.degrees(surface.total_angle)
    elapsed = time.perf_counter() - t0
    return Solution(
        frame=frame,
        model=m,
        apex_height=float(h),
        surface=surface,
        angle_sum_deg=total,
        angle_condition_error_deg=abs(total - 360.0),
        time_direction_surface=elapsed,
        bracket=(lo, hi),
        evaluations=evals,
    )
