"""A placed part's triangle mesh for the site's writers and its clearance
check: OCCT's mesher (BRepMesh_IncrementalMesh) with an *absolute* linear
deflection and an angular one, read face by face with each face's location
and orientation.

Every mesh vertex lies on the part's B-rep and every triangle lies within
the linear deflection of it. (An absolute deflection matters: build123d's
``tessellate`` passes a relative one, with which OCCT meshes the solid's
long faces tapering to the crease with overlapping triangles, a quarter too
much area on those faces.) Lengths in the part's unit.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.TopAbs import TopAbs_REVERSED
from OCP.TopLoc import TopLoc_Location

from onefold_cad.errors import ExportError
from onefold_cad.geometry.numeric import Array

__all__ = ["mesh_area", "mesh_shape"]


def mesh_shape(shape: Any, deflection: float, angular: float) -> tuple[Array, Array]:
    """The triangle mesh of ``shape`` (a build123d shape).

    Args:
        shape: the part.
        deflection: the largest distance of a triangle from the B-rep (length).
        angular: the largest turn of a triangle from the surface (rad).

    Returns:
        ``(vertices (k, 3), triangles (m, 3) int)``, each face's triangles
        oriented with the face (outwards on a solid).

    Raises:
        ExportError: OCCT could not mesh a face.
    """
    BRepTools.Clean_s(shape.wrapped)
    BRepMesh_IncrementalMesh(shape.wrapped, float(deflection), False, float(angular), True)
    verts: list[Array] = []
    tris: list[Array] = []
    base = 0
    for face in shape.faces():
        loc = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face.wrapped, loc)
        if tri is None:
            raise ExportError(f"OCCT could not mesh a face of {shape.label or 'the part'}")
        trsf = loc.Transformation()
        pts = np.array([tri.Node(i).Transformed(trsf).Coord() for i in range(1, tri.NbNodes() + 1)])
        idx = np.array([tri.Triangle(i).Get() for i in range(1, tri.NbTriangles() + 1)]) - 1
        if face.wrapped.Orientation() == TopAbs_REVERSED:
            idx = idx[:, [0, 2, 1]]
        verts.append(pts)
        tris.append(idx + base)
        base += len(pts)
    return np.concatenate(verts), np.concatenate(tris).astype(np.int64)


def mesh_area(verts: Array, tris: Array) -> float:
    """The area of a triangle mesh (length^2)."""
    a, b, c = verts[tris[:, 0]], verts[tris[:, 1]], verts[tris[:, 2]]
    return 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
