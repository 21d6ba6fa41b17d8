"""The bend sheet for the press brake: one row per crease half.

Every number comes from the flat pattern and its bend model
(:mod:`onefold_cad.geometry.bend`); nothing is derived here. The same rows
are written as ``NAME-bends.csv`` (:func:`write_bend_csv`), printed by
``onefold build`` (:func:`bend_table`) and written in the DXF's NOTES.

Lengths are in the design's unit, angles in degrees, points in the blank's
(sheet's own) frame, the frame of the DXF.
"""

from __future__ import annotations

import csv
import io
import math
import os
from dataclasses import astuple, dataclass, fields
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from onefold_cad.export.atomic import atomic_output

if TYPE_CHECKING:
    from onefold_cad.design import Design
    from onefold_cad.export.flat_pattern import FlatPattern
    from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["BendRow", "bend_rows", "bend_table", "write_bend_csv"]


@dataclass(frozen=True)
class BendRow:
    """One crease half on the press brake (lengths in the design's unit).

    Attributes:
        half: 'plus_x' or 'minus_x'.
        direction: 'UP' or 'DOWN'.
        inside_face: 'top' or 'bottom': the flat sheet's face inside the bend
            (top: the face the DXF shows).
        fold_angle_deg: the bend angle from flat (deg).
        included_angle_deg: the angle between the flanges after bending (deg).
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
            halves' shifts; 0 when nothing is compensated).
        width_error: the blank's width across this half minus the bend
            model's, 2 (shift - shift_used).
        compensation: 'sharp' or 'none'.
        material: the material's name.
        units: the length unit.
    """

    half: str
    direction: str
    inside_face: str
    fold_angle_deg: float
    included_angle_deg: float
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
    compensation: str
    material: str
    units: str


def bend_rows(pattern: FlatPattern) -> tuple[BendRow, BendRow]:
    """The bend sheet's rows ('plus_x', 'minus_x') of ``pattern``."""
    rows = []
    for half, err in zip(pattern.halves, pattern.move.errors, strict=True):
        b = half.values
        d = half.end - half.start
        full = float(np.hypot(*d))
        start = half.start + d * (min(pattern.hole_diameter / 2.0, full) / full)
        rows.append(
            BendRow(
                half=half.name,
                direction=half.bend,
                inside_face=b.inside_face,
                fold_angle_deg=b.angle_deg,
                included_angle_deg=b.included_deg,
                start_x=float(start[0]),
                start_y=float(start[1]),
                end_x=float(half.end[0]),
                end_y=float(half.end[1]),
                length=float(math.hypot(*(half.end - start))),
                inside_radius=b.radius,
                thickness=b.thickness,
                k_factor=b.k_factor,
                reference=b.reference.value,
                allowance=b.allowance,
                deduction=b.deduction,
                setback=b.setback,
                shift=b.shift,
                shift_used=pattern.shift,
                width_error=err,
                compensation=pattern.compensation,
                material=pattern.material.name or "unspecified",
                units=pattern.units.value,
            )
        )
    return rows[0], rows[1]


def bend_table(pattern: FlatPattern) -> str:
    """The bend sheet as plain text (what ``build`` prints and the DXF notes hold)."""
    u = pattern.units.value
    m = pattern.material
    lines = [
        f"BEND SHEET ({u}, deg; blank frame as in the DXF): {m.name or 'material unspecified'}, "
        f"t = {m.thickness:g}, inside radius r = {pattern.halves[0].values.radius:g}, "
        f"K = {m.k_factor:g}",
    ]
    for r in bend_rows(pattern):
        lines.append(
            f"{r.half}: {r.direction} ({r.inside_face} face inside), fold {r.fold_angle_deg:.2f}, "
            f"included {r.included_angle_deg:.2f}; line ({r.start_x:.3f}, {r.start_y:.3f}) -> "
            f"({r.end_x:.3f}, {r.end_y:.3f}), length {r.length:.3f}"
        )
        lines.append(
            f"  {r.reference} reference: SB {r.setback:.4f}, BA {r.allowance:.4f}, "
            f"BD {r.deduction:.4f}, shift {r.shift:.4f}; blank moved {r.shift_used:.4f} "
            f"({r.compensation}), width error {round(r.width_error, 9) + 0.0:+.4f}"
        )
    return "\n".join(lines)


def bend_csv(pattern: FlatPattern) -> str:
    """The bend sheet as CSV text: a header row, then one row per crease half."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([f.name for f in fields(BendRow)])
    for row in bend_rows(pattern):
        writer.writerow(astuple(row))
    return out.getvalue()


def write_bend_csv(
    source: FlatPattern | Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    compensation: str = "sharp",
) -> Path:
    """Write ``NAME-bends.csv`` (atomically: nothing is written if anything fails).

    Args:
        source: a flat pattern, or a design (its pattern is computed with
            ``compensation``; ``folded`` is ``build_design(design)`` if given).
        path: the output file.
        folded: for a design: its fold, if already computed.
        compensation: for a design: 'sharp' or 'none'.

    Returns:
        The path written.
    """
    from onefold_cad.design import Design, build_design
    from onefold_cad.export.flat_pattern import flat_pattern

    if isinstance(source, Design):
        folded = build_design(source) if folded is None else folded
        source = flat_pattern(source, folded, compensation)
    text = bend_csv(source)
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
