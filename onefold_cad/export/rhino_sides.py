"""The folded form as one rhino3dm Brep per side (a rhino3dm adapter): the
side's single NURBS face (:func:`~onefold_cad.export.rhino_faces.side_nets`,
on the exact cone to :data:`TOLERANCE` x the sheet's size) with its render
mesh and its user strings, checked valid by openNURBS. The .3dm writer
(:mod:`.rhino3dm_file`) calls :func:`fold_sides`; anything handing Breps on
(a Hops server) calls :func:`side_breps` (``Brep.Encode()`` gives the JSON
Grasshopper decodes, the render mesh and user strings included).

rhino3dm 8 binds no way to add faces, loops or trims to a Brep nor to join
Breps, so a side cannot be several faces in one Brep: it is one face whose
surface is C0 at the sheet's corners (Rhino's ``DivideAlongCreases`` splits
it there if separate faces are wanted).

Lengths are in the design unit.
"""

from __future__ import annotations

import ctypes
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import rhino3dm

from onefold_cad.choices import Body, Compensation, Placement
from onefold_cad.design import Design
from onefold_cad.errors import ExportError, InvalidParameterError
from onefold_cad.export.rhino_faces import (
    Place,
    SideNet,
    face_nets,
    nurbs_surface,
    render_mesh,
    side_nets,
)
from onefold_cad.export.rhino_strings import design_strings, report_strings
from onefold_cad.export.step_checks import BOUNDARY_TOLERANCE
from onefold_cad.fabrication.flat_pattern import FlatPattern
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
from onefold_cad.fabrication.rules import resting_placement
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = [
    "PLACEMENTS",
    "SIDE_NAMES",
    "TOLERANCE",
    "FoldSides",
    "attach_render_mesh",
    "fold_sides",
    "placement_of",
    "side_brep",
    "side_breps",
]

#: The faces' largest distance from the exact cone, relative to the sheet's size
#: (the STEP's boundary tolerance).
TOLERANCE = BOUNDARY_TOLERANCE
#: The sides' names: the +y side's, then the -y side's.
SIDE_NAMES = ("upper", "lower")
#: Where the form may stand: as it rests on the ground, or in the fold frame.
PLACEMENTS = ("rest", "frame")


@dataclass(frozen=True)
class FoldSides:
    """The folded form's side Breps and what was measured making them.

    Attributes:
        breps: ``(side name, Brep)`` for the upper (+y) and lower (-y) side.
        nets: the sides' control nets (fold frame).
        deviation: the faces' largest measured distance from the exact cone
            (length).
        tolerance: the distance allowed (length).
        strings: the user strings every side Brep carries besides its own
            (``side``, ``sectors``, ``fit_deviation``).
    """

    breps: tuple[tuple[str, Any], ...]
    nets: tuple[SideNet, ...]
    deviation: float
    tolerance: float
    strings: Mapping[str, str]


def attach_render_mesh(brep: rhino3dm.Brep, mesh: rhino3dm.Mesh) -> None:
    """Give ``brep``'s one face ``mesh`` as its render mesh.

    ``BrepFace.SetMesh`` hands the mesh to the face, which deletes it with
    the Brep, while the Python object still owns it too (rhino3dm 8: the
    process crashes on exit, a double free). The Python object is kept
    alive for good (a few bytes per face) so that only the face frees it.
    """
    ctypes.pythonapi.Py_IncRef(ctypes.py_object(mesh))
    if not brep.Faces[0].SetMesh(mesh, rhino3dm.MeshType.Render):
        raise ExportError("rhino3dm refused a face's render mesh")


def side_brep(
    folded: FoldedSheet,
    net: SideNet,
    hole_radius: float,
    place: Place,
    strings: Mapping[str, str] | None = None,
) -> Any:
    """One side as a one-face Brep, placed, with its render mesh and
    ``strings`` as its (geometry) user strings.

    Raises:
        ExportError: openNURBS finds the Brep invalid (with its log).
    """
    brep = rhino3dm.Brep.CreateFromSurface(nurbs_surface(net, place))
    if brep is None:
        raise ExportError("rhino3dm could not make a Brep of a side")
    valid, log = brep.IsValidWithLog
    if not (valid and brep.IsValid):
        raise ExportError(f"rhino3dm finds a side's Brep invalid: {log.strip()}")
    attach_render_mesh(brep, render_mesh(folded, net, hole_radius, place))
    for key, value in (strings or {}).items():
        brep.SetUserString(key, value)
    return brep


def placement_of(
    design: Design,
    folded: FoldedSheet,
    placement: Placement = Placement.REST,
    body: Body | None = None,
) -> tuple[Place, Any]:
    """The rigid map of fold-frame points for ``placement`` and the resting
    placement it applies (None in the fold frame).

    Raises:
        InvalidParameterError: a placement not in :data:`PLACEMENTS`.
    """
    if placement not in PLACEMENTS:
        allowed = ", ".join(PLACEMENTS)
        raise InvalidParameterError("placement", f"must be one of {allowed}, not {placement!r}")
    rest = resting_placement(design, folded, body) if placement == "rest" else None

    def place(p: Array) -> Array:
        return np.asarray(p, dtype=float) if rest is None else rest.apply(p)

    return place, rest


def fold_sides(
    design: Design,
    folded: FoldedSheet,
    *,
    placement: Placement = Placement.REST,
    body: Body | None = None,
    pattern: FlatPattern | None = None,
    compensation: Compensation | str = Compensation.SHARP,
) -> FoldSides:
    """The side Breps of ``design`` (see :func:`side_breps`) with their nets,
    fit and common user strings: the design's parameters, the report's key
    numbers (:mod:`.rhino_strings`; ``pattern`` and ``compensation`` as the
    report takes them) and ``rhino.placement`` / ``rhino.fit_deviation`` /
    ``rhino.fit_tolerance``.

    Raises:
        FabricationError: the relief hole does not fit the sheet.
        ExportError: a face cannot reach the tolerance.
        InvalidParameterError: a placement not in :data:`PLACEMENTS`.
    """
    problem = relief_hole_problem(design, folded)
    if problem is not None:
        raise problem
    place, _ = placement_of(design, folded, placement, body)
    tol = TOLERANCE * folded.sheet.size
    hole = relief_hole_diameter(design, folded) / 2.0
    nets = side_nets(face_nets(folded, hole, tol))
    deviation = max(n.deviation for n in nets)
    strings = design_strings(design)
    strings.update(
        report_strings(design, folded, pattern=pattern, compensation=compensation, body=body)
    )
    strings.update(
        {
            "rhino.placement": placement,
            "rhino.fit_deviation": f"{deviation:.6g}",
            "rhino.fit_tolerance": f"{tol:.6g}",
        }
    )
    breps = []
    for net in nets:
        own = {
            "side": SIDE_NAMES[net.side],
            "sectors": str(len(net.sectors)),
            "fit_deviation": f"{net.deviation:.6g}",
        }
        breps.append((SIDE_NAMES[net.side], side_brep(folded, net, hole, place, strings | own)))
    return FoldSides(tuple(breps), tuple(nets), deviation, tol, strings)


def side_breps(
    design: Design,
    folded: FoldedSheet,
    placement: Placement = Placement.REST,
    body: Body | None = None,
) -> list[tuple[str, Any]]:
    """The folded form's Breps: ``[("upper", Brep), ("lower", Brep)]``, the
    +y and -y side, each one NURBS face on the exact cone (its natural
    boundary the part's edge, C0 at the sheet's corners) with a render mesh
    and user strings (the design's parameters, the report's key numbers,
    ``side``, ``sectors``, ``fit_deviation``: :meth:`Brep.GetUserStrings`).

    Args:
        design: the design.
        folded: ``fold_design(design)``.
        placement: 'rest' (standing on the ground z = 0, as the STEP's) or
            'frame' (the fold frame).
        body: the body whose resting placement stands the form ('solid',
            'shell'; None for the default).

    Raises:
        FabricationError: the relief hole does not fit the sheet.
        ExportError: a face cannot reach the tolerance.
        InvalidParameterError: a placement not in :data:`PLACEMENTS`.
    """
    return list(fold_sides(design, folded, placement=placement, body=body).breps)
