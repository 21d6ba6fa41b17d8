"""SITE-order.csv: the site's bill of materials, one row per sheet and a
total, every number read from the sheet's report
(:func:`onefold_cad.fabrication.report.design_report`, the one its
NAME.json holds), never recomputed.

Columns: the sheet, its design's description, material and gauge (thickness), the stock
sheet (the designed sheet's size in its own frame), the blank (the cut
part: size, net area), the mass (with its unit), the cut length (outline
and relief hole), the number of bends and each one's angle and direction;
with the site's ``[loads]`` (``onefold loads`` on every sheet: the report's
``outdoors`` section) its feet, how many of them an anchor must hold down,
the anchors' pull and shear added over its feet (each foot's largest over
the cases, N), the ballast that would replace them (kg) and the case that
governs (empty without loads).
Lengths in the site's unit; the blank's area in ``area_unit``: m^2 for mm
sites, ft^2 for inch and foot sites (as one orders sheet metal; a 22 m^2
blank, not 22274271.6 mm^2).
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from onefold_cad.export.atomic import atomic_output

__all__ = ["ORDER_COLUMNS", "order_csv", "order_rows", "write_order_csv"]

#: The CSV's header row.
ORDER_COLUMNS = (
    "sheet",
    "description",
    "material",
    "thickness",
    "stock_width",
    "stock_height",
    "blank_width",
    "blank_height",
    "blank_area",
    "area_unit",
    "mass",
    "mass_unit",
    "cut_length",
    "bends",
    "bend_angles_deg",
    "bend_directions",
    "units",
    "feet",
    "anchors",
    "anchor_pull_N",
    "anchor_shear_N",
    "ballast_kg",
    "governing_case",
)


#: The unit a blank's area is ordered in, and unit^2 per it, by the length unit.
AREA_UNITS = {"mm": ("m^2", 1e6), "m": ("m^2", 1.0), "in": ("ft^2", 144.0), "ft": ("ft^2", 1.0)}


def _area(value: Any, units: str) -> Any:
    """An area in the design's unit^2 as ordered (m^2 or ft^2), or None."""
    return None if value is None else value / AREA_UNITS[units][1]


def _anchors(rep: Mapping[str, Any]) -> list[Any]:
    """The outdoors columns of one report (blank without its section)."""
    o = rep.get("outdoors")
    if o is None:
        return [""] * 6
    t = o["totals"]
    return [t["feet"], t["anchored_feet"], t["tension_N"], t["shear_N"], t["ballast_kg"],
            o["governing"]]  # fmt: skip


def _number(value: Any) -> Any:
    """Floats with 10 significant digits (the reports' values, without the
    binary rounding's tail: 7315.2, not 7315.199999999999)."""
    return f"{value:.10g}" if isinstance(value, float) else value


def _or_blank(value: Any) -> Any:
    return "" if value is None else value


def order_rows(reports: Sequence[tuple[str, Mapping[str, Any]]]) -> list[list[Any]]:
    """One row per ``(sheet name, report)`` then a ``TOTAL`` row (the masses
    added up when every sheet has one, the blank areas and cut lengths)."""
    rows: list[list[Any]] = []
    masses, areas, cuts, bends = [], [], [], 0
    for name, rep in reports:
        m = rep["inputs"].get("material", {})
        fp = rep.get("flat_pattern") or {}
        blank = rep.get("flat_size") or [None, None]
        crease = rep["crease"]
        halves = [k for k, v in crease.items() if abs(v["fold_angle_deg"]) > 0.0]
        mass = rep.get("mass")
        masses.append(None if mass is None else mass["value"])
        area = _area(rep.get("flat_area"), rep["units"])
        areas.append(area)
        cuts.append(fp.get("cut_length"))
        bends += len(halves)
        rows.append(
            [
                name,
                rep["description"],
                m.get("name", ""),
                m.get("thickness", ""),
                *rep["sheet"]["size"],
                _or_blank(blank[0]),
                _or_blank(blank[1]),
                _or_blank(area),
                AREA_UNITS[rep["units"]][0],
                "" if mass is None else mass["value"],
                "" if mass is None else mass["unit"],
                _or_blank(fp.get("cut_length")),
                len(halves),
                ";".join(f"{crease[k]['fold_angle_deg']:.3f}" for k in halves),
                ";".join(f"{k}:{crease[k]['bend']}" for k in halves),
                rep["units"],
                *_anchors(rep),
            ]
        )
    units = {r[16] for r in rows}
    mass_units = {r[11] for r in rows}
    area_units = {r[9] for r in rows}

    def total(values: list[Any]) -> Any:
        return "" if any(v is None for v in values) else sum(values)

    loads = [r[-6:] for r in rows]
    sums = [
        "" if any(v == "" for v in col) else sum(col) for col in list(zip(*loads, strict=True))[:5]
    ]
    rows.append(
        [
            "TOTAL", f"{len(rows)} sheets", "", "", "", "", "", "",
            total(areas) if len(area_units) == 1 else "",
            area_units.pop() if len(area_units) == 1 else "",
            total(masses) if len(mass_units) == 1 else "", mass_units.pop() if len(mass_units) == 1
            else "", total(cuts), bends, "", "", units.pop() if len(units) == 1 else "",
            *sums, "",
        ]
    )  # fmt: skip
    return rows


def order_csv(reports: Sequence[tuple[str, Mapping[str, Any]]]) -> str:
    """The order as CSV text: the header, a row per sheet, the total."""
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(ORDER_COLUMNS)
    w.writerows([[_number(v) for v in row] for row in order_rows(reports)])
    return out.getvalue()


def write_order_csv(
    reports: Sequence[tuple[str, Mapping[str, Any]]], path: str | os.PathLike[str]
) -> Path:
    """Write SITE-order.csv atomically; return the path."""
    text = order_csv(reports)
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
