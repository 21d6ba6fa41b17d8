"""SITE-order.csv: the site's bill of materials, one row per sheet and a
total, every number read from the sheet's report
(:func:`onefold_cad.fabrication.report.design_report`, the one its
NAME.json holds), never recomputed.

Columns: the sheet, its design's description, material and gauge (thickness), the stock
sheet (the designed sheet's size in its own frame), the blank (the cut
part: size, net area), the mass (with its unit), the cut length (outline
and relief hole), the number of bends and each one's angle and direction.
Lengths in the site's unit, areas in unit^2.
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
    "mass",
    "mass_unit",
    "cut_length",
    "bends",
    "bend_angles_deg",
    "bend_directions",
    "units",
)


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
        areas.append(rep.get("flat_area"))
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
                _or_blank(rep.get("flat_area")),
                "" if mass is None else mass["value"],
                "" if mass is None else mass["unit"],
                _or_blank(fp.get("cut_length")),
                len(halves),
                ";".join(f"{crease[k]['fold_angle_deg']:.3f}" for k in halves),
                ";".join(f"{k}:{crease[k]['bend']}" for k in halves),
                rep["units"],
            ]
        )
    units = {r[-1] for r in rows}
    mass_units = {r[10] for r in rows}

    def total(values: list[Any]) -> Any:
        return "" if any(v is None for v in values) else sum(values)

    rows.append(
        [
            "TOTAL", f"{len(rows)} sheets", "", "", "", "", "", "", total(areas),
            total(masses) if len(mass_units) == 1 else "", mass_units.pop() if len(mass_units) == 1
            else "", total(cuts), bends, "", "", units.pop() if len(units) == 1 else "",
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
