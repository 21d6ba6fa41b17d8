"""NAME.fold: the design as a FOLD 1.2 file for origami tools (Origami
Simulator, Rabbit Ear, the FOLD viewer).

Spec: edemaine/fold, doc/spec.md (version 1.2). The file holds two frames:

* the key frame, ``frame_classes: ["creasePattern"]``: the flat sheet (2D,
  in the sheet's own frame, as in the DXF), triangulated along its rulings;
* ``file_frames[0]``, ``["foldedForm"]``, ``frame_parent: 0``,
  ``frame_inherit: true``: the same vertices folded (3D), standing as the
  form rests on the ground (z = 0; :attr:`FoldedSheet.resting`).

The mesh is a fan about H: one vertex at H, one at every ruling's end on the
outline, one triangle between each two neighbouring rulings (counter-clockwise
in the crease pattern, so every face's normal is the sheet's top, +z, side).
Edges: ``B`` on the outline; the two crease halves ``V`` or ``M`` from their
bend direction (:attr:`CreaseHalf.bend` 'UP' rotates both sides towards the
top side, +z: a valley seen from +z); the rulings ``V``/``M`` by the sign of
their own small dihedral angle, or ``F`` where they run inside a planar
triangle of the fan (the rulings through polygon vertices); both from
:mod:`onefold_cad.geometry.fan_folds`, as the DXF's ruling folds. ``edges_foldAngle``
is in degrees, valley positive, mountain negative, 0 for ``F`` and ``B``
(the spec's convention).

Which polyhedral surface. The paper model is a fan of planar triangles: it is
written as it is, every ruling of :attr:`FoldedSheet.rulings_flat` /
``rulings_3d`` (the division rays and the rays through polygon vertices) an
edge. The exact model is a smooth cone, which a FOLD file (flat faces) can only
approximate. The obvious approximation, a polyhedral cone inscribed in the
exact one (the exact apex, rulings at chosen angles), is not isometric to the
flat sheet: its triangles' apex angles are chords of the cone's directions,
so they add up to less than 180 deg per side and the folded triangles cannot
have their flat shapes. The isometric approximation is the paper's fan over
the same frame curve with ``frame.divisions`` triangles per side, solved for
its own apex (the angle condition then holds exactly for the fan). That is what
an exact-model design writes; its folded frame differs from the exact cone by
O(1 / divisions^2), and the file records the largest distance between the two
(fold frame, matched by flat point) as ``onefold:max_deviation_from_exact``.
So the folded frame is exact to itself: every edge keeps its flat length and
every dihedral angle equals its ``edges_foldAngle``, to rounding.

The relief hole is not cut: the FOLD file describes the folded reference
surface, whose rulings all meet at H (origami tools expect that vertex); the
hole is a fabrication detail of the DXF and STEP, recorded here as
``onefold:relief_hole_diameter``.

Units: ``frame_unit`` is the design's unit ('mm' and 'in' are the spec's own
values; 'ft' is a custom value the spec allows, with ``onefold:mm_per_unit``
so a reader can convert). Our extra values carry the ``onefold:`` prefix.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from onefold_cad.design import Design, relief_hole_diameter
from onefold_cad.errors import InvalidParameterError, NoSolutionError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.geometry.cone import PaperFan
from onefold_cad.geometry.fan_folds import on_division_rays, ring_angles, signed_fold_angles
from onefold_cad.geometry.folding import FoldedSheet, fold
from onefold_cad.geometry.params import Model
from onefold_cad.geometry.solver import solve

__all__ = ["FOLD_SPEC", "fold_data", "fold_fan", "write_fold"]

#: The FOLD spec version written.
FOLD_SPEC = 1.2
Array = NDArray[np.float64]


def fold_fan(design: Design, folded: FoldedSheet) -> FoldedSheet:
    """The paper-model fan the FOLD file triangulates: ``folded`` itself for the
    paper model; for the exact model the paper's fan over the same frame curve
    and ``divisions``, solved for its own apex and folded (see the module notes).

    Raises:
        InvalidParameterError: ('divisions') the fan of that many divisions has
            no non-trivial apex (always so for 1 division).
    """
    if isinstance(folded.solution.surface, PaperFan):
        return folded
    try:
        return fold(solve(design.frame, Model.PAPER), design.sheet)
    except NoSolutionError:
        raise InvalidParameterError(
            "divisions",
            f"the FOLD file approximates the exact cone by the paper fan of "
            f"{design.frame.divisions} triangles per side, which has no non-trivial apex "
            "for this frame; use more divisions (at least 2)",
        ) from None


def fold_data(design: Design, folded: FoldedSheet) -> dict[str, Any]:
    """The FOLD 1.2 document of ``design`` as a JSON-ready dict.

    Args:
        design: the design (name, units, frame, sheet, material).
        folded: its fold (:func:`onefold_cad.build_design`).

    Returns:
        The key frame (crease pattern, 2D, the sheet's own frame) with the
        folded form as ``file_frames[0]`` (3D, standing on z = 0); lengths in
        ``design.units``. Vertex 0 is H; vertex 1 + i is the i-th ruling end
        counter-clockwise from the +x crease end. Edge i is the ruling to
        vertex 1 + i, edge n + i the outline from vertex 1 + i to the next.
    """
    fan = fold_fan(design, folded)
    theta, minus_x = ring_angles(fan)
    flat = np.vstack([np.zeros((1, 2)), fan.boundary_flat])
    pts3 = np.vstack([fan.apex[None, :], fan.boundary_3d])
    n = len(theta)
    ring = np.arange(1, n + 1)
    edges = [[0, int(v)] for v in ring] + [
        [int(v), int(ring[(i + 1) % n])] for i, v in enumerate(ring)
    ]

    angle = signed_fold_angles(fan.apex, fan.boundary_3d)
    division = on_division_rays(theta, fan)
    assignment = np.where(angle > 0.0, "V", np.where(angle < 0.0, "M", "F")).astype(object)
    kind = np.full(n, "ruling", dtype=object)
    flat_ray = ~division
    assignment[flat_ray], angle[flat_ray], kind[flat_ray] = "F", 0.0, "flat_ruling"
    for i, half in ((0, fan.crease[0]), (minus_x, fan.crease[1])):
        valley = half.bend == "UP"  # both sides turn towards +z: a valley seen from +z
        assignment[i] = "V" if valley else "M"
        angle[i] = half.fold_angle_deg if valley else -half.fold_angle_deg
        kind[i] = f"crease_{half.name}"

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
            else f"the paper fan of {frame.divisions} divisions per side over the exact "
            "model's frame curve, solved for its own apex: the isometric polyhedral "
            "approximation of the exact cone"
        ),
        "onefold:apex_height": fan.solution.apex_height,
        "onefold:crease": [
            {"name": c.name, "length": c.length, "fold_angle_deg": c.fold_angle_deg, "bend": c.bend}
            for c in fan.crease
        ],
        "onefold:relief_hole_diameter": relief_hole_diameter(design, folded),
        "onefold:relief_hole_cut": False,
        "onefold:resting_tilt_deg": fan.resting.tilt_deg,
    }
    if fan is not folded:
        exact = folded.map_points(fan.boundary_flat)
        dev = max(
            float(np.max(np.linalg.norm(exact - fan.boundary_3d, axis=1))),
            abs(fan.solution.apex_height - folded.solution.apex_height),
        )
        extras["onefold:exact_apex_height"] = folded.solution.apex_height
        extras["onefold:max_deviation_from_exact"] = dev

    folded_frame = {
        "frame_title": f"{design.name}: folded, standing on the ground (z = 0)",
        "frame_classes": ["foldedForm"],
        "frame_attributes": ["3D", "manifold", "orientable", "convexFaces"],
        "frame_parent": 0,
        "frame_inherit": True,
        "vertices_coords": fan.resting.apply(pts3).tolist(),
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
        "vertices_coords": design.sheet.to_sheet.apply(flat).tolist(),
        "edges_vertices": edges,
        "edges_assignment": list(assignment) + ["B"] * n,
        "edges_foldAngle": [float(a) for a in angle] + [0.0] * n,
        "edges_onefold:kind": list(kind) + ["outline"] * n,
        "faces_vertices": [[0, int(ring[i]), int(ring[(i + 1) % n])] for i in range(n)],
        **extras,
        "file_frames": [folded_frame],
    }
    return doc


def _version() -> str:
    from onefold_cad import __version__

    return __version__


def write_fold(design: Design, folded: FoldedSheet, path: str | os.PathLike[str]) -> Path:
    """Write ``design`` as a FOLD 1.2 file (:func:`fold_data`), atomically.

    Returns:
        The path written.

    Raises:
        ExportError: the file could not be written.
        InvalidParameterError: ('divisions') the exact model's fan
            approximation has no apex (:func:`fold_fan`).
    """
    out = Path(path)
    text = json.dumps(fold_data(design, folded), indent=1, allow_nan=False)
    with atomic_output(out) as tmp:
        tmp.write_text(text + "\n", encoding="utf-8")
    return out
