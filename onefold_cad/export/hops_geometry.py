"""The rhino3dm objects the Grasshopper Hops server answers with, and the
sheet it reads from a Hops curve (a rhino3dm adapter for :mod:`onefold_cad.hops`).

Nothing is derived here: the folded form's Breps are the .3dm writer's
(:func:`.rhino_sides.side_breps`, one per side, fitted to the same
tolerance), the creases and the apex are the fold's, the outline, relief
hole and bend lines the flat pattern's
(:mod:`onefold_cad.fabrication.flat_pattern`). Points are placed by the
.3dm's rigid map (:func:`.rhino_sides.placement_of`): standing as the form
rests or in the fold frame; the flat pattern lies in its own frame (the
sheet's, z = 0), as the DXF draws it.

Points and lines go out as the JSON structs RhinoCommon reads
(``{"X": .., "Y": .., "Z": ..}``, ``{"From": .., "To": ..}``): rhino3dm's
``Line`` has no ``Encode``. Lengths are in the design's unit.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import rhino3dm

from onefold_cad.errors import InvalidSheetError
from onefold_cad.export.rhino_faces import Place
from onefold_cad.fabrication.flat_pattern import FlatPattern, FoldHalf, FoldRuling
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = [
    "FlatCurves",
    "crease_lines",
    "decode",
    "flat_curves",
    "point",
    "sheet_polygon",
]


def point(p: Array) -> dict[str, float]:
    """A point ``(3,)`` as RhinoCommon's Point3d JSON."""
    x, y, z = (float(c) for c in p)
    return {"X": x, "Y": y, "Z": z}


def crease_lines(folded: FoldedSheet, place: Place) -> list[dict[str, Any]]:
    """The crease halves (plus_x, minus_x) as lines from the apex to the
    sheet's edge, placed, as RhinoCommon's Line JSON."""
    apex = place(folded.apex[None, :])[0]
    return [
        {"From": point(apex), "To": point(place(half.end_3d[None, :])[0])} for half in folded.crease
    ]


def _p3(p: Array) -> Any:
    x, y = (float(c) for c in p)
    return rhino3dm.Point3d(x, y, 0.0)


@dataclass(frozen=True)
class FlatCurves:
    """The flat pattern's curves on z = 0 (sheet frame).

    Attributes:
        outline: the cut outline, a closed PolylineCurve.
        relief_hole: the relief hole's cutting circle (a NurbsCurve), or None.
        bend_lines: LineCurves: the fold halves (plus_x, minus_x), then the
            paper model's ruling folds.
        bends: 'UP' or 'DOWN' for each bend line.
        bend_angles_deg: the fold angle of each bend line (deg).
    """

    outline: Any
    relief_hole: Any | None
    bend_lines: list[Any]
    bends: list[str]
    bend_angles_deg: list[float]


def flat_curves(pattern: FlatPattern) -> FlatCurves:
    """The cut outline, relief hole and bend lines of ``pattern``."""
    outline = [_p3(p) for p in pattern.cut_outline]
    hole = None
    if pattern.cut_hole_diameter > 0.0:
        circle = rhino3dm.Circle(_p3(pattern.apex), pattern.cut_hole_diameter / 2.0)
        hole = circle.ToNurbsCurve()
    bends: list[FoldHalf | FoldRuling] = [*pattern.halves, *pattern.fold_rulings]
    return FlatCurves(
        rhino3dm.PolylineCurve([*outline, outline[0]]),
        hole,
        [rhino3dm.LineCurve(_p3(b.start), _p3(b.end)) for b in bends],
        [b.bend for b in bends],
        [float(b.angle_deg) for b in bends],
    )


def decode(data: dict[str, Any]) -> Any:
    """The rhino3dm object of a Hops value's geometry (``CommonObject`` JSON:
    ``version``, ``archive3dm``, ``opennurbs``, ``data``), or None."""
    return rhino3dm.CommonObject.Decode(data)


def sheet_polygon(curve: Any, name: str = "sheet") -> list[tuple[float, float]]:
    """The vertices ``(x, y)`` of a closed polyline in the fold frame's XY
    plane (the last one, repeating the first, dropped), as ``--polygon``
    takes them.

    Raises:
        InvalidSheetError: named ``name``: not a curve, not a polyline, not
            closed, or off the XY plane (z != 0).
    """
    if not isinstance(curve, rhino3dm.Curve):
        kind = type(curve).__name__
        raise InvalidSheetError(name, f"must be a closed polyline curve, got a {kind}")
    polyline = curve.TryGetPolyline()
    if polyline is None:
        raise InvalidSheetError(
            name, "must be a closed polyline (straight segments only), got a curved curve"
        )
    pts = [polyline[i] for i in range(polyline.Count)]
    if len(pts) < 4 or not polyline.IsClosed:
        raise InvalidSheetError(
            name, f"must be a closed polyline, got an open one of {len(pts)} points"
        )
    for i, p in enumerate(pts):
        if p.Z != 0.0:
            raise InvalidSheetError(
                name, f"must lie in the XY plane (z = 0: the flat sheet), vertex {i} has z = {p.Z}"
            )
    return [(float(p.X), float(p.Y)) for p in pts[:-1]]
