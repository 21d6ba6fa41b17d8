"""The bend sheet as ``NAME-bends.csv``: the rows of the bend table
(:func:`onefold_cad.fabrication.bend_table.bend_rows`), a header row first.
"""

from __future__ import annotations

import csv
import io
import os
from dataclasses import astuple, fields
from pathlib import Path

from onefold_cad.choices import Compensation
from onefold_cad.design import Design, fold_design
from onefold_cad.export.atomic import atomic_output
from onefold_cad.fabrication.bend_table import BendRow, bend_rows
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern_once
from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["bend_csv", "write_bend_csv"]


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
