"""A flat-sheet mesh graded toward H for the CalculiX forming benchmark
(``calculix_forming.py --growth G``): onefold's own mesher
(``onefold_cad.mechanics.mesh.mesh_sheet``, Triangle) with the edge length
``clip(G r, G r_hole, h)`` at distance r from H, the crease halves (the x
axis from the relief hole to the outline) kept as edges, so that a cone's
curvature k / r times the element's length stays about k G everywhere instead
of growing toward H as on a uniform mesh."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]


def axis_crossings(polygon: Array) -> tuple[float, float]:
    """The outline's crossings of the x axis: ``(largest x, smallest x)``."""
    p = np.asarray(polygon, dtype=float)
    q = np.roll(p, -1, axis=0)
    xs = []
    for a, b in zip(p, q, strict=True):
        if (a[1] <= 0 <= b[1] or b[1] <= 0 <= a[1]) and a[1] != b[1]:
            xs.append(a[0] + (b[0] - a[0]) * (0 - a[1]) / (b[1] - a[1]))
        elif a[1] == 0:
            xs.append(a[0])
    return max(xs), min(xs)


def graded_sheet(
    polygon: Array, hole_diameter: float, h: float, growth: float
) -> tuple[Array, NDArray[np.int64], dict[str, Any]]:
    """``(points (n, 2), triangles (m, 3), info)`` like
    ``kratos_shell.mesh_sheet`` (the polygon's unit): ``info['vertices']``
    the nodes at the polygon's vertices, ``info['crease_ends']`` the nodes
    where the crease meets the outline (+x, -x)."""
    from onefold_cad.mechanics.mesh import mesh_sheet

    poly = np.asarray(polygon, dtype=float)
    r = 0.5 * hole_diameter
    xp, xm = axis_crossings(poly)
    mesh = mesh_sheet(
        poly,
        size=(growth * r, growth, h),
        hole_radius=r,
        creases=[((r, 0.0), (xp, 0.0)), ((-r, 0.0), (xm, 0.0))],
    )
    pts = mesh.nodes
    near = lambda p: int(np.argmin(np.hypot(*(pts - p).T)))  # noqa: E731
    info = {
        "vertices": [near(v) for v in poly],
        "crease_ends": [near((xp, 0.0)), near((xm, 0.0))],
    }
    return pts, mesh.triangles, info
