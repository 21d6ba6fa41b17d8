"""The JSON report of a design: its inputs and everything measured on its fold.

The report is plain JSON data (numbers, strings, lists, dicts): what
``onefold solve --json`` prints and ``onefold build`` writes as ``NAME.json``.
Lengths are in the design's unit (``units``), areas in unit^2, angles in
degrees, times in seconds, the mass in ``mass.unit`` (kg or lb) and the
density in kg/m^3. Every number is checked to be finite before the report
is printed or written (:func:`check_finite`).

Numpy and the geometry core only; the file is written by
:func:`onefold_cad.export.report_file.write_report`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.choices import Body, Compensation
from onefold_cad.design import Design, derived
from onefold_cad.errors import (
    ExportError,
    FabricationError,
    InvalidParameterError,
    NoSolutionError,
    OneFoldError,
)
from onefold_cad.fabrication.bend_checks import bend_error, check_bends
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern_once
from onefold_cad.fabrication.mass import design_mass
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, solid_min_relief_hole
from onefold_cad.fabrication.rules import (
    fabrication_warnings,
    resting_placement,
    solid_bend_problem,
    solid_problem,
)
from onefold_cad.geometry.bend_model import bendable, crease_bends
from onefold_cad.geometry.developability import developability
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import edge_lengths_2d
from onefold_cad.geometry.placement import stability_warnings
from onefold_cad.templates import design_to_data

__all__ = [
    "REPORT_VERSION",
    "check_finite",
    "cut_length",
    "design_report",
    "design_warnings",
    "report_flat_pattern",
    "report_json",
    "report_warnings",
    "resting_numbers",
]

#: Bumped when a key of the report changes meaning or disappears.
#: 2: ``apex_height``/``apex`` moved to ``direction_surface``; ``mass`` became
#: ``{value, unit, density}``; ``warnings``, ``sources``, ``resting.span`` added;
#: the flat pattern keys are null when the flat pattern cannot be made.
REPORT_VERSION = 2

#: What the paper's h is, said wherever it is printed.
APEX_HEIGHT_MEANING = (
    "the paper's h: height of the direction-surface apex A above H for the frame "
    "curve of radius R; it scales with R, not with the sheet (the folded form's "
    "size is under 'resting')"
)


def _floats(a: Any) -> list[Any]:
    return np.asarray(a, dtype=float).tolist()


def resting_numbers(
    design: Design, folded: FoldedSheet, body: Body | None = None
) -> dict[str, Any]:
    """The report's ``resting`` section: how the body the STEP holds (``body``,
    default :func:`~onefold_cad.fabrication.rules.default_body`) stands on the ground
    (:func:`~onefold_cad.fabrication.rules.resting_placement`): its exact
    bounding box, height, footprint (width along the resting frame's x axis,
    the fold line's direction, depth across it, and the area of its shadow),
    ``span`` (the footprint's width: what ``onefold fit --span`` aims at),
    apex, tilt, centre of mass, contacts, support polygon, tipping margin and
    edge, and the stability warnings. The 3D preview's caption reads it too."""
    rest = resting_placement(design, folded, body)
    data = rest.to_data(folded.apex)
    data["span"] = data["footprint"]["width"]
    data["warnings"] = stability_warnings(rest, design.units.value)  # worded as solve warns
    return data


def _crease(design: Design, folded: FoldedSheet) -> dict[str, Any]:
    out: dict[str, Any] = {}
    if all(bendable(c.fold_angle_deg) for c in folded.crease):
        bends: tuple[Any, Any] = crease_bends(folded, design.material)
    else:
        bends = (None, None)
    for half, bv in zip(folded.crease, bends, strict=True):
        # a crease folded flat onto itself has no bend model (its warning says so)
        out[half.name] = {
            "length": float(half.length),
            "fold_angle_deg": float(half.fold_angle_deg),
            "bend": half.bend,
            "bend_allowance": None if bv is None else bv.allowance,
            "outside_setback": None if bv is None else bv.outside_setback,
            "bend_deduction": None if bv is None else bv.deduction,
            "reference_surface": None if bv is None else bv.reference.value,
            "setback": None if bv is None else bv.setback,
            "shift": None if bv is None else bv.shift,
            "end_flat": _floats(half.end_flat),
            "end_3d": _floats(half.end_3d),
        }
    return out


def _solid_min_hole(design: Design, folded: FoldedSheet, warnings: list[str]) -> float | None:
    if design.model.value != "exact" or design.material.thickness <= 0.0:
        return None
    try:
        return solid_min_relief_hole(folded, design.material)
    except InvalidParameterError as exc:  # e.g. a flat fold has no mitre
        if not any(str(exc) in w for w in warnings):  # design_warnings' "no STEP solid"
            warnings.append(str(exc))
        return None


def report_flat_pattern(
    design: Design,
    folded: FoldedSheet,
    warnings: list[str] | None = None,
    compensation: Compensation | str = Compensation.SHARP,
) -> FlatPattern | None:
    """The flat pattern the report measures (its size, net area and mass):
    past the bend model's limits the uncompensated one; None when the writer
    refuses it, with its refusal appended to ``warnings`` (if given)."""
    warnings = [] if warnings is None else warnings
    try:
        try:
            return flat_pattern_once(design, folded, compensation)
        except FabricationError as exc:  # past the bend model's limits: design_warnings names them
            bends = bend_error(check_bends(folded, design.material, design.units))
            if bends is None or str(exc) != str(bends):
                raise  # not a bend limit (a relief hole that does not fit, ...)
            return flat_pattern_once(design, folded, "none")
    except OneFoldError as exc:  # the writer's parameter checks (hole, kerf)
        if not any(str(exc) in w for w in warnings):  # said already
            warnings.append(f"{exc} (flat pattern; build refuses the DXF)")
        return None


def cut_length(fp: FlatPattern) -> float:
    """The laser's path (length): the cutting outline's perimeter and the relief
    hole's cutting circle (none when the hole is 0)."""
    return float(edge_lengths_2d(fp.cut_outline).sum() + math.pi * fp.cut_hole_diameter)


def _pattern_keys(design: Design, fp: FlatPattern | None) -> dict[str, Any]:
    if fp is None:
        return {"flat_size": None, "flat_area": None, "flat_pattern": None, "mass": None}
    mass = design_mass(design, fp.area)
    return {
        "flat_size": list(fp.size),
        "flat_area": float(fp.area),
        "flat_pattern": {
            "size": list(fp.size),
            "net_area": float(fp.area),
            "hole_diameter": float(fp.hole_diameter),
            "cut_hole_diameter": float(fp.cut_hole_diameter),
            "shift": float(fp.shift),
            "residual": float(fp.residual),
            "compensation": fp.compensation,
            "bend_problems": [q.message for q in fp.problems],
            "kerf": float(fp.kerf),
            "cut_length": cut_length(fp),
        },
        "mass": None
        if mass is None
        else {"value": mass.value, "unit": mass.unit, "density": mass.density},
    }


def design_warnings(
    design: Design,
    folded: FoldedSheet,
    compensation: Compensation | str = Compensation.SHARP,
    body: Body | None = None,
) -> list[str]:
    """What ``solve`` and ``build`` warn about before any writer runs, one
    line each: the solver's own warnings (when it gives any),
    :func:`~onefold_cad.fabrication.rules.fabrication_warnings`, the resting form's
    stability (a tipping margin below 5 deg,
    :func:`~onefold_cad.geometry.placement.stability_warnings`, for ``body``
    as :func:`resting_numbers` places it) and the bend model's
    limits (:func:`~onefold_cad.fabrication.bend_checks.check_bends`), worded for what
    ``build`` does with ``compensation`` ('sharp': refuses the flat pattern's
    files, and the STEP solid unless only the blank's width is off; 'none':
    writes the uncompensated blank)."""
    comp = Compensation.parse(compensation)
    problems = check_bends(folded, design.material, design.units)
    error = bend_error(problems)
    bends = []
    closed = bool(problems) and problems[0].kind == "closed"  # alone: no bend model at all
    if error is not None and comp is Compensation.NONE and not closed:
        bends.append(
            f"{error}; with --compensation none build writes the uncompensated blank (the "
            "designed outline; its notes say so) and the STEP as designed"
        )
    elif closed:  # whatever the compensation
        bends.append(f"{error}; build refuses the DXF, cut DXF, bend sheet and flat preview")
    elif error is not None:
        solid_refused = solid_bend_problem(design, folded) is not None  # the writers' check
        refused = "the DXF, cut DXF, bend sheet and flat preview" + (
            " and a STEP solid and its GLB" if solid_refused else ""
        )
        bends.append(
            f"{error}; build refuses {refused} (--compensation none writes the uncompensated blank)"
        )
    try:
        stability = stability_warnings(resting_placement(design, folded, body), design.units.value)
    except (InvalidParameterError, NoSolutionError):  # no such body: its writer says why
        stability = []
    solid = solid_problem(design, folded) if body is None else None
    if solid is not None:  # the default solid cannot be made: the shell stands instead
        stability.insert(
            0,
            f"no STEP solid: {solid}; the form stands and is rated as its reference surface "
            "(zero thickness), and build refuses the solid",
        )
    return [
        *getattr(folded.solution, "warnings", ()),
        *fabrication_warnings(design, folded),
        *stability,
        *bends,
    ]


def report_warnings(
    design: Design,
    folded: FoldedSheet,
    pattern: FlatPattern | None = None,
    *,
    warnings: Iterable[str] = (),
    compensation: Compensation | str = Compensation.SHARP,
    body: Body | None = None,
) -> tuple[list[str], FlatPattern | None, float | None]:
    """The report's ``warnings`` (``warnings`` given, then
    :func:`design_warnings`, the flat pattern's refusal and the solid's relief
    hole problem: in order, each once), the flat pattern it measures
    (``pattern`` if given, else :func:`report_flat_pattern`) and
    ``solid_min_relief_hole`` (length, None when not defined): what
    :func:`design_report` says about them, without its measurements of the
    surface (the explorer's page shows these on every move)."""
    comp = Compensation.parse(compensation)
    notes = [*warnings, *design_warnings(design, folded, comp, body)]
    fp = report_flat_pattern(design, folded, notes, comp) if pattern is None else pattern
    solid_hole = _solid_min_hole(design, folded, notes)
    return list(dict.fromkeys(notes)), fp, solid_hole


def design_report(
    design: Design,
    folded: FoldedSheet,
    files: Iterable[str | os.PathLike[str]] = (),
    pattern: FlatPattern | None = None,
    *,
    sources: Mapping[str, str] | None = None,
    timings: Mapping[str, float] | None = None,
    warnings: Iterable[str] = (),
    compensation: Compensation | str = Compensation.SHARP,
    body: Body | None = None,
    step: Mapping[str, Any] | None = None,
    rhino: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """Everything a fabricator or a test needs to know about one fold.

    The geometry is always reported; what a writer would refuse (a flat
    pattern that cannot be made, a relief hole that does not fit, ...) is a
    line in ``warnings`` and the keys that depend on it are null.

    Args:
        design: the design.
        folded: ``fold_design(design)``.
        files: the files written for the design (listed by name).
        pattern: ``flat_pattern(design, folded)`` if already computed.
        sources: where each input came from, keyed like the template
            (``material.thickness`` -> ``--thickness``, ``template NAME``,
            ``inherited from template NAME`` or ``default``).
        timings: further stage times (s) to report, e.g. ``{"step": 2.1}``.
        warnings: warnings found elsewhere, added before the report's own.
        compensation: the flat pattern's ('sharp' or 'none', as ``build
            --compensation``); past the bend model's limits a 'sharp' report
            gives the uncompensated pattern's numbers, with the warning.
        body: the STEP's body ('solid', 'shell'; None: the default), which
            the ``resting`` section places.
        step: what the STEP writer built, when it did (``build``): ``body``,
            ``placement`` and the part's ``fit_deviation`` and
            ``fit_tolerance`` (length); the report itself never runs the CAD
            kernel.
        rhino: what the .3dm writer wrote, when it did (``build``):
            ``placement``, ``faces`` and the faces' ``fit_deviation`` and
            ``fit_tolerance`` (length).

    Returns:
        A JSON-serialisable dict: ``inputs`` (the design as template data),
        ``sources``, ``direction_surface`` (``apex_height``: the paper's h
        at ``frame_radius`` R, ``apex``, ``apex_height_error`` (a bound on
        its distance to the exact root), and the problem's conditioning:
        ``ds_dh`` (dS/dh at the root, rad per length) and ``s_max_minus_pi``
        (how far one side's angle sum rises above 180 deg, rad)),
        ``angle_sum_deg``, ``angle_condition_error_deg`` (a verified bound on
        |sum of the apex angles - 360 deg|, evaluated independently of the
        search), ``gammas_deg`` (paper model, else
        null), ``fold_angles_deg`` and ``bend`` keyed ``plus_x``/``minus_x``,
        ``crease`` (per half: length, fold angle, bend direction, bend
        allowance, outside set-back and bend deduction),
        ``relief_hole_diameter``, ``solid_min_relief_hole`` (the smallest
        hole a STEP solid of this thickness needs; null for the paper model
        or zero thickness), ``flat_size`` and ``flat_area`` (the cut part:
        thickness-compensated outline, net of the relief hole),
        ``flat_pattern`` (its compensation shift and residual, the ``cut_length``), ``sheet``
        (the designed sheet: size in its own frame, area, perimeter,
        vertices), ``surface_area`` (measured on the folded surface),
        ``mass`` (``{value, unit, density}`` or null), ``resting`` (the form
        standing on the ground: bounding box, height, span, footprint),
        ``developability`` (measured errors), ``step`` (as given, or null),
        ``warnings``, ``timings_s`` and ``files``.
    """
    sol, sheet = folded.solution, folded.sheet
    m = derived(folded, "developability", lambda: developability(folded))
    notes, fp, solid_hole = report_warnings(
        design, folded, pattern, warnings=warnings, compensation=compensation, body=body
    )
    own = sheet.to_sheet.apply(sheet.vertices)
    flat_size = own.max(axis=0) - own.min(axis=0)
    gammas = sol.gammas_deg
    crease = _crease(design, folded)
    stage_times = {"direction_surface": float(sol.time_direction_surface)}
    stage_times["final_surface"] = float(folded.time_final_surface)
    stage_times.update({k: float(v) for k, v in (timings or {}).items()})
    return {
        "report_version": REPORT_VERSION,
        "name": design.name,
        "description": design.description,
        "units": design.units.value,
        "model": design.model.value,
        "inputs": design_to_data(design),
        "sources": dict(sources or {}),
        "direction_surface": {
            "apex_height": float(sol.apex_height),
            "frame_radius": float(design.frame.radius),
            "apex": _floats(sol.apex),
            "meaning": APEX_HEIGHT_MEANING,
            "apex_height_error": float(sol.apex_height_error),
            "ds_dh": float(sol.ds_dh),
            "s_max_minus_pi": float(sol.s_max_minus_pi),
        },
        "angle_sum_deg": float(sol.angle_sum_deg),
        "angle_condition_error_deg": float(sol.angle_condition_error_deg),
        "gammas_deg": None if gammas is None else _floats(gammas),
        "fold_angles_deg": {k: v["fold_angle_deg"] for k, v in crease.items()},
        "bend": {k: v["bend"] for k, v in crease.items()},
        "crease": crease,
        "relief_hole_diameter": float(relief_hole_diameter(design, folded)),
        "solid_min_relief_hole": solid_hole,
        **_pattern_keys(design, fp),
        "sheet": {
            "kind": sheet.kind,
            "size": _floats(flat_size),
            "area": float(sheet.area),
            "perimeter": float(sheet.perimeter),
            "vertices": _floats(sheet.vertices),
        },
        "surface_area": float(m.area_3d),
        "resting": resting_numbers(design, folded, body),
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
        "step": None if step is None else dict(step),
        "rhino": None if rhino is None else dict(rhino),
        "warnings": notes,
        "timings_s": stage_times,
        "files": [Path(f).name for f in files],
    }


def check_finite(report: Mapping[str, Any], where: str = "") -> None:
    """Raise :class:`ExportError` naming the first key whose number is NaN or
    infinite (``resting.height``, ``crease.plus_x.end_3d[2]``)."""

    def walk(value: Any, key: str) -> None:
        if isinstance(value, float) and not math.isfinite(value):
            raise ExportError(
                f"the report of {report.get('name')!r} has {key} = {value}: not a finite "
                "number (the computation failed for this design); nothing written"
            )
        if isinstance(value, Mapping):
            for k, v in value.items():
                walk(v, f"{key}.{k}" if key else str(k))
        elif isinstance(value, list | tuple):
            for i, v in enumerate(value):
                walk(v, f"{key}[{i}]")

    walk(report, where)


def report_json(report: Mapping[str, Any]) -> str:
    """The report as indented JSON text, after :func:`check_finite`."""
    import json  # here: solve's text summary needs none

    check_finite(report)
    return json.dumps(report, indent=2, allow_nan=False) + "\n"
