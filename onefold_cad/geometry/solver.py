"""The apex: the non-trivial root of the angle condition (paper section 3.2).

S(h), the sum of one side's apex angles with the apex at (0, 0, h), equals
180 deg at h = 0 (the flat, trivial solution), rises to a maximum and falls
towards 0 as h grows. The design is the root past the maximum. The paper
bisects on [l, 2R]; that bracket misses the root for large alpha and beta, so
:func:`solve` finds the root with a safeguarded Newton's method of its own,
which keeps every height it has tried as a bound on the root.
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


#: The lowest apex height searched, as a fraction of the paper's lower bound l:
#: below it S(h) - 180 deg is lost in rounding (S(0) = 180 deg exactly).
_FLOOR = 2.0**-20
#: A Newton step smaller than this (relative to h) on the falling flank of S
#: ends the search: the error it leaves is of the order of its square.
_STEP_TOL = 1e-8
_MAX_EVALUATIONS = 200
#: A measured |S(h) - 180 deg| above this (radians) at the root gets one more
#: Newton step (rare: the search's expanded S(h) loses digits only when the
#: apex is very low).
_POLISH = 1e-13


def _find_root(
    surface: DirectionSurface, frame: FrameCurve, start: float
) -> tuple[float, float, float, int]:
    """The non-trivial root of S(h) = 180 deg: (h, lo, hi, evaluations).

    S(h) > 180 deg exactly on (0, h*), so every evaluation is a lower (S above
    180 deg) or an upper (below) bound of h*. Newton's method from ``start``
    (the paper's lower bound l, or a previous root), kept inside the known
    bounds: before the maximum of S (S above 180 deg and still rising) the
    height doubles; a step out of the bounds bisects them, or, with no lower
    bound yet, goes to a quarter of the upper one. Below ``_FLOOR * l``
    without a lower bound there is no non-trivial root.
    The search ends with a Newton step below ``_STEP_TOL * h`` on the falling
    flank of S, where h* is the only root (:func:`solve` measures the angle
    condition at the result), or when the bounds meet.
    """
    l0 = frame.paper_lower_bound
    floor = _FLOOR * l0
    lo, hi = 0.0, math.inf
    h = start
    for evals in range(1, _MAX_EVALUATIONS + 1):
        s, slope = surface.angle_sum_and_slope(h)
        f = s - _HALF_TURN
        if f > 0.0:
            lo = h
        elif f < 0.0:
            hi = h
        else:
            return h, lo or h, h if math.isinf(hi) else hi, evals
        if lo == 0.0 and hi <= floor:
            raise _no_solution(frame, surface)
        if f > 0.0 and slope >= 0.0:
            new = 2.0 * h  # still on the rising flank of S: climb past its maximum
        else:
            new = h - f / slope if slope != 0.0 else math.nan
        if (slope < 0.0 and abs(new - h) <= _STEP_TOL * h) or hi - lo <= 4e-16 * lo:
            new = min(max(new, lo), hi)
            return new, lo or new, new if math.isinf(hi) else hi, evals
        if not lo < new < hi:
            if math.isinf(hi):
                new = 2.0 * h
            elif lo == 0.0:
                new = 0.25 * hi
            else:
                new = 0.5 * (lo + hi)
        if lo == 0.0 and new < floor:
            new = floor  # below it S(h) - 180 deg is rounding noise
        h = new
    if lo == 0.0 or math.isinf(hi):
        raise _no_solution(frame, surface)
    return h, lo, hi, _MAX_EVALUATIONS


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
    h, lo, hi, evals = _find_root(surface, frame, frame.paper_lower_bound)
    while surface.refine(h):  # a finer rule (exact model): solve again from h
        h, lo, hi, more = _find_root(surface, frame, h)
        evals += more
    surface.set_apex(float(h))
    residual = surface.total_angle - _HALF_TURN
    if abs(residual) > _POLISH:
        # the search's S(h) (expanded in h) and the angle sum set_apex measures
        # (unexpanded) differ by more than rounding: one Newton step on the latter
        h -= residual / surface.angle_sum_and_slope(h)[1]
        surface.set_apex(float(h))
        evals += 1
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
