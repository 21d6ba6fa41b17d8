"""A planar face's plane with axes that suit OCC's default integration.

Lengths are in the design unit.
"""

from __future__ import annotations

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.gp import gp_Ax3, gp_Dir, gp_Pln, gp_Pnt
from OCP.TopAbs import TopAbs_VERTEX
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Wire

from onefold_cad.errors import ExportError
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.thick.slab import Slab

__all__ = ["aligned_plane"]


def _xyz(p) -> Array:
    return np.array([p.X(), p.Y(), p.Z()])


def aligned_plane(plane: gp_Pln, wire: TopoDS_Wire) -> gp_Pln:
    """``plane`` with its origin at the middle of ``wire``'s vertices and its
    x axis along their longest chord. OCC's default area and volume of a
    planar face integrate x along its edges (Green's theorem): on a sliver
    (a mitre face is t wide and metres long) lying askew in the plane's axes
    that is a small difference of large integrals (72 % off on
    patkau-one-fold's mitre faces); along its length it is not."""
    d = _xyz(plane.Axis().Direction())
    pts = []
    ex = TopExp_Explorer(wire, TopAbs_VERTEX)
    while ex.More():
        pts.append(_xyz(BRep_Tool.Pnt_s(TopoDS.Vertex(ex.Current()))))
        ex.Next()
    p = np.array(pts)
    q = p[:, None, :] - p[None, :, :]
    i, j = np.unravel_index(np.argmax(np.einsum("ijk,ijk->ij", q, q)), q.shape[:2])
    along = q[i, j] - (q[i, j] @ d) * d
    if np.linalg.norm(along) <= 1e-9 * max(1.0, float(np.abs(p).max())):
        return plane
    o = _xyz(plane.Location())
    c = p.mean(axis=0)
    c = c - ((c - o) @ d) * d
    return gp_Pln(
        gp_Ax3(gp_Pnt(*map(float, c)), gp_Dir(*map(float, d)), gp_Dir(*map(float, along)))
    )


def cutting_plane(wire: TopoDS_Wire, slab: Slab, tol: float) -> gp_Pln:
    """The thick sheet's cutting plane (y = 0 or a mitre plane, both sides'
    coordinates) that holds ``wire``'s vertices within ``tol`` (length).

    Raises:
        ExportError: no cutting plane holds them (a gap in the solid's faces).
    """
    pts = []
    ex = TopExp_Explorer(wire, TopAbs_VERTEX)
    while ex.More():
        q = BRep_Tool.Pnt_s(TopoDS.Vertex(ex.Current()))
        pts.append((q.X(), q.Y(), q.Z()))
        ex.Next()
    p = np.array(pts)
    apex = slab.sides[0].apex
    for w, c in slab.planes.values():  # symmetric in y: the -y side's are the same planes
        origin = apex + c * w
        if np.max(np.abs((p - origin) @ w)) <= tol:
            return gp_Pln(gp_Pnt(*map(float, origin)), gp_Dir(*map(float, w)))
    raise ExportError("the thick sheet's faces leave a gap that is not on a cutting plane")
