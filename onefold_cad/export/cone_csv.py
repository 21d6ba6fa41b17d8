"""The cones' forming sheet as ``NAME-cones.csv``: the stations of
:func:`onefold_cad.mechanics.cone_forming.cone_stations`, a header row first,
rounded as the bend sheet is (lengths to 0.01 mm, 0.001 in or 0.0001 ft,
angles to 0.01 deg; a flat cone's radius is ``inf``)."""

from __future__ import annotations

import os
from dataclasses import astuple, fields
from pathlib import Path

from onefold_cad.design import Design, fold_design
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.bend_csv import csv_rows
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.mechanics.cone_forming import ConeStation, cone_stations

__all__ = ["cone_csv", "write_cone_csv"]


def cone_csv(design: Design, folded: FoldedSheet) -> str:
    """The forming sheet as CSV text: one row per station."""
    rows = [astuple(s) for s in cone_stations(design, folded)]
    names = [f.name for f in fields(ConeStation)]
    return csv_rows(names, rows, design.units.value)


def write_cone_csv(
    design: Design, path: str | os.PathLike[str], folded: FoldedSheet | None = None
) -> Path:
    """Write ``NAME-cones.csv`` (atomically: nothing is written if anything fails).

    Raises:
        InvalidParameterError: what :func:`cone_stations` refuses.
    """
    text = cone_csv(design, fold_design(design) if folded is None else folded)
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
