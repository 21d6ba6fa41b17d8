"""The cones' forming sheet: at stations along rulings of each cone, the
radius the design has there and the radius the machine forms it to.

A cone of the exact model bends across its rulings only; at distance r
from its apex along the ruling at flat angle theta its radius of curvature
is ``r / |k(theta)|`` (:meth:`~onefold_cad.geometry.thick.thick_map.SideMap.curvature`).
Formed to the design (``cone_forming`` 'design' or unset), that is also the
radius to form to, and the sheet springs back from it. Formed past its
springback ('compensated'), the radius to form to is the one from which a
plane-strain J2 section of the sheet, released, keeps the design's
(:class:`~onefold_cad.mechanics.j2.springback.SpringbackTable`, the same
table ``onefold simulate`` forms each face to). ``onefold build`` writes the
stations as ``NAME-cones.csv``.

Lengths in the design's unit, angles in degrees, points in the blank's
frame (H at the origin, the crease on the x axis), as the bend sheet's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.design import Design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.thick.thick_map import SideMap
from onefold_cad.mechanics.j2.springback import SpringbackTable
from onefold_cad.mechanics.j2.stages import FORMING_STEPS, j2_section
from onefold_cad.mechanics.model import shell_material

__all__ = ["RULING_STEP_DEG", "STATIONS", "ConeStation", "check_cone_sheet", "cone_stations"]

#: The rulings listed: every this many degrees of flat angle from one crease half to the other.
RULING_STEP_DEG = 10.0
#: Stations along each ruling, evenly from the relief hole's edge to the sheet's.
STATIONS = 9


@dataclass(frozen=True)
class ConeStation:
    """One point of a cone on the forming sheet (design unit, degrees).

    Attributes:
        side: '+y' or '-y', the side of the crease the cone lies on.
        ruling_deg: the ruling's flat angle about H from the +x crease half.
        distance: the station's distance from H along the ruling.
        x, y: the station on the blank (H at the origin).
        cone_radius: the cone's radius of curvature across the ruling there
            (the design's form; inf where the cone is flat).
        form_radius: the radius to form it to (the design's unless the cones
            are formed past their springback).
    """

    side: str
    ruling_deg: float
    distance: float
    x: float
    y: float
    cone_radius: float
    form_radius: float


def cone_stations(design: Design, folded: FoldedSheet) -> list[ConeStation]:
    """The forming sheet's stations: per side, one ruling every
    :data:`RULING_STEP_DEG` deg and :data:`STATIONS` points along each.

    Raises:
        InvalidParameterError: the paper model (its cones are a fan of ruling
            folds, in the bend sheet), or cones formed past their springback
            without the material values the J2 law needs (named).
    """
    table = check_cone_sheet(design)
    metres = design.units.mm / 1000.0
    hole = relief_hole_diameter(design, folded) / 2
    n = int(round(180.0 / RULING_STEP_DEG))
    rows = []
    for lower in (False, True):
        side = SideMap(folded, lower=lower)
        theta = np.linspace(0.0, side.total, n + 1)
        k = np.abs(side.curvature(theta))
        edge = side.edge_radius(theta)
        for t, kk, e in zip(theta, k, edge, strict=True):
            r = np.linspace(hole, e, STATIONS)
            if kk == 0.0:  # flat (past a crease)
                cone_r = form_r = np.full(STATIONS, math.inf)
            else:
                cone_r = r / kk
                form_r = (
                    cone_r
                    if table is None
                    else 1.0 / table.forming(1.0 / (cone_r * metres)) / metres
                )
            y = -1.0 if lower else 1.0
            for ri, dr, fr in zip(r, cone_r, form_r, strict=True):
                rows.append(ConeStation(
                    "-y" if lower else "+y", math.degrees(t), float(ri), float(ri * math.cos(t)),
                    float(y * ri * math.sin(t)), float(dr), float(fr),
                ))  # fmt: skip
    return rows


def check_cone_sheet(design: Design) -> SpringbackTable | None:
    """What :func:`cone_stations` refuses, raised before any file is written;
    the J2 section's springback table of the design's sheet where its cones
    are formed past their springback (None: formed to the design).

    Raises:
        InvalidParameterError: as :func:`cone_stations`.
    """
    if design.model.value != "exact":
        raise InvalidParameterError(
            "model", "must be 'exact' for the cones' forming sheet (the paper model's fan "
            "folds are in the bend sheet), got 'paper'"
        )  # fmt: skip
    if not design.material.cones_compensated:
        return None
    return SpringbackTable.of(*j2_section(shell_material(design)), FORMING_STEPS)
