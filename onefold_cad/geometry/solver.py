"""The apex: the non-trivial root of the angle condition (paper section 3.2).

S(h), the sum of one side's apex angles with the apex at (0, 0, h), equals
180 deg at h = 0 (the flat, trivial solution), rises (its slope there is
sin(beta) (1/L+ + 1/L-) > 0, L+- the distances from H to the f-line's ends)
and falls towards 0 as h grows, so a root past the maximum always exists,
except for the paper model's single triangle, whose apex angle is below
180 deg for every h > 0. The paper bisects on [l, 2R]; that bracket misses
the root for large alpha and beta and for H near an end of the f-line, so
:func:`solve` brackets for itself (relative to l, and as far down as the
root may lie: there is no fixed floor) and refines by inverse polynomial
interpolation through several heights evaluated at once.

Every returned root is verified: the angle sum is evaluated again at the
returned height by an independent computation (the fan's apex angles from
the unit direction-vectors; the cone's integral with every quadrature panel
halved), and ``angle_condition_error_deg`` is that evaluation's deviation
from 360 deg plus a bound on its own error. Where that cannot be brought
within 1e-9 deg, :class:`NoSolutionError` says why.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from onefold_cad.choices import Model
from onefold_cad.errors import InvalidParameterError, NoSolutionError
from onefold_cad.geometry.arc import ArcSpacing
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.frame_curve import FrameCurve
from onefold_cad.geometry.root import Search, SearchFailed, find_root
from onefold_cad.geometry.surface import DirectionSurface

__all__ = ["Solution", "solve", "make_direction_surface", "ANGLE_TOLERANCE_DEG"]

#: The angle condition every returned solution meets: |sum of apex angles - 360| (deg).
ANGLE_TOLERANCE_DEG = 1e-9
#: The same per side, in radians: |S(h) - pi|.
_TOL = math.radians(ANGLE_TOLERANCE_DEG) / 2.0
#: An apex height known less precisely than this (relative) is reported as a warning.
_WARN_REL = 1e-9
_EPS = 2.0**-52


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
        angle_sum_deg: the sum of apex angles around the apex, both sides,
            evaluated independently of the search at ``apex_height`` (deg).
        angle_condition_error_deg: a bound on |sum - 360| at ``apex_height``:
            the verifying evaluation's deviation plus a bound on its own
            rounding (and, exact model, quadrature) error (deg); at most
            :data:`ANGLE_TOLERANCE_DEG`.
        time_direction_surface: wall time spent solving (s).
        bracket: heights (lo, hi) with S above / below 180 deg between which
            the root was refined (length).
        evaluations: how many times S(h) was evaluated.
        apex_height_error: a bound on |apex_height - h*|, h* the exact root for
            these inputs (length): the verified angle error over |dS/dh|.
        ds_dh: dS/dh at the root (one side's angle sum, radians per length; < 0).
        warnings: what the user must know about this solution (one line each).
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
    apex_height_error: float = 0.0
    ds_dh: float = math.nan
    warnings: tuple[str, ...] = ()

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

    @cached_property
    def _s_max(self) -> tuple[float, float]:
        h, value = _s_max(self.surface, self.apex_height / self.frame.radius)
        return h * self.frame.radius, value

    @property
    def s_max_minus_pi(self) -> float:
        """max over h of S(h) - pi (radians, one side): how far the angle sum
        rises above 180 deg before it falls to the root, to its evaluation's
        error bound plus ~1e-14 of itself (see :func:`_s_max`). Tiny values
        (beta near 0) mean an ill-determined apex height. Computed on first
        access (a few ms to 0.2 s)."""
        return self._s_max[1]

    @property
    def s_max_height(self) -> float:
        """The apex height (length) at which S is largest (see
        :attr:`s_max_minus_pi`), to 1e-7 of itself."""
        return self._s_max[0]


def make_direction_surface(frame: FrameCurve, model: Model | str) -> DirectionSurface:
    """The (unsolved) direction-surface of ``frame`` in the chosen model."""
    m = Model.parse(model)
    return PaperFan(frame) if m is Model.PAPER else ExactCone(frame)


def _describe(frame: FrameCurve, model: Model) -> str:
    text = (
        f"alpha={frame.alpha!r} deg, beta={frame.beta!r} deg, h_c={frame.h_c!r}, "
        f"radius={frame.radius!r}, model={model.value}"
    )
    if model is Model.PAPER:
        text += f", divisions={frame.divisions}"
    return text


def _no_root(frame: FrameCurve, model: Model, why: str, reason: str = "no_root") -> NoSolutionError:
    err = NoSolutionError(f"no non-trivial apex for {_describe(frame, model)}: {why}")
    err.reason = reason  # type: ignore[attr-defined]
    return err


def _unresolved(
    frame: FrameCurve, model: Model, why: str, heights: tuple[float, float]
) -> NoSolutionError:
    err = NoSolutionError(
        f"the apex cannot be resolved to {ANGLE_TOLERANCE_DEG:g} deg in double precision "
        f"for {_describe(frame, model)}: {why}"
    )
    err.reason = "unresolved"  # type: ignore[attr-defined]
    err.heights = heights  # type: ignore[attr-defined]
    return err


#: The grid on which :func:`_s_max` looks for the maximum: heights root * 2^(-j / 2),
#: j = 0 .. 2 * _S_MAX_OCTAVES.
_S_MAX_OCTAVES = 80


def _excess_rel(surface: DirectionSurface, h: float, fast: float | None = None) -> float:
    """S(h) - pi (radians, h in units of R) to a relative accuracy: the fast
    value when it is far above its rounding bound, else the accurate one."""
    if fast is not None and abs(fast) > 1e6 * surface.excess_bound():
        return fast
    return surface.excess_accurate(h)[0]


def _s_max(surface: DirectionSurface, root: float) -> tuple[float, float]:
    """(h, S(h) - pi) at the maximum of S on (0, root] (h in units of R).

    S - pi is evaluated on a grid of half-octave steps from 2^-80 root to
    root (its value, not its rounding, decides: the accurate evaluation where
    the fast one is within 1e6 of its rounding bound, as it is for every
    height when beta is tiny), then the largest grid value is refined by
    golden section on log h between its neighbours to 1e-7 of h. The value
    returned is therefore the maximum to within its evaluation's error bound
    plus about 1e-14 of itself (S is quadratic at its maximum), provided S
    has no narrower peak between grid heights than half an octave."""
    hs = np.asarray(root * 2.0 ** (-0.5 * np.arange(2 * _S_MAX_OCTAVES + 1)), dtype=np.float64)
    fast = surface.excesses(hs)
    # a height whose fast value lies below the largest by far more than their
    # rounding cannot hold the maximum: only the others need the accurate S
    # (on a well-conditioned frame that leaves a few of the 161 heights)
    margin = 1e3 * surface.excess_bound() + 1e-9 * float(np.max(np.abs(fast)))
    floor = float(np.max(fast)) - 2.0 * margin
    vals = [
        _excess_rel(surface, float(h), float(f)) if f >= floor else -math.inf
        for h, f in zip(hs, fast, strict=True)
    ]
    k = int(np.argmax(vals))
    lo = math.log(hs[min(k + 1, len(hs) - 1)])
    hi = math.log(hs[max(k - 1, 0)])
    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    fa, fb = _excess_rel(surface, math.exp(a)), _excess_rel(surface, math.exp(b))
    while hi - lo > 1e-7:
        if fa < fb:
            lo, a, fa = a, b, fb
            b = lo + g * (hi - lo)
            fb = _excess_rel(surface, math.exp(b))
        else:
            hi, b, fb = b, a, fa
            a = hi - g * (hi - lo)
            fa = _excess_rel(surface, math.exp(a))
    best = max((fa, a), (fb, b), (vals[k], math.log(hs[k])))
    h = math.exp(best[1])
    return h, surface.excess_accurate(h)[0]


def _refine(
    surface: DirectionSurface, search: Search, h: float, slope: float
) -> tuple[float, float, float]:
    """Newton steps on the accurate S (relative accuracy, see
    :meth:`DirectionSurface.excess_accurate`) from the search's root h (units
    of R) while they reduce |S - pi|: where max S - pi is tiny (beta near 0)
    the fast S's rounding leaves h known only to ~1e-9 of itself, the
    accurate S to ~1e-14. Returns (h, S(h) - pi, its error bound)."""
    f, b = surface.excess_accurate(h)
    search.evals += 1
    for _ in range(4):
        if abs(f) <= b:
            break
        x = h - f / slope
        if x == h or not x > 0.0:
            break
        fx, bx = surface.excess_accurate(x)
        search.evals += 1
        if not abs(fx) < abs(f):
            break
        h, f, b = x, fx, bx
    return h, f, b


def _resolve(
    surface: DirectionSurface,
    frame: FrameCurve,
    m: Model,
    search: Search,
    h: float,
    res: float,
    bound: float,
    slope: float,
) -> tuple[float, float, float]:
    """The verified root when the search's root fails verification (lengths).

    Steps on the verifying evaluation itself (Newton with the search's slope,
    then regula falsi and bisection between heights it shows above and below
    180 deg) until it meets the tolerance, or two adjacent doubles show
    that no height does (raise), or its own error bound is too large (raise).
    """
    pts: dict[float, tuple[float, float]] = {h: (res, bound)}

    def check(x: float) -> tuple[float, float]:
        if x not in pts:
            surface.set_apex(x)
            pts[x] = surface.verify(_TOL)
            search.evals += 1
        return pts[x]

    def fail(why: str, heights: tuple[float, float]) -> NoSolutionError:
        surface.set_apex(h)
        return _unresolved(frame, m, why, heights)

    x = h - res / slope if slope < 0.0 else h
    for _ in range(200):
        r, b = check(x)
        if abs(r) + b <= _TOL:
            return x, r, b
        if b > 0.5 * _TOL:
            raise fail(
                f"at h = {x!r} the verifying evaluation's own error bound is "
                f"{2 * math.degrees(b):.3g} deg",
                (x, x),
            )
        above = [k for k, (rk, bk) in pts.items() if rk > bk]
        below = [k for k, (rk, bk) in pts.items() if rk < -bk]
        lo = max(above) if above else None
        hi = min((k for k in below if lo is None or k > lo), default=None)
        if lo is None:
            x = 0.5 * min(pts)
            continue
        if hi is None:
            x = 2.0 * max(pts)
            continue
        if math.nextafter(lo, math.inf) >= hi:
            rl, rh = pts[lo][0], pts[hi][0]
            raise fail(
                f"the angle sum falls from {2 * math.degrees(rl):+.3g} to "
                f"{2 * math.degrees(rh):+.3g} deg off 360 deg between the adjacent "
                f"doubles h = {lo!r} and {hi!r} (dS/dh = {(rh - rl) / (hi - lo):.3g} "
                "rad per length)",
                (lo, hi),
            )
        rl, rh = pts[lo][0], pts[hi][0]
        x = lo + (hi - lo) * rl / (rl - rh)  # regula falsi
        if not lo < x < hi or len(pts) % 3 == 0:
            x = 0.5 * (lo + hi)
    raise fail("the verified search did not converge", (h, h))


def solve(
    frame: FrameCurve, model: Model | str = Model.EXACT, spacing: ArcSpacing | None = None
) -> Solution:
    """Find the apex that satisfies the angle condition (360 deg around A).

    Args:
        frame: the validated frame curve.
        model: 'exact' (continuous cone) or 'paper' (triangle fan).
        spacing: paper model only: the fan's division points at these arc
            parameters (of ``frame.divisions``) instead of the paper's equal steps.

    Returns:
        The :class:`Solution`, verified at the returned apex to within
        :data:`ANGLE_TOLERANCE_DEG`.

    Raises:
        NoSolutionError: the paper model's single triangle (no h > 0 makes its
            apex angle 180 deg), a root that double precision cannot resolve,
            or a design too flat to represent; the message names the inputs
            and the reason.
    """
    m = Model.parse(model)
    if spacing is not None and m is not Model.PAPER:
        raise InvalidParameterError("spacing", "only the paper model's fan has a spacing")
    try:
        return _solve(frame, m, spacing)
    except FloatingPointError as exc:
        # only when the caller made numpy raise on underflow: a vanishing term
        # of a design near the limits of double precision; harmless here
        if "underflow" not in str(exc):
            raise
        with np.errstate(under="ignore"):
            return _solve(frame, m, spacing)


def _solve(frame: FrameCurve, m: Model, spacing: ArcSpacing | None) -> Solution:
    t0 = time.perf_counter()
    if m is Model.PAPER and frame.divisions == 1:
        raise _no_root(
            frame,
            m,
            "the sum of apex angles never exceeds 180 deg: a single triangle's apex "
            "angle is below 180 deg for every apex height (use 2 or more divisions)",
        )
    surface: DirectionSurface = PaperFan(frame, spacing) if m is Model.PAPER else ExactCone(frame)
    g = surface.geometry
    near = min(g.l_plus, g.l_minus)
    if near <= 0.0:
        end = "+x" if g.l_plus <= g.l_minus else "-x"
        raise InvalidParameterError(
            "h_c",
            f"H must lie strictly inside the f-line: evaluated to 40 digits, h_c={frame.h_c!r} "
            f"puts H {-near * frame.radius:.3g} beyond its {end} end "
            f"(radius={frame.radius!r}, alpha={frame.alpha!r} deg)",
        )
    if near < 1e-100:
        raise _no_root(
            frame,
            m,
            f"H lies {near:.3g} R from an end of the f-line: the apex would lie about "
            "as close to it, beyond double precision",
            "precision",
        )
    if g.sin_beta < 1e-100:
        raise _no_root(
            frame,
            m,
            f"sin(beta) = {g.sin_beta:.3g}: the apex would lie within about "
            f"{g.sin_beta:.1g} R of H, beyond double precision",
            "precision",
        )
    r = frame.radius
    l0 = (1.0 + g.sin_alpha) * g.sin_beta
    try:
        h, search, slope = find_root(surface, l0)
    except SearchFailed as exc:
        raise _no_root(frame, m, f"the root search failed ({exc})") from None
    h_abs = h * r
    surface.set_apex(h_abs)
    res, bound = surface.verify(_TOL)
    search.evals += 1
    if abs(res) + bound > _TOL:
        h_abs, res, bound = _resolve(surface, frame, m, search, h_abs, res, bound, slope / r)
        h = h_abs / r
    # the apex height's own uncertainty: from the most accurate evaluation at h
    err_f = abs(res) + bound
    if slope != 0.0 and err_f / abs(slope) > _WARN_REL * h:
        h, f_acc, b_acc = _refine(surface, search, h, slope)
        if h != h_abs / r:
            # the refined height must meet the angle condition as verified
            surface.set_apex(h * r)
            r2, b2 = surface.verify(_TOL)
            search.evals += 1
            if abs(r2) + b2 <= _TOL:
                h_abs, res, bound = h * r, r2, b2
            else:
                h = h_abs / r
                surface.set_apex(h_abs)
                f_acc, b_acc = surface.excess_accurate(h)
                search.evals += 1
        err_f = min(abs(res) + bound, abs(f_acc) + b_acc)
    h_err = (err_f / abs(slope) if slope != 0.0 else math.inf) + 4.0 * _EPS * h
    warnings: list[str] = []
    peak: tuple[float, float] | None = None
    if h_err > _WARN_REL * h:
        peak = _s_max(surface, h)
        smax = peak[1]
        warnings.append(
            f"ill-conditioned apex: the angle sum rises only {2 * math.degrees(smax):.3g} deg "
            f"above 360 deg before it falls to the root, so the apex height "
            f"{h * r:.10g} is known only to +-{h_err * r:.3g} ({h_err / h:.2g} relative)"
        )
    lo, hi = min(search.lo, h), max(search.hi, h)
    total = 2.0 * math.degrees(math.pi + res)
    elapsed = time.perf_counter() - t0
    sol = Solution(
        frame=frame,
        model=m,
        apex_height=h_abs,
        surface=surface,
        angle_sum_deg=total,
        angle_condition_error_deg=2.0 * math.degrees(abs(res) + bound),
        time_direction_surface=elapsed,
        bracket=(lo * r, hi * r),
        evaluations=search.evals,
        apex_height_error=h_err * r,
        ds_dh=slope / r,
        warnings=tuple(warnings),
    )
    if peak is not None:  # computed for the warning: Solution.s_max_* reuse it
        sol.__dict__["_s_max"] = (peak[0] * r, peak[1])
    return sol
