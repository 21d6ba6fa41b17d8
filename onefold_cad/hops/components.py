"""What the Hops components compute: ``onefold/solve`` and ``onefold/fit``.

Each takes the values :func:`~onefold_cad.hops.inputs.read_values` read and
returns an :class:`Answer`: one value (or list) per output, in the
component's order, and the warnings. Nothing is computed here that the
commands do not: a design is made from its template and flags as ``onefold
solve`` makes it (:func:`~onefold_cad.flags.jobs.load_jobs`), its numbers are
the report's (:func:`~onefold_cad.fabrication.report.design_report`, as
``onefold solve --json`` prints them), its geometry the .3dm writer's and
the flat pattern's (:mod:`onefold_cad.export.hops_geometry`), the fit
:func:`~onefold_cad.fit.fit_design`'s (as ``onefold fit --json``).
Lengths are in the design's unit, angles in degrees.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from onefold_cad.choices import Placement
from onefold_cad.errors import InvalidParameterError
from onefold_cad.hops.inputs import FIT_INPUTS, SOLVE_INPUTS, flag_args, parse_solve_args

__all__ = [
    "FIT_OUTPUTS",
    "SOLVE_OUTPUTS",
    "Answer",
    "HopsOutput",
    "fit_answer",
    "solve_answer",
    "units_warning",
]


@dataclass(frozen=True)
class HopsOutput:
    """One output of a Hops component.

    Attributes:
        name: its ParamName.
        kind: 'brep', 'line', 'point', 'curve', 'number' or 'text'.
        description: what Grasshopper shows for it.
        many: a list (else one item).
    """

    name: str
    kind: str
    description: str
    many: bool = False


@dataclass(frozen=True)
class Answer:
    """A component's outputs (one entry per output, a list where ``many``)
    and its warnings (one line each)."""

    values: tuple[Any, ...]
    warnings: tuple[str, ...] = ()


#: The outputs of ``onefold/solve``, in the component's order.
SOLVE_OUTPUTS: tuple[HopsOutput, ...] = (
    HopsOutput("breps", "brep", "the folded form: NURBS faces on the exact cone, as the "
               ".3dm's", True),
    HopsOutput("creases", "line", "the crease halves plus_x, minus_x: apex to the sheet's "
               "edge", True),
    HopsOutput("apex", "point", "the apex (H on the folded form)"),
    HopsOutput("outline", "curve", "flat pattern: the cut outline (sheet frame, z = 0)", True),
    HopsOutput("relief_hole", "curve", "flat pattern: the relief hole's cut circle (if any)", True),
    HopsOutput("bend_lines", "curve", "flat pattern: the bend lines (plus_x, minus_x, then the "
               "paper model's ruling folds)", True),
    HopsOutput("bends", "text", "UP or DOWN for each bend line", True),
    HopsOutput("fold_angles", "number", "fold angles of the crease halves plus_x, minus_x (deg)",
               True),
    HopsOutput("height", "number", "height of the resting form (report: resting.height)"),
    HopsOutput("span", "number", "footprint width of the resting form (resting.span)"),
    HopsOutput("tipping_margin", "number", "tipping margin of the resting form, deg "
               "(resting.tipping_margin_deg)"),
    HopsOutput("warnings", "text", "the design's warnings (as onefold solve prints them)", True),
    HopsOutput("report", "text", "the JSON report, as onefold solve --json prints it"),
)  # fmt: skip

#: The outputs of ``onefold/fit``.
FIT_OUTPUTS: tuple[HopsOutput, ...] = (
    HopsOutput("alpha", "number", "the found arc opening alpha (deg)"),
    HopsOutput("beta", "number", "the found tilt beta (deg)"),
    HopsOutput("hc", "number", "the found offset h_c"),
    HopsOutput("height", "number", "height of the found resting form"),
    HopsOutput("span", "number", "footprint width of the found resting form"),
    HopsOutput("depth", "number", "footprint depth of the found resting form"),
    HopsOutput("tipping_margin", "number", "its tipping margin (deg)"),
    HopsOutput("report", "text", "the result as JSON, as onefold fit --json prints it"),
)

#: Rhino's unit systems (a Hops request's ``modelunits``) by the design's unit.
RHINO_UNITS = {"mm": "Millimeters", "m": "Meters", "in": "Inches", "ft": "Feet"}


def units_warning(design_units: str, model_units: object) -> str | None:
    """A warning when the Rhino document's unit (``modelunits`` of the Hops
    request, e.g. 'Millimeters') is not the design's: lengths are never converted."""
    want = RHINO_UNITS.get(design_units)
    if not isinstance(model_units, str) or not model_units or model_units == want:
        return None
    name = _UNIT_NAMES.get(design_units, design_units)
    return (
        f"the design's lengths are in {name} (units {design_units!r}) and the Rhino "
        f"document's in {model_units}: they are not converted (open a document in {want}, "
        "or set the units input to the document's)"
    )


#: The design units' names in a sentence.
_UNIT_NAMES = {"mm": "millimetres", "m": "metres", "in": "inches", "ft": "feet"}


def _sheet_text(curve: Mapping[str, Any]) -> str:
    """``--polygon``'s text of a Hops curve (a closed polyline)."""
    from onefold_cad.errors import InvalidSheetError
    from onefold_cad.export.hops_geometry import decode, sheet_polygon

    try:
        obj = decode(dict(curve))
    except Exception:  # rhino3dm refuses what is not its JSON
        obj = None
    if obj is None:
        raise InvalidSheetError("sheet", "is not a curve rhino3dm can read")
    return ";".join(f"{x!r},{y!r}" for x, y in sheet_polygon(obj))


def solve_answer(values: Mapping[str, Any], model_units: object = None) -> Answer:
    """``onefold/solve``: the design of ``values`` (see
    :data:`~onefold_cad.hops.inputs.SOLVE_INPUTS`) solved and reported as
    ``onefold solve --json`` does, its folded form placed as ``placement``
    says and its flat pattern; the outputs of :data:`SOLVE_OUTPUTS`. With
    the Rhino document's unit (``model_units``, the request's
    ``modelunits``) it warns when that is not the design's
    (:func:`units_warning`).

    Raises:
        UsageError, OneFoldError: a value the command refuses (its message).
    """
    from onefold_cad.design import fold_design
    from onefold_cad.export.hops_geometry import (
        crease_lines,
        flat_curves,
        point,
    )
    from onefold_cad.export.rhino_sides import placement_of, side_breps
    from onefold_cad.fabrication.relief_hole import relief_hole_problem
    from onefold_cad.fabrication.report import (
        check_finite,
        design_report,
        report_flat_pattern,
        report_json,
    )
    from onefold_cad.flags.jobs import load_jobs

    given = dict(values)
    if given.get("sheet") is not None:
        given["sheet"] = _sheet_text(given["sheet"])
    flags, placed = parse_solve_args(flag_args(SOLVE_INPUTS, given))
    placement = Placement.parse(placed)
    template = given.get("template")
    (job,) = load_jobs([template] if template is not None else [], flags)
    design = job.design
    folded = fold_design(design)
    report = design_report(design, folded, sources=job.sources)
    check_finite(report)
    notes = list(report["warnings"])
    units = units_warning(design.units.value, model_units)
    if units is not None:
        notes.append(units)
    problem = relief_hole_problem(design, folded)
    if problem is None:
        breps = [brep for _, brep in side_breps(design, folded, placement)]
    else:  # as the .3dm writer: no faces past a hole that does not fit
        breps = []
        notes.append(f"{problem} (no Breps: the .3dm writer refuses them too)")
    pattern = report_flat_pattern(design, folded)  # the report's (made once per design)
    flat = None if pattern is None else flat_curves(pattern)
    rest = report["resting"]
    place, _ = placement_of(design, folded, placement)
    return Answer(
        (
            breps,
            crease_lines(folded, place),
            point(place(folded.apex[None, :])[0]),
            [] if flat is None else [flat.outline],
            [] if flat is None or flat.relief_hole is None else [flat.relief_hole],
            [] if flat is None else flat.bend_lines,
            [] if flat is None else flat.bends,
            [report["fold_angles_deg"]["plus_x"], report["fold_angles_deg"]["minus_x"]],
            rest["height"],
            rest["span"],
            rest["tipping_margin_deg"],
            notes,
            report_json(report),
        ),
        tuple(notes),
    )


def fit_answer(values: Mapping[str, Any]) -> Answer:
    """``onefold/fit``: the frame whose resting form has the target height and
    span (and depth) for the template's sheet and material, as ``onefold fit``
    finds it; the outputs of :data:`FIT_OUTPUTS`.

    Raises:
        OneFoldError: a target that is not a positive length, or out of reach
            (the ranges the template's sheet reaches).
    """
    from onefold_cad.fit import fit_design
    from onefold_cad.flags.jobs import load_jobs
    from onefold_cad.templates import DEFAULT_TEMPLATE

    names = [inp.name for inp in FIT_INPUTS]
    template, height, span, depth, margin = (values.get(n) for n in names)
    if height is None or span is None:  # read_values refuses a request without them
        raise InvalidParameterError("height" if height is None else "span", "is required")
    (job,) = load_jobs([DEFAULT_TEMPLATE if template is None else template], {})
    result = fit_design(job.design, height, span, depth, margin)
    data = result.to_data()
    frame, got = data["frame"], data["achieved"]
    assert isinstance(frame, dict) and isinstance(got, dict)
    return Answer(
        (
            frame["alpha"],
            frame["beta"],
            frame["h_c"],
            got["height"],
            got["span"],
            got["depth"],
            got["tipping_margin_deg"],
            json.dumps(data, indent=2, allow_nan=False),
        )
    )
