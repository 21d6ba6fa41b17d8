"""The bend sheet as ``NAME-bends.csv``: the rows of the bend table
(:func:`onefold_cad.fabrication.bend_table.bend_rows`), a header row first.

Numbers are rounded to what a press brake and a tape can use, and each
header cell names its step: angles to 0.01 deg (``fold_angle_deg [0.01
deg]``), lengths to 0.01 mm (0.00001 m), 0.001 in or 0.0001 ft (``length [0.01 mm]``).
The material's own values (r, t, K) are written as given.
"""

from __future__ import annotations

import csv
import io
import math
import os
from dataclasses import astuple, fields
from pathlib import Path

from onefold_cad.choices import Compensation
from onefold_cad.design import Design, fold_design
from onefold_cad.export.atomic import atomic_output
from onefold_cad.fabrication.bend_table import BendRow, bend_rows
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern_once
from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["bend_csv", "csv_rows", "write_bend_csv"]


#: Decimals of a rounded length, by the design's unit (0.01 mm, 0.001 in, 0.0001 ft).
LENGTH_DECIMALS = {"mm": 2, "m": 5, "in": 3, "ft": 4}
#: Decimals of a rounded angle (0.01 deg).
ANGLE_DECIMALS = 2
#: The columns written as given (the material's values).
_AS_GIVEN = ("inside_radius", "thickness", "k_factor")


def _decimals(name: str, units: str, as_given: tuple[str, ...]) -> int | None:
    """The decimals column ``name`` is rounded to (None: written as given or text)."""
    if name.endswith("_deg"):
        return ANGLE_DECIMALS
    if name in as_given:
        return None
    return LENGTH_DECIMALS[units]


def csv_rows(names: list[str], rows: list[tuple[object, ...]], units: str,
             as_given: tuple[str, ...] = ()) -> str:  # fmt: skip
    """CSV text: a header row naming each column's rounding step (``length
    [0.01 mm]``, ``angle_deg [0.01 deg]``; text, and the columns ``as_given``,
    plain), then ``rows`` rounded so (lengths in ``units``: columns not
    ending in ``_deg``; ``inf`` written as ``inf``)."""

    def header(name: str, value: object) -> str:
        d = _decimals(name, units, as_given)
        if d is None or not isinstance(value, float):
            return name
        return f"{name} [{10.0**-d:.{d}f} {'deg' if name.endswith('_deg') else units}]"

    def cell(name: str, value: object) -> object:
        d = _decimals(name, units, as_given)
        if d is None or not isinstance(value, float) or math.isinf(value):
            return value
        return f"{round(value, d) + 0.0:.{d}f}"  # + 0.0: no '-0.00'

    sample = rows[0] if rows else (None,) * len(names)
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([header(n, v) for n, v in zip(names, sample, strict=True)])
    for row in rows:
        writer.writerow([cell(n, v) for n, v in zip(names, row, strict=True)])
    return out.getvalue()


def bend_csv(pattern: FlatPattern) -> str:
    """The bend sheet as CSV text: a header row naming each column's rounding
    step, then one row per crease half (and per ruling fold)."""
    rows = [astuple(row) for row in bend_rows(pattern)]
    names = [f.name for f in fields(BendRow)]
    return csv_rows(names, rows, pattern.units.value, _AS_GIVEN)


def write_bend_csv(
    source: FlatPattern | Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    compensation: Compensation = Compensation.SHARP,
) -> Path:
    """Write ``NAME-bends.csv`` (atomically: nothing is written if anything fails).

    Args:
        source: a flat pattern, or a design (its pattern is computed with
            ``compensation``; ``folded`` is ``fold_design(design)`` if given).
        path: the output file.
        folded: for a design: its fold, if already computed.
        compensation: for a design: 'sharp' or 'none'.

    Returns:
        The path written.
    """
    if isinstance(source, Design):
        folded = fold_design(source) if folded is None else folded
        source = flat_pattern_once(source, folded, compensation)
    text = bend_csv(source)
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
