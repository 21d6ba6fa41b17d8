"""The paper model's B-rep faces (OCP): the paper's planar triangles, one per
flat sector between consecutive rulings of a side; with a relief hole the
hole's boundary in each triangle is an exact circular arc about A. One shell
with shared topology, for the build123d adapter in :mod:`.part`.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
)
from OCP.BRepLib import BRepLib
from OCP.GC import GC_MakeArcOfCircle
from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pln
from OCP.TopoDS import (
    TopoDS,
    TopoDS_Edge,
    TopoDS_Shell,
    TopoDS_Vertex,
    TopoDS_Wire,
)

from onefold_cad.errors import ExportError
from onefold_cad.export.brep.cone_patch import pnt, ruling_sectors
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = ["PRECISION", "fan_shell"]


#: OCC's precision (Precision::Confusion): points closer are one point.
PRECISION = 1e-7


#: Ruling ends closer than 3 x NEAR (length) are one ruling (OCC cannot make
#: an edge much shorter than 10 x its precision).
NEAR = 1e-6


def _distinct(points: Array, gap: float) -> NDArray[np.bool_]:
    """Which of the rulings to keep so that no two kept neighbours' points
    ``(n, 3)`` lie within ``gap`` (the first and last, on the crease, always
    kept): a ruling closer than that to the last one kept is left out, and
    the two triangles beside it become one."""
    keep = np.zeros(len(points), dtype=bool)
    keep[0] = True
    last = 0
    for k in range(1, len(points) - 1):
        if np.linalg.norm(points[k] - points[last]) > gap:
            keep[k], last = True, k
    if len(points) > 2 and np.linalg.norm(points[-1] - points[last]) <= gap and last > 0:
        keep[last] = False
    keep[-1] = True
    return keep


def fan_shell(
    folded: FoldedSheet, hole_radius: float, check: Callable[[], None] | None = None
) -> TopoDS_Shell:
    """The paper model's planar triangles (with an exact arc of the relief
    hole) as one shell, built with shared topology: one vertex per ruling end
    (and one apex), one edge per ruling shared by the triangles on either
    side of it (the two crease rulings by both sides), so no sewing is
    needed and the work grows linearly with the number of triangles. Face
    normals are the top side's. ``check`` is called every 256 triangles (a
    time budget that raises)."""
    b = BRep_Builder()
    apex = folded.apex
    tol = 1e-7

    def vertex(p: Array, tolerance: float = tol) -> TopoDS_Vertex:
        v = TopoDS_Vertex()
        b.MakeVertex(v, pnt(p), tolerance)
        return v

    def line(v0: TopoDS_Vertex, v1: TopoDS_Vertex) -> TopoDS_Edge:
        return BRepBuilderAPI_MakeEdge(v0, v1).Edge()

    sides = []
    for side, angles in enumerate(folded.ruling_angles):
        thetas = ruling_sectors(angles)
        sgn = 1.0 if side == 0 else -1.0
        dirs = np.stack([np.cos(thetas), sgn * np.sin(thetas)], axis=-1)
        rho = folded.sheet.ray_lengths(sgn * thetas)
        outer = folded.map_points(dirs * rho[:, None])
        unit = folded.map_points(dirs) - apex
        keep = _distinct(outer, 3.0 * NEAR)
        if hole_radius > 0.0:  # and the hole's points (arcs need a few x OCC's precision)
            keep &= _distinct(apex + hole_radius * unit, 4.0 * PRECISION)
        sides.append((outer[keep], unit[keep]))
    # the crease rulings (first and last of each side) are shared by both sides
    apex_v = vertex(apex) if hole_radius <= 0.0 else None
    crease_ends = [vertex(sides[0][0][i]) for i in (0, -1)]
    crease_inner = [
        apex_v if apex_v is not None else vertex(apex + hole_radius * sides[0][1][i])
        for i in (0, -1)
    ]
    crease_rulings = [line(crease_inner[i], crease_ends[i]) for i in (0, 1)]
    shell = TopoDS_Shell()
    b.MakeShell(shell)
    for side, (outer, unit) in enumerate(sides):
        n = len(outer)
        ends = [crease_ends[0]] + [vertex(p) for p in outer[1:-1]] + [crease_ends[1]]
        if apex_v is not None:
            inner = [apex_v] * n
        else:
            inner = (
                [crease_inner[0]]
                + [vertex(apex + hole_radius * u) for u in unit[1:-1]]
                + [crease_inner[1]]
            )
        rulings = (
            [crease_rulings[0]]
            + [line(inner[k], ends[k]) for k in range(1, n - 1)]
            + [crease_rulings[1]]
        )
        for k in range(n - 1):
            if check is not None and k % 256 == 255:
                check()
            p, q = outer[k], outer[k + 1]
            arc_edge = apex_v is None
            origin = apex
            # (p - A) x (q - p), not (p - A) x (q - A): the same normal, but a
            # thin triangle's two long sides cancel in the latter, leaving its
            # far vertex off the plane by |q| eps / (its angle at A) (2.5e-6 on
            # a sheet of 1.3e7 with 1e-3 rad triangles, 25 x the kernel's
            # precision); the short side is nearly square to the ruling
            normal = np.cross(p - origin, q - p)
            if side == 1:
                normal = -normal
            edges = [rulings[k], line(ends[k], ends[k + 1]), rulings[k + 1].Reversed()]
            if arc_edge:
                hp, hq = apex + hole_radius * unit[k], apex + hole_radius * unit[k + 1]
                axis = np.cross(p - apex, q - apex)
                circle = gp_Circ(gp_Ax2(pnt(apex), gp_Dir(*axis), gp_Dir(*unit[k])), hole_radius)
                arc = GC_MakeArcOfCircle(circle, pnt(hp), pnt(hq), True).Value()
                edges.append(BRepBuilderAPI_MakeEdge(arc, inner[k], inner[k + 1]).Edge().Reversed())
            if side == 1:  # the mirror image: the same loop, the other way round
                edges = [e.Reversed() for e in reversed(edges)]
            wire = TopoDS_Wire()
            b.MakeWire(wire)
            for e in edges:
                b.Add(wire, e)
            plane = gp_Pln(pnt(origin), gp_Dir(*normal))
            mk = BRepBuilderAPI_MakeFace(plane, wire, True)
            if not mk.IsDone():
                raise ExportError("could not make a planar fan face")
            face = mk.Face()
            for e in edges:
                BRepLib.BuildPCurveForEdgeOnPlane_s(TopoDS.Edge(e), face)
            b.Add(shell, face)
    shell.Closed(False)
    return shell
