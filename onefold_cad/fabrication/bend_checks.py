"""The limits of the sharp-crease bend compensation, checked on a fold: the
one check ``solve`` reports as warnings and every writer of the blank or the
solid refuses with (numpy only, cheap: linear in the sheet's vertex count).

The bend model itself is :mod:`onefold_cad.geometry.bend_model`; the
reasoning behind each limit is in docs/fabrication.md. Lengths are in the
design's unit, angles in degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.choices import Units
from onefold_cad.errors import FabricationError
from onefold_cad.geometry.bend_model import (
    BendValues,
    bend_model,
    bendable,
    blank_move,
    crease_bends,
)
from onefold_cad.geometry.fan_folds import RulingFold, ruling_folds
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.numeric import Array

__all__ = [
    "MAX_SETBACK_FRACTION",
    "MAX_WIDTH_ERROR_FRACTION",
    "BendProblem",
    "bend_error",
    "check_bends",
]

#: The largest set-back, as a fraction of the flange beside the crease half,
#: for which the sharp-crease compensation is accepted (see docs/fabrication.md).
MAX_SETBACK_FRACTION = 0.1

#: The largest width error of the blank across a bend, as a fraction of the
#: thickness t: the blank is refused when it is more than 0.1 t wider or
#: narrower across a bend than the bend model asks. The bend model itself is
#: no better: the K-factor of one material and tooling is known to about
#: +-0.05, which moves BA = psi (r + K t) by psi x 0.05 t, 0.08 t at a 90 deg
#: fold (see docs/fabrication.md).
MAX_WIDTH_ERROR_FRACTION = 0.1


@dataclass(frozen=True)
class BendProblem:
    """One limit of the sharp-crease compensation passed.

    Attributes:
        half: the crease half ('plus_x' or 'minus_x'), or the paper model's
            ruling fold ('+y ruling 3', see :class:`RulingFold`).
        angle_deg: its fold angle (deg).
        kind: 'setback' (large beside the flanges), 'corner' (a sheet corner
            in the bend zone), 'edge' (a sheet edge across the bend zone) or
            'width' (the blank's width across the bend off by more than
            MAX_WIDTH_ERROR_FRACTION x t), or 'closed' (folded flat onto
            itself: no bend model at all, whatever the thickness).
        parameter: what to change, as the CLI spells it.
        message: one line: the half, its angle, the numbers, what to change.
    """

    half: str
    angle_deg: float
    kind: str
    parameter: str
    message: str


def _chains(sheet_vertices: Array, k: int) -> tuple[Array, Array]:
    """Both sides' boundary runs from the +x crease end to the -x one, each with
    y >= 0 (the -y side mirrored), ``(m, 2)`` each."""
    v = np.asarray(sheet_vertices, dtype=float)
    upper = v[: k + 1]
    lower = np.vstack([v[:1], v[:k:-1], v[k : k + 1]]) * np.array([1.0, -1.0])
    return upper, lower


def _flange_depth(chain: Array, x_lo: float, x_hi: float) -> float:
    """The largest distance from the fold line of the chain's points whose
    foot lies in [x_lo, x_hi] (vertices there and the chain's crossings of x = 0)."""
    x, y = chain[:, 0], chain[:, 1]
    inside = (x >= x_lo) & (x <= x_hi)
    depth = float(np.max(y[inside])) if np.any(inside) else 0.0
    a, b = chain[:-1], chain[1:]
    cross = (a[:, 0] * b[:, 0] <= 0.0) & (a[:, 0] != b[:, 0])
    if np.any(cross):
        u = a[cross, 0] / (a[cross, 0] - b[cross, 0])
        depth = max(depth, float(np.max(a[cross, 1] + u * (b[cross, 1] - a[cross, 1]))))
    return depth


def _radius_hint(target: float, b: BendValues) -> str:
    """What keeps the set-back SB below ``target`` (length): the largest bend
    radius, the largest thickness, the largest fold angle."""
    tan = math.tan(math.radians(b.angle_deg) / 2.0)
    hints = []
    if target > 0.0 and tan > 0.0:
        r_max = target / tan - b.s * b.thickness
        if r_max > 0.0:
            hints.append(f"bend_radius <= {r_max:.4g}")
        if b.s > 0.0 and target / tan > b.radius:
            hints.append(f"thickness <= {(target / tan - b.radius) / b.s:.4g}")
        ref = b.radius + b.s * b.thickness
        if ref > 0.0:
            psi_max = 2.0 * math.degrees(math.atan(target / ref))
            hints.append(f"alpha/beta giving a fold angle <= {psi_max:.4g} deg")
    if not hints:
        hints.append("a smaller bend_radius or thickness, or other alpha/beta")
    return "use " + ", or ".join(hints) + ", or --compensation none"


def _width_hint(
    bends: tuple[BendValues, BendValues], h: int, tol: float, mat: Material
) -> tuple[str, str]:
    """What brings the width error across half ``h`` within +-``tol`` (length):
    the parameter to name and the hint. The error, shift_h - shift_other, is
    linear in the bend radius r (read off the bend model at r = 0 and 1)."""
    b, o = bends[h], bends[1 - h]

    def width(r: float) -> float:
        m = mat.with_changes(bend_radius=r)
        return (
            bend_model(b.angle_deg, b.direction, m).shift
            - bend_model(o.angle_deg, o.direction, m).shift
        )

    rest = width(0.0)
    slope = width(1.0) - rest
    hints = ["h_c nearer 0 (at h_c = 0 both halves fold alike)"]
    parameter = "hc"
    if slope != 0.0:
        lo, hi = sorted(((-tol - rest) / slope, (tol - rest) / slope))
        lo = max(lo, 0.0)
        if hi >= lo and b.radius > hi:
            hints.insert(0, f"bend_radius <= {hi:.4g}")
            parameter = "bend_radius"
        elif hi >= lo and b.radius < lo:
            hints.insert(0, f"bend_radius >= {lo:.4g}")
            parameter = "bend_radius"
    return parameter, "use " + ", or ".join(hints) + ", or --compensation none"


def _ruling_widths(
    folded: FoldedSheet, mat: Material, tol: float
) -> list[tuple[float, RulingFold, BendValues]]:
    """The paper model's ruling folds whose width error 2 x shift (they are
    not compensated) is larger than ``tol``: (error, fold, bend model), the
    largest first."""
    out = []
    for f in ruling_folds(folded):
        b = bend_model(f.angle_deg, f.bend, mat, half=f.name)
        if abs(2.0 * b.shift) > tol:
            out.append((2.0 * b.shift, f, b))
    return sorted(out, key=lambda x: -abs(x[0]))


def _line_at_h(a: Array, b: Array) -> float:
    """y where the line through ``a`` and ``b`` (x of different signs) meets x = 0."""
    return float(a[1] + a[0] / (a[0] - b[0]) * (b[1] - a[1]))


def check_bends(
    folded: FoldedSheet, material: Material, units: Units | str
) -> tuple[BendProblem, ...]:
    """The limits of the sharp-crease compensation of ``material`` (lengths in
    ``units``, named in the messages), checked on ``folded``.

    Numpy only and cheap (linear in the sheet's vertex count): ``solve`` can
    report the problems as warnings, the writers refuse with them.

    Limits (docs/fabrication.md gives the reasoning), for each crease half of
    fold angle psi with set-back SB and allowance BA, each side of the blank
    moved towards the fold line by the mean shift d (:func:`blank_move`):

    1. setback: SB <= MAX_SETBACK_FRACTION x the flange beside the half (on
       each side, the sheet's largest distance from the fold line over the
       half's length; the narrower side counts). SB grows as tan(psi / 2), so
       this is also the limit as psi nears 180 deg.
    2. corner: every sheet corner but the two crease ends lies, once moved by
       d, outside the bend zone (farther than BA / 2 from the fold line) of
       each half it lies beside (x >= 0: plus_x, x <= 0: minus_x).
    3. edge: no sheet edge crosses a bend zone but the two at each crease end,
       and those leave the zone on their own half's side of H. (When the mean
       shift puts a crease end itself outside its half's zone, the blank's
       bridge starts right there; the width error says by how much.)
    4. width: the blank's width error across each bend, 2 (own shift - d)
       across a crease half and 2 shift across a paper-model ruling fold
       (:func:`~onefold_cad.geometry.fan_folds.ruling_folds`, not
       compensated), is at most MAX_WIDTH_ERROR_FRACTION x t either way.

    Returns:
        The problems found (empty: the compensated blank is valid), each with
        a one-line message naming the half, its fold angle, the numbers and
        what to change. Zero thickness: empty but for a crease half folded
        flat onto itself (then that problem alone, whatever the thickness).
    """
    mat, sheet = material, folded.sheet
    closed = tuple(_closed(c.name, c.fold_angle_deg) for c in folded.crease
                   if not bendable(c.fold_angle_deg))  # fmt: skip
    if closed or mat.thickness <= 0.0:
        return closed
    bends = crease_bends(folded, mat)
    d = blank_move(bends).shift
    u = Units.parse(units).value
    c = (bends[0].allowance / 2.0, bends[1].allowance / 2.0)
    ends = sheet.crease_lengths
    place = sheet.to_sheet
    chains = _chains(sheet.vertices, sheet.minus_x_index)
    problems: list[BendProblem] = []

    def add(
        b: BendValues, kind: str, text: str, target: float, hint: tuple[str, str] | None = None
    ) -> None:
        head = (
            f"{b.half} (fold angle {b.angle_deg:.2f} deg, {b.direction}, {b.reference} reference, "
            f"bend_radius {b.radius:g} {u}, thickness {b.thickness:g} {u})"
        )
        parameter, advice = hint or ("bend_radius", _radius_hint(target, b))
        line = f"{head}: {text}; {advice}"
        problems.append(BendProblem(b.half, b.angle_deg, kind, parameter, line))

    for h, b in enumerate(bends):
        span = (0.0, ends[0]) if h == 0 else (-ends[1], 0.0)
        depth, side = min(
            (_flange_depth(ch, *span), sd) for ch, sd in zip(chains, "+-", strict=True)
        )
        if not b.setback <= MAX_SETBACK_FRACTION * depth:
            add(
                b,
                "setback",
                f"set-back SB = {b.setback:.4g} {u} is {b.setback / depth:.1%} of the {depth:.4g} "
                f"{u} flange beside it on the {side}y side (limit {MAX_SETBACK_FRACTION:.0%}): "
                "the bend would replace that much of the designed surface",
                MAX_SETBACK_FRACTION * depth,
            )
    corners: tuple[list[tuple[float, Array]], ...] = ([], [])  # per half: (distance, corner)
    for chain, sign in zip(chains, (1.0, -1.0), strict=True):
        side = "+y" if sign > 0 else "-y"
        x, y = chain[:, 0], chain[:, 1] - d  # y: distance from the fold line in the blank
        last = len(chain) - 1
        inner_x, inner_y = x[1:last], y[1:last]
        for h in (0, 1):
            beside = inner_x >= 0.0 if h == 0 else inner_x <= 0.0
            for v in np.flatnonzero(beside & ~(inner_y > c[h])) + 1:
                corners[h].append((float(chain[v, 1]), chain[v] * np.array([1.0, sign])))
        for i in range(1, last - 1):  # edges between corners that pass over H
            if x[i] * x[i + 1] < 0.0:
                y0 = _line_at_h(np.array([x[i], y[i]]), np.array([x[i + 1], y[i + 1]]))
                if not y0 > max(c):
                    b = bends[int(np.argmax(c))]
                    add(
                        b,
                        "edge",
                        f"the sheet's edge passes {y0 + d:.4g} {u} from H on the {side} side, "
                        f"inside the bend zone (it must pass farther than d + BA/2 = "
                        f"{d + max(c):.4g} {u})",
                        y0 + b.shift,
                    )
        for h, (i, j) in enumerate(((0, 1), (last, last - 1))):
            # the edge from the crease end: its part beside the half must end (at H, when
            # it runs on past H) outside the half's zone (its corner j is checked above)
            if x[j] < 0.0 if h == 0 else x[j] > 0.0:
                y0 = _line_at_h(np.array([x[i], y[i]]), np.array([x[j], y[j]]))
                if not y0 > c[h]:
                    b = bends[h]
                    add(
                        b,
                        "edge",
                        f"on the {side} side the sheet beside the half is narrower than its bend "
                        f"zone all the way to H (its edge passes {y0 + d:.4g} {u} from H; it must "
                        f"pass farther than d + BA/2 = {d + c[h]:.4g} {u})",
                        y0 + b.shift,
                    )
    for h, found in enumerate(corners):
        if found:
            b = bends[h]
            dist, worst = min(found, key=lambda f: f[0])
            at = place.apply(worst)
            more = f" (and {len(found) - 1} more corners)" if len(found) > 1 else ""
            add(
                b,
                "corner",
                f"the sheet corner at ({at[0]:.4g}, {at[1]:.4g}) {u} lies {dist:.4g} {u} from "
                f"the fold line, inside the bend zone{more} (a corner must lie farther than "
                f"d + BA/2 = {d + c[h]:.4g} {u}; SB = {b.setback:.4g} {u})",
                dist - (d - b.shift),
            )
    tol = MAX_WIDTH_ERROR_FRACTION * mat.thickness
    errors = blank_move(bends).errors
    if max(abs(e) for e in errors) > tol:
        h = 0 if errors[0] > 0.0 else 1  # the half the blank is too wide across
        b, o = bends[h], bends[1 - h]
        add(
            b,
            "width",
            f"the blank is {errors[h]:+.4g} {u} too wide across it and {errors[1 - h]:+.4g} {u} "
            f"across {o.half} (fold angle {o.angle_deg:.2f} deg): one rigid blank moves each side "
            f"by the mean d = {d:.4g} {u} of the halves' shifts {b.shift:.4g} and "
            f"{o.shift:.4g} {u} (limit +-{tol:.4g} {u}, {MAX_WIDTH_ERROR_FRACTION:.0%} of t)",
            0.0,
            _width_hint(bends, h, tol, mat),
        )
    rulings = _ruling_widths(folded, mat, tol)
    if rulings:
        err, _, b = rulings[0]
        more = f"; {len(rulings) - 1} more ruling folds past the limit" if len(rulings) > 1 else ""
        add(
            b,
            "width",
            f"the paper model's ruling folds are not compensated: across this one the blank is "
            f"{err:+.4g} {u} off the bend model's width (2 x its shift; limit +-{tol:.4g} {u}, "
            f"{MAX_WIDTH_ERROR_FRACTION:.0%} of t){more}",
            0.0,
            (
                "divisions",
                "use more divisions (each ruling then folds less), the exact model (smooth, "
                "no ruling folds), or --compensation none",
            ),
        )
    order = {"setback": 0, "corner": 1, "edge": 2, "width": 3}
    return tuple(sorted(problems, key=lambda q: order[q.kind]))


def _closed(half: str, angle_deg: float) -> BendProblem:
    """The problem of a crease half folded flat onto itself (the bend model's
    fold angles end short of 180 deg: :func:`~onefold_cad.geometry.bend_model.bendable`)."""
    return BendProblem(
        half, angle_deg, "closed", "beta",
        f"{half}: folds {angle_deg:.6g} deg, flat onto itself (beta within rounding of 90 "
        "deg): a bend of 180 deg has no bend allowance, set-back or deduction; set a "
        "smaller beta",
    )  # fmt: skip


def bend_error(problems: tuple[BendProblem, ...]) -> FabricationError | None:
    """The error a writer raises for ``problems`` (:func:`check_bends`): the
    first problem's line and how many more there are; None when there are none."""
    if not problems:
        return None
    more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
    return FabricationError(problems[0].parameter, problems[0].message + more)
