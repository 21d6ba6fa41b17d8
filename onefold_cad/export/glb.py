"""NAME.glb: the folded form as binary glTF 2.0, for web viewers.

The part is the design's STEP part (:func:`onefold_cad.export.step.build_part`:
the solid when the design has thickness, else the sewn shell), stood on the
ground as it rests (:attr:`FoldedSheet.resting`), tessellated and written by
build123d's ``export_gltf`` (OCCT's RWGltf_CafWriter), which turns OCCT's
z-up into glTF's y-up (a -90 deg turn about x in the root node) and the
design's unit into metres, as glTF requires. So in the file the ground is
y = 0 and the form stands on it (y >= 0).

Tessellation: :data:`LINEAR_DEFLECTION` of the sheet's size and
:data:`ANGULAR_DEFLECTION` radians. Every mesh vertex lies on the part's
surface; the triangles are chords of it, each turning at most about the
angular deflection from the surface, so the mesh's area falls short of the
surface's by at most about ``ANGULAR_DEFLECTION ** 2 / 6`` (relative; a chord
of half-angle a is shorter than its arc by a^2 / 6). The one material is
double-sided, so a zero-thickness shell shows from both sides. The same part
gives the same bytes.
"""

from __future__ import annotations

import os
from pathlib import Path

import build123d as bd
from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
from OCP.gp import gp_Trsf

from onefold_cad.design import Design
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.step import build_part
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Units

__all__ = ["ANGULAR_DEFLECTION", "LINEAR_DEFLECTION", "COLOUR", "stand_part", "write_glb"]

#: Largest distance between the mesh and the surface, relative to ``sheet.size``.
LINEAR_DEFLECTION = 1e-4
#: Largest turn of the surface across one triangle (radians).
ANGULAR_DEFLECTION = 0.05
#: The material's base colour (sRGB), a light steel grey.
COLOUR = (0.72, 0.74, 0.78)

_UNIT = {Units.MM: bd.Unit.MM, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}


def stand_part(part: bd.Shape, folded: FoldedSheet) -> bd.Shape:
    """A copy of ``part`` (fold frame) moved by ``folded.resting``: standing on
    z = 0. The motion is baked into the geometry (not left as a location),
    because ``export_gltf`` composes its own z-up to y-up turn on the wrong
    side of a shape's location."""
    rest = folded.resting
    trsf = gp_Trsf()
    r, t = rest.rotation, rest.translation
    trsf.SetValues(*r[0], t[0], *r[1], t[1], *r[2], t[2])
    moved = bd.Shape.cast(BRepBuilderAPI_Transform(part.wrapped, trsf, True).Shape())
    moved.label = part.label
    return moved


def write_glb(
    design: Design,
    folded: FoldedSheet,
    path: str | os.PathLike[str],
    part: bd.Shape | None = None,
) -> Path:
    """Write the folded form, standing as it rests, as binary glTF (metres, y-up).

    Args:
        design: the design (its unit and material).
        folded: its fold.
        path: the ``.glb`` file to write (atomically).
        part: the design's part in the fold frame if already built (e.g. for
            the STEP), else :func:`build_part` builds it.

    Returns:
        The path written.

    Raises:
        ExportError: the part could not be built or the file not written.
    """
    out = Path(path)
    part = build_part(design, folded) if part is None else part
    placed = stand_part(part, folded)
    placed.color = bd.Color(*COLOUR)
    size = design.sheet.size
    with atomic_output(out) as tmp:
        try:
            ok = bd.export_gltf(
                placed,
                tmp,
                unit=_UNIT[design.units],
                binary=True,
                linear_deflection=LINEAR_DEFLECTION * size,
                angular_deflection=ANGULAR_DEFLECTION,
            )
        except Exception as err:  # RuntimeError, or OCC's Standard_Failure family
            raise ExportError(f"writing glTF failed ({err.__class__.__name__}: {err})") from None
        if not ok:
            raise ExportError("writing glTF failed")
    return out
