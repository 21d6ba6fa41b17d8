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
* With thickness t > 0 (exact model): a solid of the sheet, offset from the
  reference surface according to ``material.sheet_surface`` (INSIDE: the
  material lies below the top face; OUTSIDE: above it; MID: half each way),
  built from ruled faces (:mod:`onefold_cad.export.solid`), with the relief
  hole through it and a mitre at the crease. It is the default part of a
  design with thickness; its volume is checked against the volume
  integrated from the geometry (0.1%).

Lengths are in the design's unit.

Example::

    import build123d as bd
    from onefold_cad import Design, FrameCurve, Material, Sheet, build_design
    from onefold_cad.export.step import build_part, build_shell, export_design_step

    design = Design("demo", FrameCurve(50, 45), Sheet.quadrilateral(300, 300, 300, 300))
    part = build_part(design)                      # a build123d Shell (thickness 0)
    thick = design.with_changes(material=Material(thickness=3.0))
    solid = build_part(thick)                      # a Solid, relief hole 3 x 3 = 9
    export_design_step(design, "demo.step")        # deterministic STEP, in mm
    shell = build_shell(build_design(design), relief_hole=10.0)
    placed = bd.Pos(0, 0, 50) * shell              # use it in your own model
    bd.export_stl(part, "demo.stl")                # or any build123d exporter
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import build123d as bd
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_Controller
from OCP.TopAbs import TopAbs_SHELL
from OCP.TopoDS import TopoDS

from onefold_cad.design import Design, build_design, relief_hole_diameter, sheet_inradius
from onefold_cad.errors import ExportError, InvalidParameterError, OneFoldError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.brep import fan_faces, ruled_faces, sew
from onefold_cad.export.measure import measure
from onefold_cad.export.solid import thick_solid
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, Units
from onefold_cad.geometry.thick_sheet import min_relief_hole, sheet_offsets, slab_volume

__all__ = [
    "measure",
    "build_shell",
    "build_solid",
    "build_part",
    "default_body",
    "min_relief_hole",
    "sheet_offsets",
    "export_design_step",
    "STEP_TIMESTAMP",
]

#: The header timestamp of every STEP file written here (reproducible bytes).
STEP_TIMESTAMP = "2000-01-01T00:00:00"

_UNIT = {Units.MM: bd.Unit.MM, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}
_STEP_UNIT_NAME = {Units.MM: "MM", Units.IN: "INCH", Units.FT: "FT"}
#: Deviation allowed for the boundary curves on the cone, relative to sheet.size.
BOUNDARY_TOLERANCE = 1e-7


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
    limit = 2.0 * sheet_inradius(folded.sheet)
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


#: Deviation allowed for the solid's edge curves, relative to sheet.size (the
#: rulings between them are exact).
SOLID_TOLERANCE = 1e-6
#: Relative difference allowed between the solid's volume (OCC) and the thick
#: sheet's volume integrated from the geometry (:func:`slab_volume`). They
#: agree to 3e-5 over 36 random designs (folds up to 170 deg); broken
#: booleans were off by 0.1% to 50%.
SOLID_VOLUME_TOLERANCE = 1e-3


def build_solid(folded: FoldedSheet, material: Material) -> bd.Solid:
    """The sheet as a solid of thickness ``material.thickness`` (> 0), exact model.

    The reference surface is the folded surface; the material lies on the side
    that ``material.sheet_surface`` names (:func:`sheet_offsets`). The relief
    hole, ``material.relief_hole_diameter``, is required: the cone's apex is
    singular and its offsets fold over near it (:func:`min_relief_hole`).
    Each side is bounded by ruled faces (see :mod:`onefold_cad.export.solid`),
    and the two sides meet in a mitre at the crease.

    Returns:
        One valid build123d Solid whose volume matches the thick sheet's volume
        integrated from the geometry (:func:`slab_volume`) within 0.1%. For
        MID that is area x t up to the mitre; INSIDE and OUTSIDE differ from
        area x t by about t / (2 x the cone's radius of curvature), e.g. 0.3%
        for Table 1's square at t = 3, more on tightly curved cones.

    Raises:
        InvalidParameterError: thickness 0, the paper model, or a relief hole
            too small for the thickness.
        ExportError: the CAD kernel could not build one valid solid of that
            volume (a larger relief hole usually helps; folds sharper than about
            150 deg sometimes fail).
    """
    t = material.thickness
    if t <= 0.0:
        raise InvalidParameterError("thickness", f"must be > 0 for a solid, got {t:g}")
    if not isinstance(folded.solution.surface, ExactCone):
        raise InvalidParameterError(
            "model", "must be 'exact' for a solid of the sheet's thickness, got 'paper'"
        )
    hole = material.relief_hole_diameter
    limit = 2.0 * sheet_inradius(folded.sheet)
    need = min_relief_hole(folded, material)
    if need >= limit:
        raise InvalidParameterError(
            "thickness",
            f"{t:g} is too thick for a solid on this sheet: its relief hole would need a "
            f"diameter > {need:.6g}, but the sheet allows < {limit:.6g} (length)",
        )
    if not need < hole < limit:
        raise InvalidParameterError(
            "relief_hole",
            f"diameter must be in ({need:.6g}, {limit:.6g}) (length) for a solid of thickness "
            f"{t:g} ({material.sheet_surface.value}), got {hole:g}",
        )
    size = folded.sheet.size
    expected = slab_volume(folded, material, hole)
    hint = f"a larger relief_hole than {hole:g} (up to {limit:.6g}) or a thinner sheet may help"
    try:
        solid = thick_solid(folded, hole, sheet_offsets(material), SOLID_TOLERANCE * size)
    except ExportError as err:
        raise ExportError(f"no solid of thickness {t:g}: {err}; {hint}") from None
    except Exception as err:  # OCC's StdFail_NotDone and friends
        raise ExportError(
            f"no solid of thickness {t:g}: the CAD kernel failed "
            f"({err.__class__.__name__}: {err}); {hint}"
        ) from None
    volume = measure(solid, "volume")
    if not solid.is_valid or abs(volume - expected) > SOLID_VOLUME_TOLERANCE * expected:
        raise ExportError(
            f"thickness {t:g} gave an invalid solid on this folded surface (valid "
            f"{solid.is_valid}, volume {volume:.6g} vs {expected:.6g} computed from the "
            f"geometry); {hint}"
        )
    return solid


def default_body(design: Design) -> str:
    """'solid' for an exact-model design with thickness and a relief hole (the
    default hole when thickness > 0), else 'shell' (the reference surface)."""
    m = design.material
    exact = design.model.value == "exact"
    return "solid" if exact and m.thickness > 0.0 and m.relief_hole_diameter > 0.0 else "shell"


def build_part(
    design: Design, folded: FoldedSheet | None = None, *, body: str | None = None
) -> bd.Shape:
    """The design's part, labelled with its name.

    Args:
        design: the design; its material gives thickness, reference surface
            and the relief hole.
        folded: its fold, if already computed (else it is built here).
        body: 'shell': the sewn reference surface, with the relief hole of
            ``material.relief_hole_diameter``; 'solid': the sheet of
            ``material.thickness`` (:func:`build_solid`); None (default):
            :func:`default_body`.
    """
    body = default_body(design) if body is None else body
    if body not in ("shell", "solid"):
        raise InvalidParameterError("body", f"must be 'shell' or 'solid', got {body!r}")
    folded = build_design(design) if folded is None else folded
    m = design.material
    m = m.with_changes(relief_hole=relief_hole_diameter(design, folded))
    try:
        if body == "solid":
            part: bd.Shape = build_solid(folded, m)
        else:
            part = build_shell(folded, relief_hole=m.relief_hole_diameter)
    except OneFoldError:
        raise
    except Exception as err:  # OCC's Standard_Failure family is not a RuntimeError
        raise ExportError(
            f"the CAD kernel failed building the {body} ({err.__class__.__name__}: {err})"
        ) from None
    part.label = design.name
    return part


def export_design_step(
    design: Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    body: str | None = None,
) -> Path:
    """Write the design's part (:func:`build_part`; ``body`` as there) as STEP,
    atomically.

    The file is in the design's unit (mm, inch or foot), the product is named
    after the design, and the header timestamp is :data:`STEP_TIMESTAMP`, so
    the same design gives the same bytes. Nothing is left at ``path`` (or
    beside it) when building or writing fails.

    Returns:
        The path written.
    """
    target = Path(path)
    part = build_part(design, folded, body=body)
    with atomic_output(target) as tmp, _step_unit(design.units):
        try:
            ok = bd.export_step(part, tmp, unit=_UNIT[design.units], timestamp=STEP_TIMESTAMP)
        except Exception as err:  # RuntimeError, or OCC's Standard_Failure family
            raise ExportError(f"writing STEP failed ({err.__class__.__name__}: {err})") from None
        if not ok:
            raise ExportError("writing STEP failed")
    return target


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
