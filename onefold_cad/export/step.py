"""STEP of the folded form: exact B-rep faces with build123d, one sewn shell, a solid.

The folded surface becomes build123d objects that you can place in your own
build123d model, show in a viewer, or export with build123d's other exporters
(glTF, STL, BREP); :func:`export_design_step` writes the STEP file.

* Exact model: one face per sheet edge per side, each a patch of the exact
  cone from the apex over the circular frame arc (a rational B-spline surface,
  degree 1 along the rulings), trimmed by the sheet's edge mapped onto the cone
  (interpolated on the surface to ``1e-7 * sheet.size`` or better). The face
  count does not depend on ``divisions``.
* Paper model: the paper's fan of planar triangles (``faces="fan"``).
* The faces are sewn into one shell: the two crease halves and the apex are
  shared by both sides. A relief hole of a given diameter may be cut about the
  apex (the default when the sheet has thickness).
* With thickness t > 0 (work in progress: OCC's offset of the creased shell
  fails or is inaccurate, so this raises ExportError today): a solid of the
  sheet, offset from the reference surface according to
  ``material.sheet_surface`` (INSIDE: the material lies
  below the top face; OUTSIDE: above it; MID: half each way).

Lengths are in the design's unit.

Example::

    import build123d as bd
    from onefold_cad import Design, FrameCurve, Sheet, build_design
    from onefold_cad.export.step import build_part, build_shell, export_design_step

    design = Design("demo", FrameCurve(50, 45), Sheet.quadrilateral(300, 300, 300, 300))
    part = build_part(design)                      # a build123d Shell (thickness 0)
    export_design_step(design, "demo.step")        # deterministic STEP, in mm
    shell = build_shell(build_design(design), relief_hole=10.0)
    placed = bd.Pos(0, 0, 50) * shell              # use it in your own model
    bd.export_stl(part, "demo.stl")                # or any build123d exporter
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import build123d as bd
from OCP.BRepGProp import BRepGProp
from OCP.BRepOffset import BRepOffset_MakeOffset, BRepOffset_Skin
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakeOffsetShape
from OCP.GeomAbs import GeomAbs_Intersection
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_SHELL
from OCP.TopoDS import TopoDS

from onefold_cad.design import Design, build_design
from onefold_cad.errors import ExportError, InvalidParameterError
from onefold_cad.export.brep import fan_faces, ruled_faces, sew
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, SheetSurface, Units

__all__ = [
    "measure",
    "build_shell",
    "build_solid",
    "build_part",
    "export_design_step",
    "STEP_TIMESTAMP",
]

#: The header timestamp of every STEP file written here (reproducible bytes).
STEP_TIMESTAMP = "2000-01-01T00:00:00"

_UNIT = {Units.MM: bd.Unit.MM, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}
#: Deviation allowed for the boundary curves on the cone, relative to sheet.size.
BOUNDARY_TOLERANCE = 1e-7


def _inradius(folded: FoldedSheet) -> float:
    v = folded.sheet.vertices
    import numpy as np

    w = np.roll(v, -1, axis=0)
    e = w - v
    t = np.clip(-(v * e).sum(axis=1) / (e * e).sum(axis=1), 0.0, 1.0)
    c = v + t[:, None] * e
    return float(np.min(np.hypot(c[:, 0], c[:, 1])))


def build_shell(
    folded: FoldedSheet, *, relief_hole: float = 0.0, faces: str | None = None
) -> bd.Shell:
    """The folded surface as one sewn build123d Shell (top side = face normals).

    Args:
        folded: the fold of a design (:func:`onefold_cad.build_design`).
        relief_hole: diameter of a hole about the apex, 0 <= d < twice the
            distance from H to the nearest sheet edge (length; 0 = none).
        faces: 'ruled' (exact cone patches, exact model only) or 'fan' (the
            paper model's planar triangles, paper model only); None picks the
            one that matches the model.

    Returns:
        A valid build123d Shell in the fold frame (apex above H).

    Raises:
        InvalidParameterError: bad ``relief_hole`` or ``faces``.
        ExportError: the CAD kernel could not build a valid shell.
    """
    exact = isinstance(folded.solution.surface, ExactCone)
    kind = faces if faces is not None else ("ruled" if exact else "fan")
    if kind not in ("ruled", "fan") or (kind == "ruled") != exact:
        raise InvalidParameterError(
            "faces",
            "must be 'ruled' for the exact model or 'fan' for the paper model "
            f"(this fold uses the {'exact' if exact else 'paper'} model), got {faces!r}",
        )
    limit = 2.0 * _inradius(folded)
    if not 0.0 <= relief_hole < limit:
        raise InvalidParameterError(
            "relief_hole", f"diameter must be in [0, {limit:.6g}) (length), got {relief_hole:g}"
        )
    size = folded.sheet.size
    if kind == "ruled":
        topo_faces, _ = ruled_faces(folded, 0.5 * relief_hole, BOUNDARY_TOLERANCE * size)
    else:
        topo_faces = fan_faces(folded, 0.5 * relief_hole)
    sewn = sew(topo_faces, 1e-6 * size)
    if sewn.ShapeType() != TopAbs_SHELL:
        raise ExportError(f"sewing gave a {sewn.ShapeType().name}, not one shell")
    shell = bd.Shell(TopoDS.Shell(sewn))
    if not shell.is_valid:
        raise ExportError("the sewn shell of the folded surface is not valid")
    return shell


def measure(shape: bd.Shape, what: str = "area") -> float:
    """Area (length^2) or volume (length^3) of ``shape`` by OCC's adaptive integration.

    build123d's ``area``/``volume`` use a fixed-order Gauss rule that is off by
    about 1e-4 (relative) on the rational cone patches; this one converges.
    """
    props = GProp_GProps()
    if what == "area":
        BRepGProp.SurfaceProperties_s(shape.wrapped, props, 1e-9)
    else:
        BRepGProp.VolumeProperties_s(shape.wrapped, props, 1e-9)
    return float(props.Mass())


def _offset_shell(shell: bd.Shell, distance: float) -> bd.Shell:
    mk = BRepOffsetAPI_MakeOffsetShape()
    mk.PerformBySimple(shell.wrapped, distance)
    if not mk.IsDone():
        raise ExportError("offsetting the reference surface failed")
    return bd.Shell(TopoDS.Shell(mk.Shape()))


def build_solid(folded: FoldedSheet, material: Material, *, faces: str | None = None) -> bd.Solid:
    """The sheet as a solid of thickness ``material.thickness`` (> 0).

    The reference surface is the folded surface; the material lies on the side
    that ``material.sheet_surface`` names. The relief hole is
    ``material.relief_hole_diameter``.

    Raises:
        InvalidParameterError: thickness 0, or too large for the geometry.
    """
    t = material.thickness
    if t <= 0.0:
        raise InvalidParameterError("thickness", f"must be > 0 for a solid, got {t:g}")
    shell = build_shell(folded, relief_hole=material.relief_hole_diameter, faces=faces)
    surface = material.sheet_surface
    start, depth = {
        SheetSurface.INSIDE: (0.0, -t),
        SheetSurface.OUTSIDE: (0.0, t),
        SheetSurface.MID: (-0.5 * t, t),
    }[surface]
    try:
        base = _offset_shell(shell, start) if start else shell
        mk = BRepOffset_MakeOffset()
        mk.Initialize(
            base.wrapped,
            depth,
            1e-6 * folded.sheet.size,
            BRepOffset_Skin,
            True,
            False,
            GeomAbs_Intersection,
            True,
            True,
        )
        mk.MakeOffsetShape()
        solid = bd.Solid(TopoDS.Solid(mk.Shape()))
    except Exception as err:  # OCC raises StdFail_NotDone and friends
        raise ExportError(
            f"the CAD kernel could not offset the folded surface by thickness {t:g} "
            f"({surface.value}; {err.__class__.__name__})"
        ) from None
    area = measure(shell, "area")
    volume = measure(solid, "volume")
    if not solid.is_valid or abs(volume - area * t) > 0.01 * area * t:
        raise ExportError(
            f"thickness {t:g} gave an invalid solid on this folded surface (volume "
            f"{volume:.6g} vs area x t = {area * t:.6g})"
        )
    return solid


def build_part(
    design: Design, folded: FoldedSheet | None = None, *, body: str = "shell"
) -> bd.Shape:
    """The design's part, labelled with its name.

    Args:
        design: the design; its material gives thickness, reference surface
            and the relief hole.
        folded: its fold, if already computed (else it is built here).
        body: 'shell' (default): the sewn reference surface, with the relief
            hole of ``material.relief_hole_diameter``; 'solid': the sheet of
            ``material.thickness`` (not available yet: the CAD kernel's offset
            of the creased shell is invalid or off in volume, and
            :func:`build_solid` refuses such a result with ExportError).
    """
    if body not in ("shell", "solid"):
        raise InvalidParameterError("body", f"must be 'shell' or 'solid', got {body!r}")
    folded = build_design(design) if folded is None else folded
    m = design.material
    if body == "solid":
        part: bd.Shape = build_solid(folded, m)
    else:
        part = build_shell(folded, relief_hole=m.relief_hole_diameter)
    part.label = design.name
    return part


def export_design_step(
    design: Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    body: str = "shell",
) -> Path:
    """Write the design's part (:func:`build_part`) as STEP, atomically.

    The file is in the design's unit (mm, inch or foot), the product is named
    after the design, and the header timestamp is :data:`STEP_TIMESTAMP`, so
    the same design gives the same bytes. Nothing is left at ``path`` (or
    beside it) when building or writing fails.

    Returns:
        The path written.
    """
    target = Path(path)
    part = build_part(design, folded, body=body)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    os.close(fd)
    try:
        try:
            ok = bd.export_step(part, tmp, unit=_UNIT[design.units], timestamp=STEP_TIMESTAMP)
        except RuntimeError as err:
            raise ExportError(f"writing STEP failed: {err}") from None
        if not ok:
            raise ExportError("writing STEP failed")
        os.replace(tmp, target)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return target
