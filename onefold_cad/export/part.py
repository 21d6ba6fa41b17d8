"""The folded form as a build123d part: exact B-rep faces, one shell, a solid.

The folded surface becomes build123d objects that you can place in your own
build123d model, show in a viewer, or export with build123d's other exporters
(glTF, STL, BREP); :func:`onefold_cad.export.step.export_design_step` writes
the STEP file, :mod:`onefold_cad.export.step_checks` refuses what the CAD
kernel cannot build before it is called.

* Exact model: one face per sheet edge per side, each a patch of the exact
  cone from the apex over the circular frame arc (a rational B-spline surface,
  degree 1 along the rulings), trimmed by the sheet's edge mapped onto the cone
  (interpolated on the surface to :data:`BOUNDARY_TOLERANCE` x sheet.size;
  a fit that cannot reach it is an ExportError). The face count does not
  depend on ``divisions``.
* Paper model: the paper's fan of planar triangles (``faces="fan"``).
* Either way the faces form one shell built with shared topology (the two
  crease rulings and the apex are shared by both sides, each ruling by its
  two faces): no sewing, so a fan of 3000 divisions takes a second or two.
  A relief hole of a given diameter may be cut about the apex (the default
  when the sheet has thickness).
* With thickness t > 0 (exact model): a solid of the sheet, offset from the
  reference surface according to ``material.sheet_surface`` (INSIDE: the
  material lies below the top face; OUTSIDE: above it; MID: half each way),
  built face by face (:mod:`onefold_cad.export.solid`, no boolean
  operation), with the relief hole through it and a mitre at the crease. It
  is the default part of a design with thickness; its volume is checked
  against the volume integrated from the geometry.
* The part is written as it stands (``placement="rest"``, the default):
  moved by the design's resting placement
  (:func:`onefold_cad.fabrication.rules.resting_placement`, the one the report, the GLB
  and the previews use) so that its lowest point lies on the ground z = 0;
  ``placement="frame"`` keeps the fold frame (apex above H).
* A solid past the bend model's limits is refused (FabricationError,
  :func:`onefold_cad.fabrication.rules.solid_bend_problem`) unless the compensation is
  'none'; the shell, the designed surface, is always built.

Every part carries ``fit_deviation`` (the largest deviation its fitted
curves reached, length; 0 for the paper fan, which is exact) and
``fit_tolerance`` (the deviation allowed) for the report.

Lengths are in the design's unit.

Example::

    import build123d as bd
    from onefold_cad import Design, FrameCurve, Material, Sheet, fold_design
    from onefold_cad.export.part import build_part, build_shell
    from onefold_cad.export.step import export_design_step

    design = Design("demo", FrameCurve(50, 45), Sheet.quadrilateral(300, 300, 300, 300))
    part = build_part(design)                      # a build123d Shell, resting on z = 0
    thick = design.with_changes(material=Material(thickness=3.0))
    solid = build_part(thick)                      # a Solid, relief hole 3 x 3 = 9
    export_design_step(design, "demo.step")        # deterministic STEP, in mm
    shell = build_shell(fold_design(design), relief_hole=10.0)   # fold frame
    placed = bd.Pos(0, 0, 50) * shell              # use it in your own model
    bd.export_stl(part, "demo.stl")                # or any build123d exporter
"""

from __future__ import annotations

import build123d as bd
import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
from OCP.gp import gp_Trsf, gp_Vec

from onefold_cad.choices import Body, Compensation, Placement
from onefold_cad.design import Design, fold_design
from onefold_cad.errors import ExportError, InvalidParameterError, OneFoldError
from onefold_cad.export.bspline_fit import MAX_NODES
from onefold_cad.export.cone_faces import FoldedBackError, ruled_shell
from onefold_cad.export.fan_faces import fan_shell
from onefold_cad.export.kernel_budget import KernelBudget
from onefold_cad.export.measure import measure
from onefold_cad.export.solid import thick_solid
from onefold_cad.export.step_checks import (
    BOUNDARY_TOLERANCE,
    check_mitre,
    near_symmetric_hint,
    scale_hint,
    shell_problem,
)
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, solid_min_relief_hole
from onefold_cad.fabrication.rules import default_body, resting_placement, solid_bend_problem
from onefold_cad.geometry.checks import shown
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.placement import RestingPlacement
from onefold_cad.geometry.sheet import sheet_inradius
from onefold_cad.geometry.slab import Slab
from onefold_cad.geometry.slab_volume import integrated_volume

__all__ = [
    "KERNEL_BUDGET",
    "PLACEMENTS",
    "SOLID_TOLERANCE",
    "build_part",
    "build_shell",
    "build_solid",
    "place",
]

#: Deviation allowed for the solid's edge curves, relative to sheet.size (the
#: rulings between them are exact) ...
SOLID_TOLERANCE = 1e-6
#: ... and relative to the thickness (a thin sheet on a big one).
SOLID_THICKNESS_TOLERANCE = 1e-3
#: Relative difference allowed between the solid's volume (OCC's
#: Gauss-Kronrod rule to 1e-8) and the thick sheet's volume integrated from
#: the geometry (:func:`~onefold_cad.geometry.slab_volume.slab_volume`,
#: about 1e-12). The edge curves' deviation (SOLID_TOLERANCE) moves the
#: volume by a few 1e-6; a face missing or doubled by a wrong construction
#: moves it by far more.
SOLID_VOLUME_TOLERANCE = 1e-4
#: Seconds the CAD kernel may spend on one part before the build gives up
#: with a clear error (the solid takes well under 1 s, a shell of 3000
#: divisions about 2 s).
KERNEL_BUDGET = 60.0
#: Where a part is written: as it stands on the ground, or in the fold frame.
PLACEMENTS = tuple(p.value for p in Placement)


def build_shell(
    folded: FoldedSheet,
    *,
    relief_hole: float = 0.0,
    faces: str | None = None,
    budget: float | None = KERNEL_BUDGET,
) -> bd.Shell:
    """The folded surface as one build123d Shell (top side = face normals).

    Args:
        folded: the fold of a design (:func:`onefold_cad.fold_design`).
        relief_hole: diameter of a hole about the apex, 0 <= d < twice the
            distance from H to the nearest sheet edge (length; 0 = none).
        faces: 'ruled' (exact cone patches, exact model only) or 'fan' (the
            paper model's planar triangles, paper model only); None picks the
            one that matches the model.
        budget: seconds the CAD kernel may take (None: no limit).

    Returns:
        A valid build123d Shell in the fold frame (apex above H), with
        ``fit_deviation`` (the largest deviation of its boundary curves from
        the sheet's edges mapped onto the cone, length; 0 for the fan) and
        ``fit_tolerance`` (``BOUNDARY_TOLERANCE * sheet.size``).

    Raises:
        InvalidParameterError: bad ``relief_hole`` or ``faces``.
        ExportError: a boundary curve cannot reach the tolerance, the CAD
            kernel could not build a valid shell, or it ran out of time (the
            message says what to reduce); exact model: H too close to the
            sheet's boundary for the kernel (:func:`near_edge_problem`, before
            any kernel call), or the cone folded back onto itself so that a
            face's edge would be no longer than the kernel's precision (alpha
            and beta both near 90 with a relief hole).
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
            "relief_hole",
            f"diameter must be in [0, {limit:.6g}) (length), got {shown(relief_hole)}",
        )
    problem = shell_problem(folded, relief_hole)
    if problem is not None:
        raise problem
    tol = BOUNDARY_TOLERANCE * folded.sheet.size
    if kind == "ruled":
        clock = KernelBudget(budget, "a sheet with fewer vertices may help")
        try:
            topo, deviation = ruled_shell(folded, 0.5 * relief_hole, tol)
        except FoldedBackError as err:
            fr = folded.solution.frame
            raise ExportError(
                f"no STEP of the exact model: {err} (alpha {fr.alpha!r}, beta {fr.beta!r} deg: "
                "both near 90 put the apex in the frame's plane); a smaller alpha or beta, "
                "or no relief hole (relief_hole 0)"
            ) from None
        if deviation > tol:
            raise ExportError(
                f"the sheet's edges mapped onto the cone need more than {MAX_NODES} points "
                f"to stay within {tol:.3g} (BOUNDARY_TOLERANCE x sheet size) of the exact "
                f"curve; the closest fit is {deviation:.3g} off. Splitting the sheet's long "
                "edges (more polygon vertices) or the paper model (--model paper) may help"
            )
        clock.check()
    else:
        triangles = sum(len(a) - 1 for a in folded.ruling_angles)
        clock = KernelBudget(
            budget, f"fewer divisions may help (this fan has {triangles} triangles)"
        )
        topo = fan_shell(folded, 0.5 * relief_hole, clock.check)
        deviation = 0.0
    shell = bd.Shell(topo)
    if not shell.is_valid:
        raise ExportError(
            "the shell of the folded surface is not valid"
            + _invalid_faces(shell, folded)
            + scale_hint(folded.sheet.size)
        )
    clock.check()
    shell.fit_deviation = deviation
    shell.fit_tolerance = tol if kind == "ruled" else 0.0
    return shell


def _invalid_faces(shell: bd.Shell, folded: FoldedSheet) -> str:
    """What the CAD kernel refused, as the design's property: how many of the
    shell's faces, the narrowest angle of theirs at the apex, and the frame
    angles that shape them ('' when no single face is invalid)."""
    faces = shell.faces()
    bad = [f for f in faces if not f.is_valid]
    if not bad:
        return ""
    apex = np.asarray(folded.apex, dtype=float)
    narrowest = np.inf
    for f in bad:
        rays = np.array([tuple(v) for v in f.vertices()], dtype=float) - apex
        lengths = np.linalg.norm(rays, axis=1)
        rays = rays[lengths > 0] / lengths[lengths > 0, None]
        for i in range(len(rays)):
            cos = np.clip(rays[i + 1 :] @ rays[i], -1.0, 1.0)
            if cos.size:
                narrowest = min(narrowest, float(np.degrees(np.arccos(cos)).min()))
    fr = folded.solution.frame
    return (
        f": the CAD kernel refuses {len(bad)} of its {len(faces)} faces, the narrowest "
        f"{narrowest:.3g} deg wide at the apex, of the fan of alpha {fr.alpha:g}, beta "
        f"{fr.beta:g} deg; fewer divisions may help, and --formats without step writes the rest"
    )


def build_solid(
    folded: FoldedSheet, material: Material, *, budget: float | None = KERNEL_BUDGET
) -> bd.Solid:
    """The sheet as a solid of thickness ``material.thickness`` (> 0), exact model.

    The reference surface is the folded surface; the material lies on the side
    that ``material.sheet_surface`` names (:func:`sheet_offsets`). The relief
    hole, ``material.relief_hole_diameter``, is required: the cone's apex is
    singular and its offsets fold over near it
    (:func:`onefold_cad.fabrication.relief_hole.solid_min_relief_hole`).
    The two sides meet in a mitre on the fold's plane of symmetry; its
    faces, the sheet's two faces and the walls along the outline and the hole
    are built directly and sewn once (:mod:`onefold_cad.export.solid`, no
    boolean operation).

    Args:
        folded: an exact-model fold.
        material: thickness, reference surface and relief hole.
        budget: seconds the CAD kernel may take (None: no limit).

    Returns:
        One valid build123d Solid whose volume matches the thick sheet's volume
        integrated from the geometry (:func:`slab_volume`) within 1e-4; its
        edge curves lie within min(1e-6 x sheet size, 1e-3 x t) of the exact
        ones (``fit_tolerance``; ``fit_deviation`` the largest reached). For
        MID that is area x t up to the mitre; INSIDE and OUTSIDE differ from
        area x t by about t / (2 x the cone's radius of curvature), e.g. 0.3%
        for Table 1's square at t = 3, more on tightly curved cones.

    Raises:
        InvalidParameterError: thickness 0, the paper model, or a relief hole
            too small for the thickness.
        ExportError: the CAD kernel could not build one valid solid of that
            volume, or ran out of its time budget; the message says what to
            change.
    """
    t = material.thickness
    if t <= 0.0:
        raise InvalidParameterError("thickness", f"must be > 0 for a solid, got {shown(t)}")
    if not isinstance(folded.solution.surface, ExactCone):
        raise InvalidParameterError(
            "model", "must be 'exact' for a solid of the sheet's thickness, got 'paper'"
        )
    hole = material.relief_hole_diameter
    limit = 2.0 * sheet_inradius(folded.sheet)
    need = solid_min_relief_hole(folded, material)
    if need >= limit:
        raise InvalidParameterError(
            "thickness",
            f"{t:g} is too thick for a solid on this sheet: its relief hole would need a "
            f"diameter > {need:.6g}, but the sheet allows < {limit:.6g} (length); a thickness "
            f"below about {t * limit / need:.3g}, or the shell (--body shell), would do",
        )
    if not need < hole < limit:
        raise InvalidParameterError(
            "relief_hole",
            f"diameter must be in ({need:.6g}, {limit:.6g}) (length) for a solid of thickness "
            f"{t:g} ({material.sheet_surface.value}), got {shown(hole)}",
        )
    check_mitre(folded, material)
    size = folded.sheet.size
    tol = min(SOLID_TOLERANCE * size, SOLID_THICKNESS_TOLERANCE * t)
    slab = Slab(folded, material, hole)
    hint = near_symmetric_hint(slab) or (
        f"a larger relief_hole than {hole:g} (up to {limit:.6g}) or a thinner sheet may help"
    )
    clock = KernelBudget(budget, f"a thinner sheet or a larger relief hole may help ({hint})")
    try:
        solid, deviation = thick_solid(slab, tol, clock)
    except ExportError as err:
        raise ExportError(f"no solid of thickness {t:g}: {err}; {hint}") from None
    except Exception as err:  # OCC's StdFail_NotDone and friends
        raise ExportError(
            f"no solid of thickness {t:g}: the CAD kernel failed "
            f"({err.__class__.__name__}: {err}); {hint}"
        ) from None
    valid = solid.is_valid
    volume = measure(solid, "volume", tol=1e-8) if valid else float("nan")
    expected = integrated_volume(slab)
    if not (valid and abs(volume - expected) <= SOLID_VOLUME_TOLERANCE * expected):
        raise ExportError(
            f"thickness {t:g} gave an invalid solid on this folded surface (valid "
            f"{valid}, volume {volume:.9g} vs {expected:.9g} integrated from the "
            f"geometry); {hint}"
        )
    clock.check()
    solid.fit_deviation = deviation
    solid.fit_tolerance = tol
    solid.solid_volume = volume
    return solid


def _fabrication_limits(design: Design, folded: FoldedSheet, compensation: Compensation) -> None:
    """Refuse a solid past the bend model's limits (FabricationError: a bend
    zone reaching a sheet corner, a large set-back beside the flanges, a fold
    near 180 deg) unless ``compensation`` is 'none':
    :func:`onefold_cad.fabrication.rules.solid_bend_problem`, the check ``build`` also
    makes before it writes anything."""
    problem = solid_bend_problem(design, folded, compensation)
    if problem is not None:
        raise problem


def place(part: bd.Shape, placement: RestingPlacement) -> bd.Shape:
    """``part`` moved by the rigid motion of ``placement`` (rotation, then
    translation; :func:`onefold_cad.fabrication.rules.resting_placement`), then lifted or
    lowered so that the B-rep's own lowest point lies on the ground z = 0
    exactly: the placement stands the exact body there, and the B-rep's
    curves lie within its ``fit_tolerance`` of it. The one place where a part
    is stood up.

    Returns:
        A new shape (the geometry transformed), with the part's label and
        attributes.
    """
    r, t = np.asarray(placement.rotation, dtype=float), np.asarray(placement.translation)
    trsf = gp_Trsf()
    trsf.SetValues(*r[0], t[0], *r[1], t[1], *r[2], t[2])
    moved = BRepBuilderAPI_Transform(part.wrapped, trsf, True).Shape()
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(moved, box, False, False)
    lift = gp_Trsf()
    lift.SetTranslation(gp_Vec(0.0, 0.0, -box.CornerMin().Z()))
    out = bd.Shape.cast(BRepBuilderAPI_Transform(moved, lift, True).Shape())
    out.label = part.label
    for name in ("fit_deviation", "fit_tolerance", "solid_volume"):
        if hasattr(part, name):
            setattr(out, name, getattr(part, name))
    return out


def build_part(
    design: Design,
    folded: FoldedSheet | None = None,
    *,
    body: Body | None = None,
    placement: Placement = Placement.REST,
    compensation: Compensation = Compensation.SHARP,
    budget: float | None = KERNEL_BUDGET,
) -> bd.Shape:
    """The design's part, labelled with its name.

    Args:
        design: the design; its material gives thickness, reference surface
            and the relief hole.
        folded: its fold, if already computed (else it is built here).
        body: 'shell': the reference surface, with the relief hole of
            ``material.relief_hole_diameter``; 'solid': the sheet of
            ``material.thickness`` (:func:`build_solid`); None (default):
            :func:`onefold_cad.fabrication.rules.default_body`.
        placement: 'rest' (default): standing on the ground, lowest point on
            z = 0 (:func:`place` with
            :func:`onefold_cad.fabrication.rules.resting_placement` of this body);
            'frame': the fold frame (apex above H).
        compensation: 'sharp' (default): a solid past the bend model's
            limits is refused; 'none': built as designed (as ``build
            --compensation``).
        budget: seconds the CAD kernel may take (None: no limit).

    Returns:
        The part, with ``fit_deviation`` and ``fit_tolerance`` (length; see
        :func:`build_shell`).

    Raises:
        InvalidParameterError: a bad ``body``, ``placement`` or
            ``compensation``, or a solid the design cannot have.
        FabricationError: a solid past the bend model's limits.
        ExportError: the CAD kernel could not build the part.
    """
    body = default_body(design) if body is None else body
    if body not in tuple(b.value for b in Body):
        raise InvalidParameterError("body", f"must be 'shell' or 'solid', got {body!r}")
    if placement not in PLACEMENTS:
        raise InvalidParameterError("placement", f"must be 'rest' or 'frame', got {placement!r}")
    folded = fold_design(design) if folded is None else folded
    m = design.material
    m = m.with_changes(relief_hole=relief_hole_diameter(design, folded))
    if body == "solid":
        _fabrication_limits(design, folded, compensation)
    else:
        Compensation.parse(compensation)  # a bad value is an error whatever the body
    try:
        if body == "solid":
            part: bd.Shape = build_solid(folded, m, budget=budget)
        else:
            part = build_shell(folded, relief_hole=m.relief_hole_diameter, budget=budget)
        part.label = design.name
        if placement == "rest":
            part = place(part, resting_placement(design, folded, body))
    except OneFoldError:
        raise
    except Exception as err:  # OCC's Standard_Failure family is not a RuntimeError
        raise ExportError(
            f"the CAD kernel failed building the {body} ({err.__class__.__name__}: {err})"
        ) from None
    return part
