"""STEP of the folded form: exact B-rep faces with build123d, one shell, a solid.

The folded surface becomes build123d objects that you can place in your own
build123d model, show in a viewer, or export with build123d's other exporters
(glTF, STL, BREP); :func:`export_design_step` writes the STEP file.

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
  (:func:`onefold_cad.design.resting_placement`, the one the report, the GLB
  and the previews use) so that its lowest point lies on the ground z = 0;
  ``placement="frame"`` keeps the fold frame (apex above H).
* A solid past the bend model's limits is refused (FabricationError,
  :func:`onefold_cad.design.solid_bend_problem`) unless the compensation is
  'none'; the shell, the designed surface, is always built.

Every part carries ``fit_deviation`` (the largest deviation its fitted
curves reached, length; 0 for the paper fan, which is exact) and
``fit_tolerance`` (the deviation allowed) for the report.

Lengths are in the design's unit.

Example::

    import build123d as bd
    from onefold_cad import Design, FrameCurve, Material, Sheet, build_design
    from onefold_cad.export.step import build_part, build_shell, export_design_step

    design = Design("demo", FrameCurve(50, 45), Sheet.quadrilateral(300, 300, 300, 300))
    part = build_part(design)                      # a build123d Shell, resting on z = 0
    thick = design.with_changes(material=Material(thickness=3.0))
    solid = build_part(thick)                      # a Solid, relief hole 3 x 3 = 9
    export_design_step(design, "demo.step")        # deterministic STEP, in mm
    shell = build_shell(build_design(design), relief_hole=10.0)   # fold frame
    placed = bd.Pos(0, 0, 50) * shell              # use it in your own model
    bd.export_stl(part, "demo.stl")                # or any build123d exporter
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import build123d as bd
import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
from OCP.gp import gp_Trsf, gp_Vec
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_Controller

from onefold_cad.design import (
    Design,
    build_design,
    default_body,
    relief_hole_diameter,
    resting_placement,
    sheet_inradius,
    solid_bend_problem,
    solid_min_relief_hole,
)
from onefold_cad.errors import ExportError, InvalidParameterError, OneFoldError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.brep import MAX_NODES, FoldedBackError, fan_shell, ruled_shell
from onefold_cad.export.measure import measure
from onefold_cad.export.solid import KernelBudget, thick_solid
from onefold_cad.geometry.bend import Compensation
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, Units
from onefold_cad.geometry.placement import RestingPlacement
from onefold_cad.geometry.sheet import Sheet
from onefold_cad.geometry.thick_sheet import SideMap, Slab, mitre_reach, sheet_offsets

__all__ = [
    "measure",
    "build_shell",
    "build_solid",
    "build_part",
    "place",
    "sheet_offsets",
    "export_design_step",
    "read_step",
    "STEP_TIMESTAMP",
    "BOUNDARY_TOLERANCE",
    "SOLID_TOLERANCE",
    "KERNEL_BUDGET",
    "PLACEMENTS",
]

#: The header timestamp of every STEP file written here (reproducible bytes).
STEP_TIMESTAMP = "2000-01-01T00:00:00"

_UNIT = {Units.MM: bd.Unit.MM, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}
_STEP_UNIT_NAME = {Units.MM: "MM", Units.IN: "INCH", Units.FT: "FT"}
#: Deviation allowed for the boundary curves on the cone, relative to sheet.size.
BOUNDARY_TOLERANCE = 1e-7
#: Deviation allowed for the solid's edge curves, relative to sheet.size (the
#: rulings between them are exact) ...
SOLID_TOLERANCE = 1e-6
#: ... and relative to the thickness (a thin sheet on a big one).
SOLID_THICKNESS_TOLERANCE = 1e-3
#: Relative difference allowed between the solid's volume (OCC's
#: Gauss-Kronrod rule to 1e-8) and the thick sheet's volume integrated from
#: the geometry (:func:`~onefold_cad.geometry.thick_sheet.slab_volume`,
#: about 1e-12). The edge curves' deviation (SOLID_TOLERANCE) moves the
#: volume by a few 1e-6; a face missing or doubled by a wrong construction
#: moves it by far more.
SOLID_VOLUME_TOLERANCE = 1e-4
#: Seconds the CAD kernel may spend on one part before the build gives up
#: with a clear error (the solid takes well under 1 s, a shell of 3000
#: divisions about 2 s).
KERNEL_BUDGET = 60.0
#: The smallest relief hole (diameter, design unit) the CAD kernel resolves:
#: 1000 x its precision (Precision::Confusion, 1e-7).
MIN_HOLE = 1e-4
#: Where a part is written: as it stands on the ground, or in the fold frame.
PLACEMENTS = ("rest", "frame")


def build_shell(
    folded: FoldedSheet,
    *,
    relief_hole: float = 0.0,
    faces: str | None = None,
    budget: float | None = KERNEL_BUDGET,
) -> bd.Shell:
    """The folded surface as one build123d Shell (top side = face normals).

    Args:
        folded: the fold of a design (:func:`onefold_cad.build_design`).
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
            "relief_hole", f"diameter must be in [0, {limit:.6g}) (length), got {relief_hole:g}"
        )
    if 0.0 < relief_hole < MIN_HOLE:
        raise ExportError(
            f"a relief hole of diameter {relief_hole:.3g} is below what the CAD kernel "
            f"resolves ({MIN_HOLE:g}): use none (--relief-hole 0) or one of at least {MIN_HOLE:g}"
        )
    tol = BOUNDARY_TOLERANCE * folded.sheet.size
    if kind == "ruled":
        problem = near_edge_problem(folded.sheet)
        if problem is not None:
            raise problem
        _hole_arcs(folded.sheet, relief_hole)
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
        lengths = [
            folded.sheet.ray_lengths(s * a)
            for s, a in zip((1.0, -1.0), folded.ruling_angles, strict=True)
        ]
        problem = near_edge_problem(folded.sheet, np.concatenate(lengths))
        if problem is not None:
            raise problem
        triangles = sum(len(a) - 1 for a in folded.ruling_angles)
        clock = KernelBudget(
            budget, f"fewer divisions may help (this fan has {triangles} triangles)"
        )
        topo = fan_shell(folded, 0.5 * relief_hole, clock.check)
        deviation = 0.0
    shell = bd.Shell(topo)
    if not shell.is_valid:
        raise ExportError(
            "the shell of the folded surface is not valid" + _scale_hint(folded.sheet.size)
        )
    clock.check()
    shell.fit_deviation = deviation
    shell.fit_tolerance = tol if kind == "ruled" else 0.0
    return shell


#: The shortest ruling (distance from H to a vertex of the sheet, crease
#: ends included; design unit) the CAD kernel can make an edge of: its
#: precision, Precision::Confusion (BRepLib_MakeEdge takes ends that close
#: for one point and fails).
MIN_RULING = 1e-7


def _hole_arcs(sheet: Sheet, diameter: float) -> None:
    """Refuse a relief hole whose arc between the rulings to two neighbouring
    vertices (crease ends included) is no longer than the CAD kernel's
    precision on the sheet: a chord of d sin(dtheta / 2) for vertices dtheta
    apart as seen from H."""
    if diameter <= 0.0:
        return
    ang = np.sort(np.mod(sheet.polar_angles, 2.0 * math.pi))
    step = np.diff(np.concatenate([ang, ang[:1] + 2.0 * math.pi]))
    step = step[step > 1e-12]  # the exact shell merges rulings closer than that
    least = float(np.min(step))
    chord = diameter * math.sin(0.5 * least)
    if chord <= MIN_RULING:
        need = MIN_RULING / math.sin(0.5 * least)
        raise ExportError(
            f"no STEP of the exact model: the relief hole's arc between two vertices "
            f"{least:.3g} rad apart as seen from H is {chord:.3g} long, no longer than the "
            f"shortest edge the CAD kernel can make ({MIN_RULING:g}); a relief hole over "
            f"{need:.3g} across or none (parameter relief_hole)"
        )


def _rectangle_advice(sheet: Sheet, ruling: bool, need: float) -> tuple[str, str]:
    """The parameter and the change for a rectangle whose H lies too close to
    a corner (``ruling``) or a side: H is at (f w, f h), min(f, 1 - f) x
    hypot(w, h) from the nearest corner and min(f, 1 - f) x min(w, h) from
    the nearest side; both must reach ``need``."""
    w, h, f = (float(sheet.inputs[k]) for k in ("width", "height", "apex_fraction"))
    least = need / (math.hypot(w, h) if ruling else min(w, h))
    if least < 0.5:
        return "apex_fraction", f"apex_fraction {f!r}: use one in [{least:.3g}, 1 - {least:.3g}]"
    if ruling:
        return (
            "width",
            f"width and height: the diagonal {math.hypot(w, h):.3g} must exceed {2.0 * need:.3g}",
        )
    short = "width" if w < h else "height"
    return short, f"{short} {min(w, h):.6g}: it must exceed {2.0 * need:.3g}"


def _quadrilateral_advice(sheet: Sheet, ruling: bool, need: float) -> tuple[str, str]:
    """The parameter and the change for a quadrilateral whose vertex
    (``ruling``) or edge lies too close to H: the vertices are x_plus ...
    from H, and the edge from (a, 0) to (0, b) passes a b / hypot(a, b) from
    it; the shorter of the two sets that distance."""
    values = {k: float(sheet.inputs[k]) for k in ("x_plus", "y_plus", "x_minus", "y_minus")}
    if ruling:
        name = min(values, key=values.__getitem__)
        return name, f"{name} {values[name]!r}: it must exceed {need:.3g}"
    pairs = [("x_plus", "y_plus"), ("x_minus", "y_plus"), ("x_minus", "y_minus")]
    pairs.append(("x_plus", "y_minus"))
    gap = [values[p] * values[q] / math.hypot(values[p], values[q]) for p, q in pairs]
    pair = pairs[int(np.argmin(gap))]
    small, big = sorted(pair, key=values.__getitem__)
    if values[big] <= need:
        return small, f"{small} and {big}: both must exceed {need:.3g}"
    want = need * values[big] / math.sqrt(values[big] ** 2 - need**2)
    return small, f"{small} {values[small]!r}: it must exceed {want:.3g}"


def near_edge_problem(sheet: Sheet, fan_rulings: np.ndarray | None = None) -> ExportError | None:
    """Why the exact model's shell cannot be built for ``sheet``, or None.

    ``fan_rulings``: the paper model's ruling lengths (its fan of planar
    triangles): then only the first bound applies, to them (the fan fits no
    curves and merges ruling ends closer than the kernel resolves).

    Two bounds, both on how close H lies to the sheet's boundary:

    * a ruling (H to a vertex, crease ends included) no longer than
      :data:`MIN_RULING` (the CAD kernel's precision, 1e-7 design units):
      the kernel cannot make an edge that short;
    * an edge passing closer to H than :data:`BOUNDARY_TOLERANCE` x the
      sheet's size (the tolerance to which the faces' boundary curves are
      fitted along the cone's rulings): the face between that edge and the
      apex is narrower than its own boundary's tolerance, and the fitted
      curve may cross the apex or its rulings;
    * a sheet edge (between neighbouring vertices, crease ends included) no
      longer than :data:`MIN_RULING`.

    The error names the parameter that puts H there (``apex_fraction``, the
    shorter side, ``x_plus`` ..., or ``polygon``), the distance measured,
    the bound and what to change.
    """
    v = sheet.vertices
    fan = fan_rulings is not None
    ruling = float(np.min(fan_rulings if fan else np.hypot(v[:, 0], v[:, 1])))
    sides = np.hypot(*(np.roll(v, -1, axis=0) - v).T)
    edge_gap = sheet_inradius(sheet)
    rel = BOUNDARY_TOLERANCE * sheet.size
    model = "paper" if fan else "exact"
    if ruling <= MIN_RULING:
        what = (
            f"a ruling from H is {ruling:.3g} long (H that close to the sheet's boundary), no "
            f"longer than the shortest edge the CAD kernel can make ({MIN_RULING:g}, its "
            "precision Precision::Confusion)"
        )
        need, short = MIN_RULING, True
    elif fan:
        return None
    elif edge_gap < rel:
        what = (
            f"an edge of the sheet passes {edge_gap:.3g} from H, less than the boundary "
            f"tolerance {rel:.3g} (BOUNDARY_TOLERANCE {BOUNDARY_TOLERANCE:g} x the sheet's "
            f"size {sheet.size:.6g}): the face between it and the apex would be narrower "
            "than its own boundary curve's tolerance"
        )
        need, short = rel, False
    elif float(np.min(sides)) <= MIN_RULING:
        k = int(np.argmin(sides))
        return ExportError(
            f"no STEP of the exact model: the sheet's edge {k} (from {v[k].tolist()} to "
            f"{v[(k + 1) % len(v)].tolist()}, the crease's ends counted as vertices) is "
            f"{sides[k]:.3g} long, no longer than the shortest edge the CAD kernel can make "
            f"({MIN_RULING:g}, its precision Precision::Confusion); make it longer or drop "
            "the vertex (parameter polygon)"
        )
    else:
        return None
    if sheet.kind == "rectangle":
        name, change = _rectangle_advice(sheet, short, need)
    elif sheet.kind == "quadrilateral":
        name, change = _quadrilateral_advice(sheet, short, need)
    else:
        name, change = "polygon", "polygon: move its vertices and edges further from H (0, 0)"
    other = "" if fan else ", or use the paper model (--model paper)"
    return ExportError(
        f"no STEP of the {model} model: {what}; change {change} (parameter {name}){other}"
    )


def _scale_hint(size: float) -> str:
    """Why a sheet of ``size`` (design unit) may be too big for the CAD
    kernel, when it is: the last place of its coordinates is coarser than
    the kernel's precision (1e-7), so the kernel's "same point" tests cannot
    hold ('' below that)."""
    ulp = math.ulp(size)
    if ulp <= MIN_RULING:
        return ""
    return (
        f"; on a sheet of size {size:.3g} the coordinates' last place is {ulp:.2g}, "
        f"{ulp / MIN_RULING:.2g} x the CAD kernel's precision (1e-7): a larger unit "
        "(parameter units: in or ft for a mm design) or a smaller sheet may help"
    )


def build_solid(
    folded: FoldedSheet, material: Material, *, budget: float | None = KERNEL_BUDGET
) -> bd.Solid:
    """The sheet as a solid of thickness ``material.thickness`` (> 0), exact model.

    The reference surface is the folded surface; the material lies on the side
    that ``material.sheet_surface`` names (:func:`sheet_offsets`). The relief
    hole, ``material.relief_hole_diameter``, is required: the cone's apex is
    singular and its offsets fold over near it
    (:func:`onefold_cad.design.solid_min_relief_hole`).
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
        raise InvalidParameterError("thickness", f"must be > 0 for a solid, got {t:g}")
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
            f"{t:g} ({material.sheet_surface.value}), got {hole:g}",
        )
    _mitre_limits(folded, material)
    size = folded.sheet.size
    tol = min(SOLID_TOLERANCE * size, SOLID_THICKNESS_TOLERANCE * t)
    slab = Slab(folded, material, hole)
    hint = _near_symmetric(slab) or (
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
    expected = slab.volume()
    if not (valid and abs(volume - expected) <= SOLID_VOLUME_TOLERANCE * expected):
        raise ExportError(
            f"thickness {t:g} gave an invalid solid on this folded surface (valid "
            f"{valid}, volume {volume:.9g} vs {expected:.9g} integrated from the "
            f"geometry); {hint}"
        )
    clock.check()
    solid.fit_deviation = deviation
    solid.fit_tolerance = tol
    return solid


#: The smallest mitre (length past or into the crease, design unit) the CAD
#: kernel resolves: 100 x its precision (Precision::Confusion, 1e-7) ...
MIN_MITRE = 1e-5
#: ... and relative to the crease half's length (thinner, the mitre's faces
#: are slivers OCC cannot classify: 1.4 micrometres by 2.3 m fails).
MIN_MITRE_REL = 1e-6
#: The mitre may reach at most this fraction of a crease half's length into
#: the sheet: beyond it the fold's two sides come within the sheet's
#: thickness of each other over much of the crease (folds near 180 deg).
MAX_MITRE_REACH = 0.5


def _mitre_limits(folded: FoldedSheet, material: Material) -> None:
    """Refuse a solid whose mitre the CAD kernel cannot resolve (a nearly flat
    fold) or whose two sides overlap (a fold near 180 deg), naming the crease
    half, its fold angle and what to change."""
    t = material.thickness
    side = SideMap(folded)
    for half, (depth, reach) in zip(
        folded.crease, mitre_reach(side, sheet_offsets(material)), strict=True
    ):
        least = max(MIN_MITRE, MIN_MITRE_REL * half.length)
        if 0.0 < max(depth, reach) < least:
            raise ExportError(
                f"no solid of thickness {t:g}: the fold along {half.name} is nearly flat "
                f"({half.fold_angle_deg:.3g} deg), its mitre only {max(depth, reach):.2g} deep, "
                f"below what the CAD kernel resolves ({least:.2g}); write the shell "
                "(--body shell) or fold it more (larger alpha or beta)"
            )
        if reach > MAX_MITRE_REACH * half.length:
            raise ExportError(
                f"no solid of thickness {t:g}: the fold along {half.name} is nearly closed "
                f"({half.fold_angle_deg:.4g} deg): the two sides come within the thickness of "
                f"each other {reach:.3g} into the sheet, more than half the crease "
                f"({half.length:.3g}); a thinner sheet or a smaller fold angle (alpha, beta), "
                "or the shell (--body shell)"
            )


def _near_symmetric(slab: Slab) -> str:
    """Advice for a sheet whose edges at a crease half's end are mirror images
    of each other to within a hair but not exactly: there the two sides'
    mitre sections differ by a sliver below the CAD kernel's resolution.
    '' when that is not the case."""
    size = slab.sides[0].sheet.size
    for end, name in ((0, "plus_x"), (1, "minus_x")):
        t = np.linspace(0.0, 0.05, 11)
        t = t if end == 0 else slab.total - t
        gap = float(np.max(np.abs(slab.outer_radius(0, t) - slab.outer_radius(1, t))))
        if 0.0 < gap < 1e-5 * size:
            return (
                f"the sheet's edges at the {name} end are symmetric about the crease to within "
                f"{gap:.2g} but not exactly: make them exactly symmetric (or differ more)"
            )
    return ""


def _fabrication_limits(design: Design, folded: FoldedSheet, compensation: str) -> None:
    """Refuse a solid past the bend model's limits (FabricationError: a bend
    zone reaching a sheet corner, a large set-back beside the flanges, a fold
    near 180 deg) unless ``compensation`` is 'none':
    :func:`onefold_cad.design.solid_bend_problem`, the check ``build`` also
    makes before it writes anything."""
    problem = solid_bend_problem(design, folded, compensation)
    if problem is not None:
        raise problem


def place(part: bd.Shape, placement: RestingPlacement) -> bd.Shape:
    """``part`` moved by the rigid motion of ``placement`` (rotation, then
    translation; :func:`onefold_cad.design.resting_placement`), then lifted or
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
    for name in ("fit_deviation", "fit_tolerance"):
        if hasattr(part, name):
            setattr(out, name, getattr(part, name))
    return out


def build_part(
    design: Design,
    folded: FoldedSheet | None = None,
    *,
    body: str | None = None,
    placement: str = "rest",
    compensation: str = "sharp",
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
            :func:`onefold_cad.design.default_body`.
        placement: 'rest' (default): standing on the ground, lowest point on
            z = 0 (:func:`place` with
            :func:`onefold_cad.design.resting_placement` of this body);
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
    if body not in ("shell", "solid"):
        raise InvalidParameterError("body", f"must be 'shell' or 'solid', got {body!r}")
    if placement not in PLACEMENTS:
        raise InvalidParameterError("placement", f"must be 'rest' or 'frame', got {placement!r}")
    folded = build_design(design) if folded is None else folded
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


def export_design_step(
    design: Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    body: str | None = None,
    placement: str = "rest",
    compensation: str = "sharp",
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
            + _scale_hint(sheet.size)
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
