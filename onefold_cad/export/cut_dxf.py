"""The cut-only DXF: the blank for the laser alone (an ezdxf adapter).

One layer, ``CUT``: the blank's outline as one closed LWPOLYLINE (POLYLINE in
R12) and the relief hole as a CIRCLE, both offset by kerf/2 when a kerf is
given (outline outwards, hole inwards). No text, no bend lines, no splines,
nothing twice; ``$INSUNITS`` (not in R12) and ``$MEASUREMENT`` follow the
design's unit. The geometry is the annotated DXF's ``CUT`` layer, from
:func:`onefold_cad.fabrication.flat_pattern.flat_pattern`; the file is
deterministic like the annotated one.
"""

from __future__ import annotations

import os
from pathlib import Path

from ezdxf.document import Drawing

from onefold_cad.choices import Compensation
from onefold_cad.design import Design, fold_design
from onefold_cad.errors import ExportError
from onefold_cad.export.dxf import design_seed, new_document, set_units, write_dxf_atomic
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern
from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["CUT_LAYER", "draw_cut", "export_design_cut_dxf"]

CUT_LAYER = "CUT"


def draw_cut(pattern: FlatPattern, *, dxfversion: str = "R2000") -> Drawing:
    """A new document holding only the cutting paths of ``pattern`` (audited)."""
    doc = new_document(dxfversion, setup=False)
    set_units(doc, pattern.units)
    doc.layers.add(CUT_LAYER, color=7)
    msp = doc.modelspace()
    outline = [tuple(p) for p in pattern.cut_outline.tolist()]
    attribs = {"layer": CUT_LAYER}
    if doc.dxfversion > "AC1009":
        msp.add_lwpolyline(outline, format="xy", close=True, dxfattribs=attribs)
    else:
        msp.add_polyline2d(outline, close=True, dxfattribs=attribs)
    if pattern.cut_hole_diameter > 0.0:
        msp.add_circle(tuple(pattern.apex.tolist()), pattern.cut_hole_diameter / 2.0, attribs)
    auditor = doc.audit()
    if auditor.has_errors:
        raise ExportError(f"the cut DXF failed its audit: {auditor.errors}")
    return doc


def export_design_cut_dxf(
    design: Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    dxfversion: str = "R2000",
    compensation: Compensation | str = Compensation.SHARP,
) -> Path:
    """Write ``NAME-cut.dxf``, the blank for the laser alone (atomically).

    Args:
        design: the design.
        path: the output file; nothing is written if anything fails.
        folded: ``fold_design(design)`` if already computed.
        dxfversion: 'R2000' (default), 'R12' or a later version.
        compensation: 'sharp' (default) or 'none' (see
            :func:`~onefold_cad.fabrication.flat_pattern.flat_pattern`).

    Raises:
        FabricationError: the sharp-crease compensation's limits are passed.
    """
    folded = fold_design(design) if folded is None else folded
    doc = draw_cut(flat_pattern(design, folded, compensation), dxfversion=dxfversion)
    return write_dxf_atomic(doc, path, seed=design_seed(design, compensation, "cut"))
