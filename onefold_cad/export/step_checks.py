"""The STEP part's pre-flight checks, numpy only: what the CAD kernel cannot
build (an edge shorter than its precision, a face narrower than its boundary
curves' tolerance, a mitre thinner than it resolves), refused with the
parameter to change and by how much before any kernel call.

Lengths are in the design's unit.
"""

from __future__ import annotations

import math

import numpy as np

from onefold_cad.errors import ExportError, OneFoldError
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.sheet import Sheet, sheet_inradius
from onefold_cad.geometry.slab import Slab
from onefold_cad.geometry.thick_map import SideMap, mitre_reach

__all__ = [
    "BOUNDARY_TOLERANCE",
    "MAX_MITRE_REACH",
    "MIN_HOLE",
    "MIN_MITRE",
    "MIN_MITRE_REL",
    "MIN_RULING",
    "check_hole_arcs",
    "check_mitre",
    "near_edge_problem",
    "near_symmetric_hint",
    "quadrilateral_advice",
    "rectangle_advice",
    "scale_hint",
    "shell_problem",
]

#: Deviation allowed for the boundary curves on the cone, relative to sheet.size.
BOUNDARY_TOLERANCE = 1e-7
#: The smallest relief hole (diameter, design unit) the CAD kernel resolves:
#: 1000 x its precision (Precision::Confusion, 1e-7).
MIN_HOLE = 1e-4
#: The shortest ruling (distance from H to a vertex of the sheet, crease
#: ends included; design unit) the CAD kernel can make an edge of: its
#: precision, Precision::Confusion (BRepLib_MakeEdge takes ends that close
#: for one point and fails).
MIN_RULING = 1e-7


def check_hole_arcs(sheet: Sheet, diameter: float) -> None:
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


def shell_problem(folded: FoldedSheet, relief_hole: float) -> OneFoldError | None:
    """What the shell's builder (:func:`onefold_cad.export.part.build_shell`)
    refuses before any kernel call, or None: a relief hole below
    :data:`MIN_HOLE`, H too close to the sheet's boundary
    (:func:`near_edge_problem`: the exact cone's faces, the paper model's
    ruling lengths) or a relief hole's arc too short (:func:`check_hole_arcs`).
    ``build`` asks before it writes anything, so such a refusal is its one line."""
    if 0.0 < relief_hole < MIN_HOLE:
        return ExportError(
            f"a relief hole of diameter {relief_hole:.3g} is below what the CAD kernel "
            f"resolves ({MIN_HOLE:g}): use none (--relief-hole 0) or one of at least {MIN_HOLE:g}"
        )
    sheet = folded.sheet
    if not isinstance(folded.solution.surface, ExactCone):
        lengths = [
            sheet.ray_lengths(s * a) for s, a in zip((1.0, -1.0), folded.ruling_angles, strict=True)
        ]
        return near_edge_problem(sheet, np.concatenate(lengths))
    problem = near_edge_problem(sheet)
    if problem is not None:
        return problem
    try:
        check_hole_arcs(sheet, relief_hole)
    except ExportError as exc:
        return exc
    return None


def rectangle_advice(sheet: Sheet, ruling: bool, need: float) -> tuple[str, str]:
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


def quadrilateral_advice(sheet: Sheet, ruling: bool, need: float) -> tuple[str, str]:
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
    ruling = float(np.min(np.hypot(v[:, 0], v[:, 1]) if fan_rulings is None else fan_rulings))
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
        name, change = rectangle_advice(sheet, short, need)
    elif sheet.kind == "quadrilateral":
        name, change = quadrilateral_advice(sheet, short, need)
    else:
        name, change = "polygon", "polygon: move its vertices and edges further from H (0, 0)"
    other = "" if fan else ", or use the paper model (--model paper)"
    return ExportError(
        f"no STEP of the {model} model: {what}; change {change} (parameter {name}){other}"
    )


def scale_hint(size: float) -> str:
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


def check_mitre(folded: FoldedSheet, material: Material) -> None:
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


def near_symmetric_hint(slab: Slab) -> str:
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
