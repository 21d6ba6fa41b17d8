"""A point load (a person) on the sheet, placed on the flat sheet.

EN 1991-1-1 Table 6.10, roofs of category H (not accessible but for
maintenance): ``Q_k = 1.0 kN`` (recommended), on a small area, taken here as
a point: shared among the corners of the triangle of the flat mesh that
holds the point, by its barycentric coordinates (the resultant passes
through the point).
"""

from __future__ import annotations

import numpy as np

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.numeric import Array

__all__ = ["barycentric", "grid_points", "point_load"]


def barycentric(flat: Array, triangles: Array, point: Array) -> tuple[int, Array] | None:
    """The triangle of the flat mesh ``flat`` ``(n, 2)`` holding ``point``
    ``(2,)`` and its barycentric coordinates, or None when no triangle does."""
    p = flat[triangles]
    a, b, c = p[:, 0], p[:, 1], p[:, 2]
    v0, v1, v2 = b - a, c - a, np.asarray(point, dtype=float) - a
    den = v0[:, 0] * v1[:, 1] - v0[:, 1] * v1[:, 0]
    u = (v2[:, 0] * v1[:, 1] - v2[:, 1] * v1[:, 0]) / den
    v = (v0[:, 0] * v2[:, 1] - v0[:, 1] * v2[:, 0]) / den
    tol = 1e-9
    inside = (u >= -tol) & (v >= -tol) & (u + v <= 1 + tol)
    if not inside.any():
        return None
    k = int(np.flatnonzero(inside)[0])
    return k, np.array([1.0 - u[k] - v[k], u[k], v[k]])


def point_load(
    flat: Array, triangles: Array, point: Array, force_N: float, name: str = "person_at"
) -> Array:
    """``(n, 3)`` nodal forces (N): ``force_N`` downwards at ``point`` of the
    flat sheet (same unit as ``flat``).

    Raises:
        InvalidParameterError: the point is not on the sheet (``name``).
    """
    found = barycentric(flat, triangles, point)
    if found is None:
        lo, hi = flat.min(axis=0), flat.max(axis=0)
        raise InvalidParameterError(
            name,
            f"must lie on the flat sheet (x {lo[0]:.6g} to {hi[0]:.6g}, y {lo[1]:.6g} to "
            f"{hi[1]:.6g}, not in the relief hole), got ({point[0]:.6g}, {point[1]:.6g})",
        )
    k, w = found
    out = np.zeros((len(flat), 3))
    out[triangles[k], 2] = -force_N * w
    return out


def grid_points(flat: Array, triangles: Array, n: int) -> Array:
    """``(k, 2)`` the points of an ``n`` x ``n`` grid over the flat sheet's
    bounding box (cell centres) that lie on the sheet."""
    lo, hi = flat.min(axis=0), flat.max(axis=0)
    t = (np.arange(n) + 0.5) / n
    pts = [
        np.array([lo[0] + a * (hi[0] - lo[0]), lo[1] + b * (hi[1] - lo[1])]) for a in t for b in t
    ]
    return np.array([p for p in pts if barycentric(flat, triangles, p) is not None]).reshape(-1, 2)
