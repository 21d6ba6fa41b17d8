"""Inverse design: the frame whose resting form has a target height and span.

Designers start from the site ("3 m high, 5.6 m wide"). :func:`fit_design`
keeps a design's sheet and material and looks for alpha, beta and h_c whose
form, standing as it rests (:func:`~onefold_cad.geometry.resting.placement.rest_form`,
the body the STEP holds), has the target height and footprint width (span,
along the resting frame's x axis; the footprint depth along its y axis is an
optional third target), within a relative tolerance (0.5 %), optionally with
a minimum tipping margin.

How: a coarse grid of alpha, beta (and h_c) on the paper's fan of 36
triangles (milliseconds a design) seeds ``scipy.optimize.least_squares`` on
a fan of 90 (or the template's own), and the result is polished on the body
the STEP holds (a tenth of a second): measure it, shift the fan's targets by
the difference, solve on the fan again. With two targets the template's h_c is kept first;
h_c is set free when that fails or a depth is given. The resting form jumps
where it starts to rest on other contacts, so several seeds are tried. When
none reaches the targets, the error gives the ranges of height, span (and
depth) the grid reached, and the closest form found.

scipy is imported inside :func:`fit_design` only (``onefold solve`` never
loads it). Lengths are in the design's unit, angles in degrees.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from onefold_cad.choices import Body, Model
from onefold_cad.design import Design
from onefold_cad.errors import InvalidParameterError, NoSolutionError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.fabrication.rules import default_body
from onefold_cad.geometry.folding import FoldedSheet, fold
from onefold_cad.geometry.frame_curve import FrameCurve
from onefold_cad.geometry.resting.placement import RestingPlacement, rest_form
from onefold_cad.geometry.solver import solve

__all__ = ["FitResult", "OutOfReachError", "fit_design", "FIT_TOLERANCE"]

#: The relative error every target is met to.
FIT_TOLERANCE = 0.005
#: The coarse grid: alpha and beta (deg), and h_c as a fraction of its limit.
_GRID_ANGLES = np.linspace(5.0, 85.0, 9)
_FINE_ANGLES = np.linspace(2.5, 87.5, 18)
#: Grid points that seed the search.
_SEEDS = 6
_GRID_HC = (-0.5, 0.0, 0.5)
_GRID_DIVISIONS = 36
#: The fan the fit is solved on for an exact-model template.
_FAN_DIVISIONS = 90
#: Bounds of the search (deg; fraction of R cos(alpha) for h_c).
_LOWER = np.array([0.5, 0.5, -0.95])
_UPPER = np.array([89.5, 89.5, 0.95])


@dataclass(frozen=True)
class FitResult:
    """A fitted design and what its resting form measures.

    Attributes:
        design: the template's design with the found frame.
        body: the body that stands ('shell' or 'solid': the STEP's).
        height, span, depth: the resting form's height and footprint extents
            along the resting frame's x and y axes (length).
        tipping_margin_deg: its tipping margin (deg).
        targets: the targets as given ('height', 'span', and 'depth' and
            'min_tipping_margin_deg' when given).
        evaluations: how many designs were solved and stood.
    """

    design: Design
    body: Body
    height: float
    span: float
    depth: float
    tipping_margin_deg: float
    targets: dict[str, float]
    evaluations: int

    @property
    def errors(self) -> dict[str, float]:
        """Relative error of each length target."""
        got = {"height": self.height, "span": self.span, "depth": self.depth}
        return {k: abs(got[k] - v) / v for k, v in self.targets.items() if k in got}

    def to_data(self) -> dict[str, object]:
        """The result as ``onefold fit --json`` prints it: the design's name and
        unit, the found ``frame`` (alpha, beta in deg, h_c), the ``body``, what
        its resting form ``achieved`` (height, span, depth, tipping margin),
        the ``targets``, the ``relative_errors`` and the ``evaluations``."""
        f = self.design.frame
        return {
            "name": self.design.name,
            "units": self.design.units.value,
            "frame": {"alpha": f.alpha, "beta": f.beta, "h_c": f.h_c},
            "body": self.body,
            "achieved": {
                "height": self.height,
                "span": self.span,
                "depth": self.depth,
                "tipping_margin_deg": self.tipping_margin_deg,
            },
            "targets": self.targets,
            "relative_errors": self.errors,
            "evaluations": self.evaluations,
        }


class OutOfReachError(InvalidParameterError):
    """No frame gives the target with this sheet and material.

    Attributes:
        reachable: the (min, max) of each length the coarse grid reached.
        closest: the closest result found, or None.
    """

    def __init__(
        self, message: str, reachable: dict[str, tuple[float, float]], closest: FitResult | None
    ) -> None:
        super().__init__("target", message)
        self.reachable = reachable
        self.closest = closest


def _body_of(design: Design, folded: FoldedSheet) -> tuple[str, object]:
    """The body the STEP holds (:func:`onefold_cad.fabrication.rules.default_body`) and
    the material it is built with."""
    m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    return default_body(design), m


def _frame(base: FrameCurve, x: np.ndarray, divisions: int | None = None) -> FrameCurve:
    alpha, beta, frac = (float(v) for v in x)
    h_c = frac * base.radius * math.cos(math.radians(alpha))
    n = base.divisions if divisions is None else divisions
    return base.with_changes(alpha=alpha, beta=beta, h_c=h_c, divisions=n)


class _Stand:
    """Stand designs of one template for given (alpha, beta, h_c fraction)."""

    def __init__(self, design: Design) -> None:
        self.design = design
        self.evaluations = 0

    def __call__(self, x: np.ndarray, mode: str) -> RestingPlacement | None:
        """mode: 'grid' (the paper's fan of 36 triangles, bare shell), 'fan'
        (of 90, or the template's fan) or 'body' (the STEP's body)."""
        self.evaluations += 1
        d = self.design
        try:
            if mode in ("grid", "fan"):
                n = _GRID_DIVISIONS if mode == "grid" else None
                if n is None and d.model is Model.EXACT:
                    n = _FAN_DIVISIONS
                frame = _frame(d.frame, x, n)
                return rest_form(fold(solve(frame, Model.PAPER), d.sheet))
            frame = _frame(d.frame, x)
            folded = fold(solve(frame, d.model), d.sheet)
            body, material = _body_of(d.with_changes(frame=frame), folded)
            return rest_form(folded, material, body)  # type: ignore[arg-type]
        except (NoSolutionError, InvalidParameterError):
            return None


def _residual(
    rest: RestingPlacement | None, targets: dict[str, float], x: np.ndarray, x0: np.ndarray
) -> np.ndarray:
    """Relative errors of the targets (a large constant where nothing stands),
    the shortfall of the tipping margin, and a small pull towards the
    template's h_c (so that two targets pick one of the frames that meet them)."""
    n = sum(k in targets for k in ("height", "span", "depth"))
    if rest is None:
        return np.full(n + 2, 10.0)
    got = {"height": rest.height, "span": rest.width, "depth": rest.depth}
    out = [_relative_miss(got[k], v) for k, v in targets.items() if k in got]
    need = targets.get("min_tipping_margin_deg")
    short = 0.0 if need is None else max(0.0, need - rest.tipping_margin_deg) / max(need, 1.0)
    pull = 0.0 if "depth" in targets else 1e-4 * (x[2] - x0[2])
    return np.array([*out, short, pull])


#: The largest relative miss of a target the residual holds: a form a
#: million times off is as far from it as any other, and the squares of
#: the residual stay finite (a span of 1e-300 gave relative errors of 1e303
#: and numpy's overflow warnings in their squares).
_FAR = 1e6


def _relative_miss(got: float, want: float) -> float:
    """(got - want) / want clipped to [-_FAR, _FAR] (floats: no numpy overflow warning)."""
    return max(-_FAR, min(_FAR, (float(got) - want) / want))


def _meets(rest: RestingPlacement | None, targets: dict[str, float], tol: float) -> bool:
    if rest is None:  # no resting form: no target met
        return False
    got = {"height": rest.height, "span": rest.width, "depth": rest.depth}
    ok = all(abs(got[k] - v) <= tol * v for k, v in targets.items() if k in got)
    need = targets.get("min_tipping_margin_deg")
    return ok and (need is None or rest.tipping_margin_deg >= need)


def _check_target(name: str, value: float | None) -> None:
    if value is not None and not (math.isfinite(value) and value > 0.0):
        raise InvalidParameterError(name, f"must be a finite length > 0, got {value!r}")


def fit_design(
    design: Design,
    height: float,
    span: float,
    depth: float | None = None,
    min_tipping_margin: float | None = None,
    *,
    tolerance: float = FIT_TOLERANCE,
    progress: Callable[[str], None] | None = None,
) -> FitResult:
    """Find alpha, beta and h_c for ``design``'s sheet and material whose
    resting form is ``height`` high and ``span`` wide (and ``depth`` deep).

    Args:
        design: the template: sheet, material, model, radius and divisions
            are kept; its h_c is preferred when only height and span are given.
        height, span, depth: the targets (length, > 0).
        min_tipping_margin: the smallest tipping margin allowed (deg), or None.
        tolerance: relative error allowed on each length (default 0.5 %).
        progress: called with one line at each step of the search (the grid
            searched, each seed refined), or None.

    Returns:
        The fitted design and what its resting form measures.

    Raises:
        InvalidParameterError: a target that is not a positive length.
        OutOfReachError: no frame meets the targets; its message gives the
            ranges reached.
    """
    for name, value in (("height", height), ("span", span), ("depth", depth)):
        _check_target(name, value)
    if min_tipping_margin is not None and not (
        math.isfinite(min_tipping_margin) and 0.0 <= min_tipping_margin < 90.0
    ):
        raise InvalidParameterError(
            "min_tipping_margin", f"must be in [0, 90) deg, got {min_tipping_margin!r}"
        )
    targets: dict[str, float] = {"height": float(height), "span": float(span)}
    if depth is not None:
        targets["depth"] = float(depth)
    if min_tipping_margin is not None:
        targets["min_tipping_margin_deg"] = float(min_tipping_margin)
    stand = _Stand(design)
    half = design.frame.radius * math.cos(math.radians(design.frame.alpha))
    x0 = np.array([design.frame.alpha, design.frame.beta, design.frame.h_c / half])
    # two targets: first with the template's h_c; then (and with a depth) h_c free
    stages = [True, False] if depth is None else [False]
    grid: list[tuple[float, np.ndarray, RestingPlacement]] = []
    best: tuple[float, np.ndarray, RestingPlacement] | None = None

    def keep(found: list[tuple[np.ndarray, RestingPlacement]]) -> bool:
        """Keep the best body measured (margin included); True when done."""
        nonlocal best
        for x, rest in found:
            cost = float(np.sum(_residual(rest, targets, x, x0)[:-1] ** 2))
            if best is None or cost < best[0]:
                best = (cost, x, rest)
        return best is not None and _meets(best[2], targets, tolerance / 10.0)

    say = progress or (lambda text: None)
    for fixed in stages:
        which = "h_c kept" if fixed else "h_c free"
        if fixed:
            stage_grid = _grid(stand, targets, _FINE_ANGLES, [float(x0[2])], x0)
        else:
            fracs = sorted({*_GRID_HC, float(x0[2])})
            stage_grid = _grid(stand, targets, _GRID_ANGLES, fracs, x0)
        grid += stage_grid
        say(f"grid ({which}): {len(stage_grid)} frames stand ({stand.evaluations} solved so far)")
        # seeds within 25 % of every target on the grid (the rest cannot get
        # there): the best by the lengths, and the best with the margin too
        lengths = {k: v for k, v in targets.items() if k != "min_tipping_margin_deg"}
        by_length = sorted(
            stage_grid,
            key=lambda item: float(np.sum(_residual(item[2], lengths, item[1], x0) ** 2)),
        )
        seeds: list[np.ndarray] = []
        for _, x, rest in [*stage_grid[:3], *by_length[:_SEEDS]]:
            near = float(np.sum(_residual(rest, lengths, x, x0) ** 2)) <= 3 * 0.25**2
            if near and not any(np.array_equal(x, y) for y in seeds):
                seeds.append(x)
        for i, seed in enumerate(seeds, 1):
            say(
                f"refining seed {i}/{len(seeds)} ({which}): alpha {seed[0]:.4g}, "
                f"beta {seed[1]:.4g} deg, h_c {seed[2]:.3g} of R cos(alpha)"
            )
            # the fan's margins are not the body's (it rests on ruling ends,
            # the body may rock on a curved edge): the fan is fitted to the
            # lengths only, and the body's margin decides among the seeds
            x = _least_squares(stand, "fan", seed, lengths, x0, fixed, 15)
            if keep(_polish(stand, x, lengths, x0, fixed)):
                break
        if best is not None and not _meets(best[2], targets, tolerance):
            fan = stand(best[1], "fan")
            if _meets(fan, targets, tolerance / 10.0):
                # the fan meets the targets where the body does not: the body
                # rests otherwise there (it rocks on a curved edge): on the body
                x = _least_squares(stand, "body", best[1], targets, x0, fixed, 8)
                on_body = stand(x, "body")
                keep([] if on_body is None else [(x, on_body)])
        if best is not None and _meets(best[2], targets, tolerance):
            break
    result = None
    if best is not None:
        _, x, rest = best
        found = design.with_changes(frame=_frame(design.frame, x))
        result = FitResult(
            found, rest.body, rest.height, rest.width, rest.depth,
            rest.tipping_margin_deg, targets, stand.evaluations,
        )  # fmt: skip
        if _meets(rest, targets, tolerance):
            return result
    grid.sort(key=lambda item: item[0])
    raise _out_of_reach(design, targets, grid, result)


def _polish(
    stand: _Stand, x: np.ndarray, targets: dict[str, float], x0: np.ndarray, fixed: bool
) -> list[tuple[np.ndarray, RestingPlacement]]:
    """Move x until the STEP's body meets the targets: each step measures the
    body and the fan at x, shifts the targets by their difference, and solves
    on the fan again (one body a step: the body is slow, the fan fast and
    nearly the same form). Returns every body measured (x, rest)."""
    out: list[tuple[np.ndarray, RestingPlacement]] = []
    for _ in range(4):
        rest, fan = stand(x, "body"), stand(x, "fan")
        if rest is None or fan is None:
            break
        out.append((x, rest))
        if _meets(rest, targets, FIT_TOLERANCE / 20.0):
            break
        got = {"height": rest.height, "span": rest.width, "depth": rest.depth}
        near = {"height": fan.height, "span": fan.width, "depth": fan.depth}
        shifted = {k: v - (got[k] - near[k]) if k in got else v for k, v in targets.items()}
        if any(v <= 0.0 for k, v in shifted.items() if k in got):
            break
        x = _least_squares(stand, "fan", x, shifted, x0, fixed, 15)
        if not _meets(stand(x, "fan"), shifted, FIT_TOLERANCE / 20.0):
            # the fan cannot meet the shifted targets here: measure once more, stop
            rest = stand(x, "body")
            if rest is not None:
                out.append((x, rest))
            break
    return out


def _grid(
    stand: _Stand,
    targets: dict[str, float],
    angles: np.ndarray,
    fracs: list[float],
    x0: np.ndarray,
) -> list[tuple[float, np.ndarray, RestingPlacement]]:
    """The coarse grid's designs that stand, best first (cost, x, rest)."""
    out = []
    for frac in fracs:
        for a in angles:
            for b in angles:
                x = np.array([a, b, frac])
                rest = stand(x, "grid")
                if rest is not None:
                    out.append((float(np.sum(_residual(rest, targets, x, x0) ** 2)), x, rest))
    out.sort(key=lambda item: item[0])
    return out


def _least_squares(
    stand: _Stand,
    mode: str,
    start: np.ndarray,
    targets: dict[str, float],
    x0: np.ndarray,
    fixed: bool,
    nfev: int,
) -> np.ndarray:
    """scipy's least_squares on the residual, over alpha and beta (h_c kept
    at ``start``'s when ``fixed``) or all three."""
    from scipy.optimize import least_squares

    keep = 2 if fixed else 3

    def full(y: np.ndarray) -> np.ndarray:
        return np.concatenate([y, start[keep:]])

    def fun(y: np.ndarray) -> np.ndarray:
        x = full(y)
        return _residual(stand(x, mode), targets, x, x0)

    y0 = np.clip(start, _LOWER, _UPPER)[:keep]
    res = least_squares(
        fun, y0, bounds=(_LOWER[:keep], _UPPER[:keep]), x_scale=np.array([10.0, 10.0, 0.2])[:keep],
        diff_step=1e-4, xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=nfev,
    )  # fmt: skip
    return full(np.asarray(res.x, dtype=float))


def _out_of_reach(
    design: Design,
    targets: dict[str, float],
    grid: list[tuple[float, np.ndarray, RestingPlacement]],
    closest: FitResult | None,
) -> OutOfReachError:
    u = design.units.value
    need = targets.get("min_tipping_margin_deg")
    ok = [r for _, _, r in grid if need is None or r.tipping_margin_deg >= need]
    measures: dict[str, Callable[[RestingPlacement], float]] = {
        "height": lambda r: r.height,
        "span": lambda r: r.width,
        "depth": lambda r: r.depth,
    }
    reachable = {
        k: (min(f(r) for r in ok), max(f(r) for r in ok)) for k, f in measures.items() if ok
    }
    asked = ", ".join(f"{k} {v:.6g}" for k, v in targets.items() if k in measures)
    margin = f" with a tipping margin of at least {need:g} deg" if need is not None else ""
    if reachable:
        ranges = ", ".join(
            f"{k} {reachable[k][0]:.4g} to {reachable[k][1]:.4g}" for k in targets if k in measures
        )
        reach = (
            f"a grid of alpha, beta and h_c over (0, 90) x (0, 90) x 3 reaches {ranges} {u}{margin}"
        )
    else:
        reach = f"no frame stands{margin}"
    near = ""
    if closest is not None:
        f = closest.design.frame
        near = (
            f"; closest: height {closest.height:.5g}, span {closest.span:.5g}, depth "
            f"{closest.depth:.5g} {u} at alpha {f.alpha:.4g}, beta {f.beta:.4g}, h_c {f.h_c:.4g}"
        )
    return OutOfReachError(
        f"{asked} {u}{margin} is out of reach for this sheet and material: {reach}{near}",
        reachable,
        closest,
    )
