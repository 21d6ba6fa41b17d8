"""Area and volume of B-rep shapes, to the precision the exports are checked to."""

from __future__ import annotations

import build123d as bd
from OCP.BRepGProp import BRepGProp
from OCP.GeomAbs import GeomAbs_C2
from OCP.GProp import GProp_GProps
from OCP.ShapeUpgrade import ShapeUpgrade_ShapeDivideArea, ShapeUpgrade_ShapeDivideContinuity
from OCP.TopoDS import TopoDS_Shape

__all__ = ["measure"]

#: Faces are cut into about this many pieces of equal area before integrating.
AREA_PIECES = 200


def _smooth_pieces(shape: TopoDS_Shape) -> TopoDS_Shape:
    """``shape`` with its faces split at every knot where they are less than C2."""
    split = ShapeUpgrade_ShapeDivideContinuity(shape)
    split.SetBoundaryCriterion(GeomAbs_C2)
    split.SetPCurveCriterion(GeomAbs_C2)
    split.SetSurfaceCriterion(GeomAbs_C2)
    split.Perform()
    return split.Result()


def measure(shape: bd.Shape, what: str = "area") -> float:
    """Area (length^2) or volume (length^3) of ``shape`` by OCC's adaptive integration.

    build123d's ``area``/``volume`` use a fixed-order Gauss rule that is off by
    up to 2e-3 (relative) on some rational cone patches. OCC's adaptive rule
    does better, but on its own it stalls on long, thin cone faces (5e-5 low
    with beta = 85 deg) and across a surface's C1 knots (3e-3 low on one
    face). So the faces are first split where they are less than C2, and for
    the area also into about :data:`AREA_PIECES` pieces of equal area
    (ShapeUpgrade: exact splits, the geometry is unchanged), then integrated
    to 1e-9: the area agrees with the flat sheet's to about 1e-10 then.
    """
    pieces = _smooth_pieces(shape.wrapped)
    props = GProp_GProps()
    if what == "area":
        BRepGProp.SurfaceProperties_s(pieces, props, 1e-6)
        divide = ShapeUpgrade_ShapeDivideArea(pieces)
        divide.MaxArea = props.Mass() / AREA_PIECES
        divide.Perform()
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(divide.Result(), props, 1e-9)
    else:
        BRepGProp.VolumeProperties_s(pieces, props, 1e-9)
    return float(props.Mass())
