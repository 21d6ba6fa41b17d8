"""STEP files of the folded form: the design's part (:mod:`onefold_cad.export.part`)
written with build123d, deterministic bytes in the design's unit, read back
before it is moved into place.

Lengths are in the design's unit.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import build123d as bd
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_Controller

from onefold_cad.choices import Body, Compensation, Placement, Units
from onefold_cad.design import Design
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.part import KERNEL_BUDGET, build_part
from onefold_cad.export.step_checks import scale_hint
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.sheet import sheet_inradius

__all__ = ["STEP_TIMESTAMP", "export_design_step", "export_site_step", "read_step"]

#: The header timestamp of every STEP file written here (reproducible bytes).
STEP_TIMESTAMP = "2000-01-01T00:00:00"

_UNIT = {Units.MM: bd.Unit.MM, Units.M: bd.Unit.M, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}
_STEP_UNIT_NAME = {Units.MM: "MM", Units.M: "M", Units.IN: "INCH", Units.FT: "FT"}


def export_design_step(
    design: Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    body: Body | None = None,
    placement: Placement = Placement.REST,
    compensation: Compensation = Compensation.SHARP,
    part: bd.Shape | None = None,
    budget: float | None = KERNEL_BUDGET,
) -> Path:
    """Write the design's part (:func:`build_part`; ``body``, ``placement``,
    ``compensation`` and ``budget`` as there, or ``part`` if already built,
    written as given) as STEP, atomically.

    The file is in the design's unit (mm, inch or foot), the product is named
    after the design, and the header timestamp is :data:`STEP_TIMESTAMP`, so
    the same design gives the same bytes. It is read back before it is moved
    into place and refused (ExportError) unless it is one valid shape. Nothing
    is left at ``path`` (or beside it) when building or writing fails.

    Returns:
        The path written.
    """
    target = Path(path)
    if part is None:
        part = build_part(
            design,
            folded,
            body=body,
            placement=placement,
            compensation=compensation,
            budget=budget,
        )
    with atomic_output(target) as tmp, _step_unit(design.units):
        try:
            ok = bd.export_step(part, tmp, unit=_UNIT[design.units], timestamp=STEP_TIMESTAMP)
        except Exception as err:  # RuntimeError, or OCC's Standard_Failure family
            raise ExportError(f"writing STEP failed ({err.__class__.__name__}: {err})") from None
        if not ok:
            raise ExportError("writing STEP failed")
        _check_reads_back(tmp, part, design)
    return target


def _check_reads_back(path: Path, part: bd.Shape, design: Design) -> None:
    """Refuse a STEP file that does not read back as one valid shape with the
    part's faces (the file holds coordinates to a finite precision: a face
    far thinner than the sheet may not survive it)."""
    try:
        shape = bd.import_step(path)
        ok = shape.is_valid and len(shape.faces()) == len(part.faces())
    except Exception:  # OCC's Standard_Failure family
        ok = False
    if not ok:
        sheet = design.sheet
        gap = sheet_inradius(sheet)
        raise ExportError(
            "the written STEP file does not read back as a valid shape (a face thinner than "
            f"the file's precision: the sheet's edge nearest H passes {gap:.3g} from it, "
            f"{gap / sheet.size:.2g} x its size); a larger relief hole (parameter "
            "relief_hole), another thickness or an edge further from H may help"
            + scale_hint(sheet.size)
        )


def read_step(path: str | os.PathLike[str]) -> bd.Shape:
    """A STEP file read back with build123d (lengths in mm, whatever the
    file's unit): for checking what was written."""
    return bd.import_step(Path(path))


@contextmanager
def _step_unit(units: Units) -> Iterator[None]:
    """OCC's STEP writer writes in its ``write.step.unit`` setting (mm unless
    set; build123d's ``unit`` alone gives inch files but writes foot designs
    in mm): set it to the design's unit while writing, then restore it."""
    STEPControl_Controller.Init_s()
    before = Interface_Static.CVal_s("write.step.unit")
    Interface_Static.SetCVal_s("write.step.unit", _STEP_UNIT_NAME[units])
    try:
        yield
    finally:
        Interface_Static.SetCVal_s("write.step.unit", before)


def export_site_step(
    parts: list[bd.Shape], units: Units, path: str | os.PathLike[str], name: str
) -> Path:
    """Write a site's placed parts (each labelled with its sheet's name) as
    one STEP assembly named ``name``, atomically, in the site's unit, with
    :data:`STEP_TIMESTAMP`; read back before it is moved into place and
    refused (ExportError) unless it holds as many valid shapes as parts.

    Returns:
        The path written.
    """
    target = Path(path)
    assembly = bd.Compound(children=[_labelled_copy(p) for p in parts], label=name)
    with atomic_output(target) as tmp, _step_unit(units):
        try:
            ok = bd.export_step(assembly, tmp, unit=_UNIT[units], timestamp=STEP_TIMESTAMP)
        except Exception as err:  # RuntimeError, or OCC's Standard_Failure family
            raise ExportError(f"writing STEP failed ({err.__class__.__name__}: {err})") from None
        if not ok:
            raise ExportError("writing STEP failed")
        try:
            back = bd.import_step(tmp)
            ok = back.is_valid and len(back.solids() or back.shells()) >= len(parts)
        except Exception:  # OCC's Standard_Failure family
            ok = False
        if not ok:
            raise ExportError("the written site STEP file does not read back as valid shapes")
    return target


def _labelled_copy(part: bd.Shape) -> bd.Shape:
    """``part`` as a new shape object (so the assembly does not re-parent the
    caller's), with its label."""
    out = bd.Shape.cast(part.wrapped)
    out.label = part.label
    return out
