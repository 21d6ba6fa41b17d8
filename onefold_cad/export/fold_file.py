"""NAME.fold: the design as a FOLD 1.2 file for origami tools (Origami
Simulator, Rabbit Ear, the FOLD viewer).

Spec: edemaine/fold, doc/spec.md (version 1.2). The file holds two frames:

* the key frame, ``frame_classes: ["creasePattern"]``: the flat sheet (2D,
  in the sheet's own frame, as in the DXF), triangulated along its folds;
* ``file_frames[0]``, ``["foldedForm"]``, ``frame_parent: 0``,
  ``frame_inherit: true``: the same vertices folded (3D), standing as the
  form rests on the ground (z = 0; :func:`onefold_cad.design.rest_once`).

The mesh (:mod:`onefold_cad.export.fold_mesh`) is the fan's crease pattern
triangulated for simulators: only the division rays fold; each planar wedge
between two of them, clipped to the outline and to the relief hole
(:func:`onefold_cad.fabrication.relief_hole.relief_hole_diameter` > 0: the
polygon of its crossings with the division rays), is triangulated with a
quality bound, no face angle under ``fold_mesh.MIN_FACE_ANGLE_DEG`` and no
edge under ``fold_mesh.MIN_EDGE`` of the sheet's size where the design
allows it (``onefold:mesh`` records what the file reached). Faces are
counter-clockwise in the crease pattern, so every face's normal is the
sheet's top, +z, side. Edges: ``B`` on the outline and the hole; the two
crease halves ``V`` or ``M`` from their bend direction (:attr:`CreaseHalf.bend`
'UP' rotates both sides towards the top side, +z: a valley seen from +z);
the division rays ``V``/``M`` by the sign of their own small dihedral angle
(:mod:`onefold_cad.geometry.fan_folds`, as the DXF's ruling folds); ``F``
inside a wedge. ``edges_foldAngle`` is in degrees, valley positive,
mountain negative, 0 for ``F`` and ``B`` (the spec's convention).

Which polyhedral surface. A FOLD file has flat faces, and simulators fold
it with explicit solvers that a vertex of many edges makes unstable (Origami
Simulator: see docs/formats.md, "vertex load"). So the file folds a paper
fan over the design's frame curve with its own division count,
:func:`fold_divisions` (:data:`FOLD_DIVISIONS` per side, or a paper-model
design's own divisions if fewer: then it is written as it is), graded
towards the crease (narrow wedges beside it; gently with a relief hole,
whose sides must stay long for Origami Simulator) and tangent-ended at the
design's apex (:mod:`onefold_cad.export.fold_fan`): the wedges beside the
crease lie in the design's tangent planes along it, so the file's crease
folds as the design's, and the directions between are moved off the
division points just enough for the fan to fold from the flat sheet. Each
ray's fold angle is that fan's. It approximates the design's surface (the
exact cone, or the paper fan of more divisions) to O(1 / divisions^2);
``onefold:max_deviation_from_design`` records the largest distance between
the two (fold frame, matched by flat point), ``onefold:design_crease_fold_angle_deg``
the design's crease, ``onefold:notes`` what a reader must know of the
file (a crease more than ``fold_fan.CREASE_TOLERANCE_DEG`` from the
design's; none for the fans ``build`` writes), and ``onefold:mesh`` both
division counts and the grading (``grading_ratio``,
``wedge_widths_of_span``: each wedge's share of the arc,
``crease_wedges_deg``: the flat angles beside the two crease halves). An
inscribed polyhedral cone (the exact apex, rulings at chosen angles) would
not do: its triangles' apex angles are chords of the cone's directions, so
they add up to less than 180 deg per side and the folded triangles cannot
have their flat shapes. So the folded frame is exact to itself: every edge keeps its
flat length and every dihedral angle equals its ``edges_foldAngle``, to
rounding.

The relief hole is cut as the polygon of its crossings with the division
rays, so every edge of it is a chord of a planar wedge and the file stays
exact to itself; ``onefold:relief_hole_diameter`` records the circle's diameter and
``onefold:relief_hole_cut`` whether there is one.

Units: ``frame_unit`` is the design's unit ('mm' and 'in' are the spec's own
values; 'ft' is a custom value the spec allows, with ``onefold:mm_per_unit``
so a reader can convert). Our extra values carry the ``onefold:`` prefix.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.design import Design, rest_once
from onefold_cad.errors import FabricationError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.fold_fan import (  # the file's fan: see the module notes
    FOLD_DIVISIONS,
    GRADING_RATIO,
    HOLE_GRADING_RATIO,
    fold_divisions,
    fold_fan,
    fold_note,
)
from onefold_cad.export.fold_mesh import FACET, division_rays, fold_mesh, mesh_quality
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.sheet import sheet_inradius
from onefold_cad.geometry.tangent_fan import TangentEndedFan

__all__ = [
    "FOLD_DIVISIONS",
    "FOLD_SPEC",
    "RESOLUTION",
    "fold_data",
    "fold_divisions",
    "fold_fan",
    "fold_note",
    "write_fold",
]

#: The FOLD spec version written.
FOLD_SPEC = 1.2
#: The shortest edge a cut relief hole may add, relative to the sheet's size
#: (:attr:`Sheet.size`): shorter ones would leave faces of no area once the
#: coordinates are rounded (about 1e-16 of the size).
RESOLUTION = 1e-12


def _hole_radius(design: Design, fan: FoldedSheet, hole: float) -> float:
    """The relief hole's radius (``hole / 2``), once it is known to fit.

    Raises:
        FabricationError: ('relief_hole' or 'thickness') the hole does not
            fit inside the sheet around H; ('relief_hole') it would add an
            edge shorter than :data:`RESOLUTION` x the sheet's size.
    """
    radius = hole / 2.0
    inner = sheet_inradius(design.sheet)
    if radius >= inner:
        u = design.units.value
        raise relief_hole_problem(design) or FabricationError(
            "relief_hole",
            f"diameter {hole:g} {u} must be < {2.0 * inner:.6g} {u} (twice the distance from "
            "H to the nearest sheet edge)",
        )
    theta = division_rays(fan)[0]
    gamma = np.diff(np.append(theta, theta[0] + 2.0 * math.pi))
    unit_chord = float(np.min(2.0 * np.sin(gamma / 2.0)))
    length = np.linalg.norm(fan.boundary_flat, axis=1)  # ray ends and corners
    _check_resolution(design, hole, unit_chord, length - radius)
    return radius


def _check_resolution(design: Design, hole: float, unit_chord: float, rest: Array) -> None:
    """Refuse a hole whose new edges the file cannot hold: every edge of the
    hole's polygon (the shortest is ``unit_chord`` x the radius) and every
    ruling's part outside the hole (``rest``) must be at least
    :data:`RESOLUTION` x the sheet's size long, or faces beside them collapse
    when the coordinates are rounded."""
    tau = RESOLUTION * design.sheet.size
    u = design.units.value
    chord = unit_chord * hole / 2.0
    if chord < tau:
        need = 2.0 * tau / unit_chord
        step = 10.0 ** (math.floor(math.log10(need)) - 2)
        need = math.ceil(need / step) * step  # 3 digits, rounded up
        raise FabricationError(
            "relief_hole",
            f"diameter {hole:.6g} {u} is too small for the FOLD file: the hole's edge "
            f"between two rulings would be {chord:.3g} {u} long, under its resolution "
            f"{tau:.3g} {u} ({RESOLUTION:g} of the sheet's size); use at least {need:.3g} {u}, "
            "or no relief hole (0)",
        )
    if rest.min() < tau:
        most = 2.0 * (rest.min() + hole / 2.0 - 2.0 * tau)
        raise FabricationError(
            "relief_hole",
            f"diameter {hole:.17g} {u} is too large for the FOLD file: a ruling would keep "
            f"{rest.min():.3g} {u} outside the hole, under its resolution {tau:.3g} {u} "
            f"({RESOLUTION:g} of the sheet's size); use at most {most:.17g} {u}",
        )


def fold_data(design: Design, folded: FoldedSheet, divisions: int | None = None) -> dict[str, Any]:
    """The FOLD 1.2 document of ``design`` as a JSON-ready dict.

    Args:
        design: the design (name, units, frame, sheet, material).
        folded: its fold (:func:`onefold_cad.fold_design`).
        divisions: the file's fan's divisions per side (None:
            :func:`fold_divisions`).

    Returns:
        The key frame (crease pattern, 2D, the sheet's own frame) with the
        folded form as ``file_frames[0]`` (3D, standing on z = 0); lengths in
        ``design.units``. Without a relief hole vertex 0 is H (a disc:
        V - E + F = 1); with one, the sheet is an annulus (V - E + F = 0).
        ``edges_onefold:kind`` names each edge: 'crease_plus_x',
        'crease_minus_x', 'ruling' (on a division ray), 'facet' (inside a
        wedge), 'outline', 'hole'.

    Raises:
        FabricationError: the relief hole does not fit inside the sheet.
        InvalidParameterError: ('divisions') see :func:`fold_fan`.
    """
    fan = fold_fan(design, folded, divisions)
    hole = relief_hole_diameter(design, folded)
    radius = _hole_radius(design, fan, hole) if hole > 0.0 else 0.0
    mesh = fold_mesh(fan, radius)
    ray_assignment = np.where(
        mesh.ray_angle_deg > 0.0, "V", np.where(mesh.ray_angle_deg < 0.0, "M", "F")
    ).astype(object)
    ray_angle = mesh.ray_angle_deg.copy()
    ray_kind = np.full(len(ray_angle), "ruling", dtype=object)
    for i, half in ((0, fan.crease[0]), (mesh.minus_x, fan.crease[1])):
        valley = half.bend == "UP"  # both sides turn towards +z: a valley seen from +z
        ray_assignment[i] = "V" if valley else "M"
        ray_angle[i] = half.fold_angle_deg if valley else -half.fold_angle_deg
        ray_kind[i] = f"crease_{half.name}"
    on_ray = mesh.edge_ray >= 0
    assignment = np.where(mesh.edge_kind == FACET, "F", "B").astype(object)
    angle = np.zeros(len(mesh.edges))
    kind = mesh.edge_kind.copy()
    assignment[on_ray] = ray_assignment[mesh.edge_ray[on_ray]]
    angle[on_ray] = ray_angle[mesh.edge_ray[on_ray]]
    kind[on_ray] = ray_kind[mesh.edge_ray[on_ray]]
    quality = mesh_quality(mesh, design.sheet.size)
    n = len(mesh.ray_theta) // 2
    quality |= {"divisions": n, "design_divisions": design.frame.divisions}
    surface = fan.solution.surface
    spacing = surface.spacing if isinstance(surface, PaperFan) else None
    if isinstance(surface, PaperFan) and spacing is not None:  # fold_fan's graded wedges
        assert surface.gammas is not None  # a solved fan has its apex angles
        steps = np.asarray(spacing.steps)
        widths = np.abs(np.diff(steps)) / spacing.per_span
        quality |= {
            "grading_ratio": GRADING_RATIO if hole == 0.0 else HOLE_GRADING_RATIO,
            "wedge_widths_of_span": widths.tolist(),
            "crease_wedges_deg": np.degrees(surface.gammas[[0, -1]]).tolist(),
        }

    units = design.units.value
    frame = design.frame
    extras: dict[str, Any] = {
        "onefold:design": design.name,
        "onefold:model": design.model.value,
        "onefold:mm_per_unit": design.units.mm,
        "onefold:frame": {
            "alpha_deg": frame.alpha,
            "beta_deg": frame.beta,
            "h_c": frame.h_c,
            "radius": frame.radius,
            "divisions": frame.divisions,
        },
        "onefold:surface": (
            "the paper model's fan of planar triangles"
            if fan is folded
            else (
                f"a graded fan of {n} divisions per side over the design's frame curve "
                "(onefold:mesh wedge_widths_of_span)"
                + (
                    ", tangent-ended at the design's apex: the wedges beside the crease lie "
                    "in the design's tangent planes along it, the directions between moved "
                    "off the division points so that the fan folds from the flat sheet"
                    if isinstance(surface, TangentEndedFan)
                    else ", solved for its own apex"
                )
                if spacing is not None
                else f"the paper fan of {n} equal divisions per side over the design's "
                "frame curve, solved for its own apex"
            )
            + f": an isometric polyhedral approximation of the design's {design.model.value} model"
        ),
        "onefold:apex_height": fan.solution.apex_height,
        "onefold:crease": [
            {"name": c.name, "length": c.length, "fold_angle_deg": c.fold_angle_deg, "bend": c.bend}
            for c in fan.crease
        ],
        "onefold:relief_hole_diameter": hole,
        "onefold:relief_hole_cut": hole > 0.0,
        "onefold:sheet_size": design.sheet.size,
        "onefold:mesh": quality,
        "onefold:resting_tilt_deg": rest_once(fan).tilt_deg,
        "onefold:notes": [n for n in [fold_note(design, folded, divisions)] if n is not None],
    }
    if fan is not folded:
        # at both fans' outline vertices and the mesh's: the larger gaps are at the outline
        pts = np.vstack([fan.boundary_flat, folded.boundary_flat, mesh.flat])
        gap = np.linalg.norm(folded.map_points(pts) - fan.map_points(pts), axis=1)
        dev = max(
            float(np.max(gap)),
            abs(fan.solution.apex_height - folded.solution.apex_height),
        )
        extras["onefold:design_apex_height"] = folded.solution.apex_height
        extras["onefold:design_crease_fold_angle_deg"] = [c.fold_angle_deg for c in folded.crease]
        extras["onefold:max_deviation_from_design"] = dev

    folded_frame = {
        "frame_title": f"{design.name}: folded, standing on the ground (z = 0)",
        "frame_classes": ["foldedForm"],
        "frame_attributes": ["3D", "manifold", "orientable", "convexFaces"],
        "frame_parent": 0,
        "frame_inherit": True,
        "vertices_coords": rest_once(fan).apply(mesh.folded).tolist(),
    }
    doc: dict[str, Any] = {
        "file_spec": FOLD_SPEC,
        "file_creator": f"onefold_cad {_version()}",
        "file_title": design.name,
        "file_description": design.description
        or f"One-Fold design {design.name}: crease pattern and folded form",
        "file_classes": ["singleModel"],
        "frame_title": f"{design.name}: crease pattern (the flat sheet, top side +z)",
        "frame_classes": ["creasePattern"],
        "frame_attributes": [
            "2D",
            "manifold",
            "orientable",
            "nonSelfTouching",
            "nonSelfIntersecting",
            "convexFaces",
        ],
        "frame_unit": units,
        "vertices_coords": design.sheet.to_sheet.apply(mesh.flat).tolist(),
        "edges_vertices": mesh.edges.tolist(),
        "edges_assignment": [str(a) for a in assignment],
        "edges_foldAngle": [float(a) for a in angle],
        "edges_onefold:kind": [str(k) for k in kind],
        "faces_vertices": mesh.faces.tolist(),
        **extras,
        "file_frames": [folded_frame],
    }
    return doc


def _version() -> str:
    from onefold_cad.version import __version__

    return __version__


def write_fold(design: Design, folded: FoldedSheet, path: str | os.PathLike[str]) -> Path:
    """Write ``design`` as a FOLD 1.2 file (:func:`fold_data`), atomically.

    Returns:
        The path written.

    Raises:
        ExportError: the file could not be written.
        FabricationError: the relief hole does not fit inside the sheet.
        InvalidParameterError: ('divisions') the exact model's fan
            approximation has no apex (:func:`fold_fan`).
    """
    out = Path(path)
    text = json.dumps(fold_data(design, folded), indent=1, allow_nan=False)
    with atomic_output(out) as tmp:
        tmp.write_text(text + "\n", encoding="utf-8")
    return out
