"""The bend table for the press brake: one row per crease half, then one per
ruling fold of the paper model's fan (none for the exact model).

Every number comes from the flat pattern and its bend model
(:mod:`onefold_cad.geometry.bend_model`); nothing is derived here. The same
rows are written as ``NAME-bends.csv``
(:func:`onefold_cad.export.bend_csv.write_bend_csv`), printed by ``onefold
build`` (:func:`bend_table`) and written in the DXF's NOTES.

Lengths are in the design's unit, angles in degrees, points in the blank's
(sheet's own) frame, the frame of the DXF.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.choices import Compensation
from onefold_cad.fabrication.flat_pattern import FlatPattern
from onefold_cad.geometry.bend_model import BendValues

__all__ = ["BendRow", "bend_rows", "bend_table"]


@dataclass(frozen=True)
class BendRow:
    """One crease half on the press brake (lengths in the design's unit).

    Attributes:
        half: 'plus_x' or 'minus_x', or a paper-model ruling fold ('+y ruling 3').
        direction: 'UP' or 'DOWN'.
        inside_face: 'top' or 'bottom': the flat sheet's face inside the bend
            (top: the face the DXF shows).
        fold_angle_deg: the bend angle from flat (deg).
        included_angle_deg: the angle between the flanges after bending (deg).
        fold_to_deg: the angle the bend is set to (deg): a crease half's fold
            angle plus the material's crease overbend
            (:meth:`~onefold_cad.geometry.material.Material.crease_set_angle`);
            a ruling fold's own fold angle.
        start_x, start_y: where the bend line starts on the blank: the relief
            hole's edge (H when there is no hole).
        end_x, end_y: where it meets the blank's outline.
        length: the bend line's length on the material (start to end).
        inside_radius: r.
        thickness: t.
        k_factor: K.
        reference: the reference surface in this bend (INSIDE, MID, OUTSIDE).
        allowance: BA = psi (r + K t).
        deduction: BD = 2 SB - BA.
        setback: SB = (r + s t) tan(psi / 2).
        shift: this half's own shift SB - BA/2.
        shift_used: how far each side of the blank moved (the mean of both
            halves' shifts; 0 when nothing is compensated, and for a ruling
            fold, which the blank does not compensate).
        width_error: the blank's width across this bend minus the bend
            model's, 2 (shift - shift_used).
        compensation: 'sharp' or 'none' ('none' for a ruling fold).
        material: the material's name.
        units: the length unit.
    """

    half: str
    direction: str
    inside_face: str
    fold_angle_deg: float
    included_angle_deg: float
    fold_to_deg: float
    start_x: float
    start_y: float
    end_x: float
    end_y: float
    length: float
    inside_radius: float
    thickness: float
    k_factor: float
    reference: str
    allowance: float
    deduction: float
    setback: float
    shift: float
    shift_used: float
    width_error: float
    compensation: Compensation
    material: str
    units: str


def _row(
    name: str, start: np.ndarray, end: np.ndarray, b: BendValues, used: float, comp: Compensation,
    pattern: FlatPattern, fold_to: float,
) -> BendRow:  # fmt: skip
    return BendRow(
        half=name,
        direction=b.direction,
        inside_face=b.inside_face,
        fold_angle_deg=b.angle_deg,
        included_angle_deg=b.included_deg,
        fold_to_deg=fold_to,
        start_x=float(start[0]),
        start_y=float(start[1]),
        end_x=float(end[0]),
        end_y=float(end[1]),
        length=float(math.hypot(*(end - start))),
        inside_radius=b.radius,
        thickness=b.thickness,
        k_factor=b.k_factor,
        reference=b.reference.value,
        allowance=b.allowance,
        deduction=b.deduction,
        setback=b.setback,
        shift=b.shift,
        shift_used=used,
        width_error=2.0 * (b.shift - used),
        compensation=comp,
        material=pattern.material.name or "unspecified",
        units=pattern.units.value,
    )


def bend_rows(pattern: FlatPattern) -> tuple[BendRow, ...]:
    """The bend sheet's rows of ``pattern``: 'plus_x', 'minus_x', then the
    paper model's ruling folds counter-clockwise from the +x crease half."""
    rows = []
    for half in pattern.halves:
        d = half.end - half.start
        full = float(np.hypot(*d))
        start = half.start + d * (min(pattern.hole_diameter / 2.0, full) / full)
        rows.append(
            _row(half.name, start, half.end, half.values, pattern.shift, pattern.move.compensation,
                 pattern, half.set_angle_deg)
        )  # fmt: skip
    for f in pattern.fold_rulings:
        rows.append(_row(f.name, f.start, f.end, f.values, 0.0, Compensation.NONE, pattern,
                         f.values.angle_deg))  # fmt: skip
    return tuple(rows)


def bend_table(pattern: FlatPattern, *, rulings: bool = True) -> str:
    """The bend sheet as plain text (what the DXF notes hold, and ``build``
    prints with ``rulings=False``: the ruling folds summed up in one line)."""
    u = pattern.units.value
    m = pattern.material
    lines = [
        f"BEND SHEET ({u}, deg; blank frame as in the DXF): {m.name or 'material unspecified'}, "
        f"t = {m.thickness:g}, inside radius r = {pattern.halves[0].values.radius:g}, "
        f"K = {m.k_factor:g}",
    ]
    rows = bend_rows(pattern)
    folds = rows[2:]
    for r in rows[:2]:
        over = r.fold_to_deg - r.fold_angle_deg
        set_to = f" (the cones), set to {r.fold_to_deg:.2f} (overbend {over:+.2f})" if over else ""
        lines.append(
            f"{r.half}: {r.direction} ({r.inside_face} face inside), fold {r.fold_angle_deg:.2f}"
            f"{set_to}, included {r.included_angle_deg:.2f}; line ({r.start_x:.3f}, "
            f"{r.start_y:.3f}) -> ({r.end_x:.3f}, {r.end_y:.3f}), length {r.length:.3f}"
        )
        lines.append(
            f"  {r.reference} reference: SB {r.setback:.4f}, BA {r.allowance:.4f}, "
            f"BD {r.deduction:.4f}, shift {r.shift:.4f}; blank moved {r.shift_used:.4f} "
            f"({r.compensation}), width error {round(r.width_error, 9) + 0.0:+.4f}"
        )
    for r in folds if rulings else ():
        lines.append(
            f"{r.half}: {r.direction} {r.fold_angle_deg:.2f}; line ({r.start_x:.3f}, "
            f"{r.start_y:.3f}) -> ({r.end_x:.3f}, {r.end_y:.3f}); SB {r.setback:.4f}, BA "
            f"{r.allowance:.4f}, shift {r.shift:.4f}, not compensated: width error "
            f"{round(r.width_error, 9) + 0.0:+.4f}"
        )
    if folds and not rulings:
        angles = [r.fold_angle_deg for r in folds]
        worst = max(abs(r.width_error) for r in folds)
        lines.append(
            f"{len(folds)} ruling folds (paper model): {min(angles):.2f} to {max(angles):.2f} deg, "
            f"UP {sum(r.direction == 'UP' for r in folds)}, DOWN "
            f"{sum(r.direction == 'DOWN' for r in folds)}; not compensated, width error up to "
            f"{worst:.4f}; each one in the bend sheet (CSV) and the DXF notes"
        )
    return "\n".join(lines)
