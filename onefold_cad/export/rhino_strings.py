"""The user strings of the .3dm and of the folded form's Breps: the design's
parameters (as its template has them) and the report's key numbers, read
from :func:`onefold_cad.fabrication.report.design_report` (never recomputed).

Keys are dotted paths: ``frame.alpha``, ``material.thickness``, ... for the
design; ``report.`` + the report's key (:data:`KEY_NUMBERS`, e.g.
``report.fold_angles_deg.plus_x``, ``report.resting.tipping_margin_deg``)
for its numbers, in the report's units (the design's length unit, degrees,
``mass.unit``). A string value is the string itself; any other value is its
JSON (numbers at full precision, lists as JSON lists, ``null`` for a number
the report leaves out, e.g. the mass of a material without a density).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from onefold_cad.choices import Body, Compensation
from onefold_cad.design import Design
from onefold_cad.fabrication.flat_pattern import FlatPattern
from onefold_cad.fabrication.report import design_report
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.templates import design_to_data

__all__ = ["KEY_NUMBERS", "design_strings", "report_strings", "user_string"]

#: The report's keys (dotted paths) written as ``report.<key>`` user strings.
KEY_NUMBERS: tuple[str, ...] = (
    "report_version",
    "fold_angles_deg.plus_x",
    "fold_angles_deg.minus_x",
    "bend.plus_x",
    "bend.minus_x",
    "crease.plus_x.length",
    "crease.minus_x.length",
    "direction_surface.apex_height",
    "angle_sum_deg",
    "resting.height",
    "resting.span",
    "resting.tilt_deg",
    "resting.stable",
    "resting.tipping_margin_deg",
    "sheet.area",
    "surface_area",
    "flat_area",
    "flat_size",
    "relief_hole_diameter",
    "mass.value",
    "mass.unit",
    "warnings",
)


def user_string(value: Any) -> str:
    """A value as a user string: a string as itself, anything else as JSON."""
    return value if isinstance(value, str) else json.dumps(value)


def _flatten(data: Mapping[str, Any], prefix: str = "") -> dict[str, str]:
    out: dict[str, str] = {}
    for key, value in data.items():
        if isinstance(value, Mapping):
            out.update(_flatten(value, f"{prefix}{key}."))
        else:
            out[f"{prefix}{key}"] = str(value)
    return out


def design_strings(design: Design) -> dict[str, str]:
    """The design's parameters as its template has them, flattened to
    dotted keys (``frame.alpha``, ``sheet.kind``, ...)."""
    return _flatten(design_to_data(design))


def _lookup(report: Mapping[str, Any], path: str) -> Any:
    value: Any = report
    for part in path.split("."):
        if not isinstance(value, Mapping):
            return None  # under a null section (no mass, no flat pattern)
        value = value.get(part)
    return value


def report_strings(
    design: Design,
    folded: FoldedSheet,
    *,
    pattern: FlatPattern | None = None,
    compensation: Compensation | str = Compensation.SHARP,
    body: Body | None = None,
) -> dict[str, str]:
    """``report.<key>`` -> value for every key of :data:`KEY_NUMBERS`, from
    the design's report (with ``pattern``, ``compensation`` and ``body`` as
    :func:`~onefold_cad.fabrication.report.design_report` takes them)."""
    report = design_report(design, folded, pattern=pattern, compensation=compensation, body=body)
    return {f"report.{key}": user_string(_lookup(report, key)) for key in KEY_NUMBERS}
