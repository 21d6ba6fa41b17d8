"""The JSON report of a design: its inputs and everything measured on its fold.

The report is plain JSON data (numbers, strings, lists, dicts): what
``onefold solve --json`` prints and ``onefold build`` writes as ``NAME.json``.
Lengths are in the design's unit (``units``), areas in unit^2, angles in
degrees, times in seconds.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.design import Design, relief_hole_diameter
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.flat_pattern import FlatPattern, flat_pattern
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import bend_values
from onefold_cad.geometry.placement import rest_form
from onefold_cad.geometry.thick_sheet import min_relief_hole
from onefold_cad.templates import design_to_data

__all__ = ["REPORT_VERSION", "design_report", "write_report", "report_json"]

#: Bumped when a key of the report changes meaning or disappears.
REPORT_VERSION = 1


def _floats(a: Any) -> list[Any]:
    return np.asarray(a, dtype=float).tolist()


def _resting(design: Design, folded: FoldedSheet) -> dict[str, Any]:
    """How the body the STEP holds stands (:func:`rest_form`)."""
    m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    exact = design.model.value == "exact"  # the rule of export.step.default_body
    body = "solid" if exact and m.thickness > 0.0 and m.relief_hole_diameter > 0.0 else "shell"
    return rest_form(folded, m, body).to_data(folded.apex)


def _crease(design: Design, folded: FoldedSheet) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for half in folded.crease:
        bv = bend_values(half.fold_angle_deg, design.material)
        out[half.name] = {
            "length": float(half.length),
            "fold_angle_deg": float(half.fold_angle_deg),
            "bend": half.bend,
            "bend_allowance": bv.allowance,
            "outside_setback": bv.outside_setback,
            "bend_deduction": bv.deduction,
            "end_flat": _floats(half.end_flat),
            "end_3d": _floats(half.end_3d),
        }
    return out


def _solid_min_hole(design: Design, folded: FoldedSheet) -> float | None:
    if design.model.value != "exact" or design.material.thickness <= 0.0:
        return None
    return float(min_relief_hole(folded, design.material))


def design_report(
    design: Design,
    folded: FoldedSheet,
    files: Iterable[str | os.PathLike[str]] = (),
    pattern: FlatPattern | None = None,
) -> dict[str, Any]:
    """Everything a fabricator or a test needs to know about one fold.

    Args:
        design: the design.
        folded: ``build_design(design)``.
        files: the files written for the design (listed by name).
        pattern: ``flat_pattern(design, folded)`` if already computed.

    Returns:
        A JSON-serialisable dict: ``inputs`` (the design as template data),
        ``apex_height``, ``angle_condition_error_deg``, ``gammas_deg`` (paper
        model, else null), ``fold_angles_deg`` and ``bend`` keyed
        ``plus_x``/``minus_x``, ``crease`` (per half: length, fold angle, bend
        direction, bend allowance, outside set-back and bend deduction),
        ``relief_hole_diameter``, ``solid_min_relief_hole`` (the smallest
        hole a STEP solid of this thickness needs; null for the paper model
        or zero thickness), ``flat_size`` and ``flat_area`` (the cut
        part: thickness-compensated outline, net of the relief hole),
        ``flat_pattern`` (its compensation shift and residual), ``sheet`` (the
        designed sheet: size in its own frame, area, perimeter, vertices),
        ``surface_area`` (measured on the folded surface), ``mass`` (if a
        density and thickness are given), ``resting`` (the STEP's body
        standing on the ground: bounding box, height, footprint, centre of
        mass, contacts, support polygon, tipping margin and its warnings;
        :meth:`RestingPlacement.to_data`),
        ``developability`` (measured errors), ``timings_s``
        (``direction_surface``, ``final_surface``) and ``files``.
    """
    sol, sheet, mat, m = folded.solution, folded.sheet, design.material, folded.metrics
    fp = flat_pattern(design, folded) if pattern is None else pattern
    own = sheet.to_sheet.apply(sheet.vertices)
    flat_size = own.max(axis=0) - own.min(axis=0)
    hole = relief_hole_diameter(design, folded)
    gammas = sol.gammas_deg
    crease = _crease(design, folded)
    mass = None
    if mat.density is not None and mat.thickness > 0.0:
        mass = mat.density * mat.thickness * fp.area
    return {
        "report_version": REPORT_VERSION,
        "name": design.name,
        "description": design.description,
        "units": design.units.value,
        "model": design.model.value,
        "inputs": design_to_data(design),
        "apex_height": float(sol.apex_height),
        "apex": _floats(sol.apex),
        "angle_sum_deg": float(sol.angle_sum_deg),
        "angle_condition_error_deg": float(sol.angle_condition_error_deg),
        "gammas_deg": None if gammas is None else _floats(gammas),
        "fold_angles_deg": {k: v["fold_angle_deg"] for k, v in crease.items()},
        "bend": {k: v["bend"] for k, v in crease.items()},
        "crease": crease,
        "relief_hole_diameter": float(hole),
        "solid_min_relief_hole": _solid_min_hole(design, folded),
        "flat_size": list(fp.size),
        "flat_area": float(fp.area),
        "flat_pattern": {
            "size": list(fp.size),
            "net_area": float(fp.area),
            "hole_diameter": float(fp.hole_diameter),
            "cut_hole_diameter": float(fp.cut_hole_diameter),
            "shift": float(fp.shift),
            "residual": float(fp.residual),
            "kerf": float(fp.kerf),
        },
        "sheet": {
            "kind": sheet.kind,
            "size": _floats(flat_size),
            "area": float(sheet.area),
            "perimeter": float(sheet.perimeter),
            "vertices": _floats(sheet.vertices),
        },
        "surface_area": float(m.area_3d),
        "mass": mass,
        "resting": _resting(design, folded),
        "developability": {
            "max_ruling_length_error": float(m.max_ruling_length_error),
            "max_boundary_segment_error": float(m.max_boundary_segment_error),
            "boundary_length_flat": float(m.boundary_length_flat),
            "boundary_length_3d": float(m.boundary_length_3d),
            "boundary_length_rel_error": float(m.boundary_length_rel_error),
            "area_flat": float(m.area_flat),
            "area_3d": float(m.area_3d),
            "area_rel_error": float(m.area_rel_error),
        },
        "timings_s": {
            "direction_surface": float(sol.time_direction_surface),
            "final_surface": float(folded.time_final_surface),
        },
        "files": [Path(f).name for f in files],
    }


def report_json(report: dict[str, Any]) -> str:
    """The report as indented JSON text (strict: no NaN or infinity)."""
    return json.dumps(report, indent=2, allow_nan=False) + "\n"


def write_report(path: str | os.PathLike[str], report: dict[str, Any]) -> Path:
    """Write ``report`` as JSON to ``path`` atomically (temp name, then rename).

    Raises:
        ExportError: the file could not be written or the report holds a
            non-finite number.
    """
    out = Path(path)
    try:
        text = report_json(report)
    except ValueError as exc:
        raise ExportError(f"report of {report.get('name')!r} is not valid JSON: {exc}") from exc
    with atomic_output(out) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return out
