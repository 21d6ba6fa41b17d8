"""NAME.glb: the folded form as binary glTF 2.0, for web viewers.

The part is the design's STEP part (:func:`onefold_cad.export.part.build_part`:
the solid when the design has thickness, else the shell), in the STEP's
placement: by default standing on the ground as it rests
(:func:`onefold_cad.fabrication.rules.resting_placement`, applied by
:func:`onefold_cad.export.part.place`), or in the fold frame. ``build``
passes the part it wrote as STEP, so the two files hold the same part in the
same place. It is tessellated and written by build123d's ``export_gltf``
(OCCT's RWGltf_CafWriter), which turns OCCT's z-up into glTF's y-up (a -90 deg
turn about x in the root node) and the design's unit into metres, as glTF
requires. So in the file the ground is y = 0 and the form stands on it
(y >= 0).

Tessellation: :data:`LINEAR_DEFLECTION` of the sheet's size and
:data:`ANGULAR_DEFLECTION` radians (build123d hands the linear value to
OCCT's mesher as relative to each edge's size, so the angular one decides;
docs/formats.md states the known overlap on a solid's tapering faces). Every
mesh vertex lies on the part's surface; the triangles are chords of it, each
turning at most about the
angular deflection a from the surface, so the mesh's area is within about
``ANGULAR_DEFLECTION ** 2 / 2`` of the surface's (relative): a chord of
half-angle a is shorter than its arc by a^2 / 6, and a thin triangle tilted by
up to a against the surface under it is larger than that surface by up to
1 / cos(a) - 1, about a^2 / 2 (the solid's faces that taper to a point at
the crease get such triangles; a shell's mesh falls short). The one material is
double-sided, so a zero-thickness shell shows from both sides. The same part
gives the same bytes.
"""

from __future__ import annotations

import os
from pathlib import Path

import build123d as bd

from onefold_cad.choices import Compensation, Placement, Units
from onefold_cad.design import Design
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.colour_scale import STEEL_GREY
from onefold_cad.export.part import build_part
from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["ANGULAR_DEFLECTION", "LINEAR_DEFLECTION", "COLOUR", "write_glb", "write_site_glb"]

#: Largest distance between the mesh and the surface, relative to ``sheet.size``.
LINEAR_DEFLECTION = 1e-4
#: Largest turn of the surface across one triangle (radians).
ANGULAR_DEFLECTION = 0.05
#: The material's base colour (sRGB), a light steel grey.
COLOUR = STEEL_GREY

_UNIT = {Units.MM: bd.Unit.MM, Units.M: bd.Unit.M, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}


def write_glb(
    design: Design,
    folded: FoldedSheet,
    path: str | os.PathLike[str],
    part: bd.Shape | None = None,
    *,
    placement: Placement = Placement.REST,
    compensation: Compensation = Compensation.SHARP,
) -> Path:
    """Write the folded form, standing as it rests, as binary glTF (metres, y-up).

    Args:
        design: the design (its unit and material).
        folded: its fold.
        path: the ``.glb`` file to write (atomically).
        part: the design's part as the STEP holds it (:func:`build_part`,
            already placed), written as given; None: built here with
            ``placement`` and ``compensation`` (as :func:`build_part`).
        placement: 'rest' (default, standing on the ground y = 0) or
            'frame' (the fold frame), when the part is built here.
        compensation: as :func:`build_part` ('none' builds a solid past the
            bend model's limits), when the part is built here.

    Returns:
        The path written.

    Raises:
        FabricationError: a solid past the bend model's limits.
        ExportError: the part could not be built or the file not written.
    """
    out = Path(path)
    if part is None:
        part = build_part(design, folded, placement=placement, compensation=compensation)
    # a copy, so that the caller's part keeps its colour; the placement is in
    # its geometry (export_gltf composes its own z-up to y-up turn on the
    # wrong side of a shape's location)
    placed = bd.Shape.cast(part.wrapped)
    placed.label = part.label
    placed.color = bd.Color(*COLOUR)
    size = design.sheet.size
    return _export(placed, design.units, size, out)


def _export(shape: bd.Shape, units: Units, size: float, out: Path) -> Path:
    """Tessellate ``shape`` (deflections relative to ``size``) into the binary
    glTF ``out``, atomically."""
    with atomic_output(out) as tmp:
        try:
            ok = bd.export_gltf(
                shape,
                tmp,
                unit=_UNIT[units],
                binary=True,
                linear_deflection=LINEAR_DEFLECTION * size,
                angular_deflection=ANGULAR_DEFLECTION,
            )
        except Exception as err:  # RuntimeError, or OCC's Standard_Failure family
            raise ExportError(f"writing glTF failed ({err.__class__.__name__}: {err})") from None
        if not ok:
            raise ExportError("writing glTF failed")
    return out


def write_site_glb(
    parts: list[bd.Shape], units: Units, path: str | os.PathLike[str], size: float, name: str
) -> Path:
    """Write a site's placed parts as one binary glTF scene (metres, y-up),
    one node per part named with its label, tessellated as :func:`write_glb`
    does with ``size`` the largest sheet's size (site unit).

    Returns:
        The path written.
    """
    out = Path(path)
    children = []
    for part in parts:
        placed = bd.Shape.cast(part.wrapped)
        placed.label = part.label
        placed.color = bd.Color(*COLOUR)
        children.append(placed)
    scene = bd.Compound(children=children, label=name)
    return _export(scene, units, size, out)
