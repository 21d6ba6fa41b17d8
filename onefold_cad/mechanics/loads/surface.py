"""Loads spread over a shell's faces, lumped to its nodes.

A face's load is shared equally by its three corners (the resultant of a
uniform load on a triangle passes through its centroid, so a load uniform
over the whole sheet keeps its resultant exactly). Units: m, N, Pa.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array

__all__ = ["face_vectors", "lump", "pressure_load", "projected_load"]


def face_vectors(x: Array, triangles: Array) -> tuple[Array, Array]:
    """``(m,)`` the faces' areas (m^2) and ``(m, 3)`` their unit normals on the
    sheet's upper side: the faces' own orientation turned, for the whole
    sheet at once, so that its area-weighted mean normal points up (+z)."""
    p = x[triangles]
    c = 0.5 * np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    area = np.linalg.norm(c, axis=1)
    normal = c / np.where(area > 0.0, area, 1.0)[:, None]
    if c[:, 2].sum() < 0.0:
        normal = -normal
    return area, normal


def lump(face_forces: Array, triangles: Array, n_nodes: int) -> Array:
    """``(n, 3)`` the nodal forces (N) of the faces' forces ``(m, 3)`` (N),
    a third to each corner."""
    out = np.zeros((n_nodes, 3))
    for k in range(3):
        np.add.at(out, triangles[:, k], face_forces / 3.0)
    return out


def pressure_load(x: Array, triangles: Array, pressure: Array) -> Array:
    """``(n, 3)`` the nodal forces (N) of a pressure ``(m,)`` (Pa) normal to
    each face, positive pushing on the upper side (down into the sheet)."""
    area, normal = face_vectors(x, triangles)
    return lump(-(np.asarray(pressure, dtype=float) * area)[:, None] * normal, triangles, len(x))


def projected_load(x: Array, triangles: Array, load: Array) -> Array:
    """``(n, 3)`` the nodal forces (N) of a vertical load ``(m,)`` (Pa, downwards)
    on each face's horizontal projection (snow: per m^2 of plan)."""
    area, normal = face_vectors(x, triangles)
    plan = area * np.abs(normal[:, 2])
    f = np.zeros((len(triangles), 3))
    f[:, 2] = -np.asarray(load, dtype=float) * plan
    return lump(f, triangles, len(x))
