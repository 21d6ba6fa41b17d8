"""The thick sheet's offsets about the exact cone: the numbers a solid needs.

A flat point at polar angle theta about H, distance r from it, offset s along
the top normal, sits at ``F(theta, r, s) = A + r u(theta) + s n(theta)`` with
``u`` the ruling direction and ``n`` the top normal of the exact cone (constant
along a ruling). The offset faces are regular only while ``r > s k(theta)``,
``k / r`` being the cone's normal curvature across the rulings, and the
crease's mitre needs the sheet continued ``mitre_depth`` past the crease clear
of the apex: both set the smallest relief hole of a solid
(:func:`min_hole_diameter`). Numpy only; the B-rep is built in
:mod:`onefold_cad.export.solid`.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, SheetSurface

__all__ = [
    "SideMap",
    "mitre_depth",
    "min_hole_diameter",
    "min_relief_hole",
    "sheet_offsets",
    "slab_volume",
]

Array = NDArray[np.float64]

_S_RANGE = {
    SheetSurface.INSIDE: (-1.0, 0.0),
    SheetSurface.OUTSIDE: (0.0, 1.0),
    SheetSurface.MID: (-0.5, 0.5),
}


class SideMap:
    """One side's map F(theta, r, s), lengths in the design unit.

    Built in the +y side's coordinates. For the -y side (``lower=True``) the
    sheet is read mirrored (flat angle theta stands for -theta) and the solid
    built from this map is mirrored in the xz-plane afterwards: the -y side's
    cone is the +y side's mirror image.

    theta is the flat polar angle about H (radians), from the +x crease half
    (0) to the -x one (pi); r the distance from the apex; s the distance along
    the top normal.
    """

    def __init__(self, folded: FoldedSheet, *, lower: bool = False) -> None:
        cone = folded.solution.surface
        if not isinstance(cone, ExactCone):
            raise InvalidParameterError(
                "model", "must be 'exact' for the thick sheet's offsets, got 'paper'"
            )
        self.cone = cone
        self.apex = folded.apex
        self.sheet = folded.sheet
        self.total = cone.total_angle
        self.lower = lower
        #: flat polar angles of the sheet's vertices, seen from this side
        self.vertex_angles = np.mod(
            -self.sheet.polar_angles if lower else self.sheet.polar_angles, 2.0 * math.pi
        )

    def frames(self, theta: Array) -> tuple[Array, Array, Array]:
        """Ruling direction u, in-surface direction e (of increasing theta) and
        top normal n ``(k, 3)`` at flat angles ``theta`` in [0, pi] (radians)."""
        u, e = self.cone.frames(np.atleast_1d(np.asarray(theta, dtype=float)))
        return u, e, np.cross(u, e)

    def crease_frame(self, end: int) -> tuple[Array, Array, Array]:
        """u, e, n ``(3,)`` on crease half ``end`` (0: theta = 0, 1: theta = pi)."""
        u, e, n = self.frames(np.array([0.0 if end == 0 else self.total]))
        return u[0], e[0], n[0]

    def points(self, theta: Array, r: Array, s: float) -> Array:
        """F(theta, r, s) ``(k, 3)``."""
        u, _, n = self.frames(theta)
        return self.apex + np.asarray(r, dtype=float)[:, None] * u + s * n

    def edge_radius(self, theta: Array) -> Array:
        """Distance from H to the sheet's edge along the flat angle ``theta``
        (measured from +x towards this side)."""
        return self.sheet.ray_lengths(-theta if self.lower else theta)

    def curvature(self, theta: Array) -> Array:
        """k(theta) = -(dn/dtheta) . e: the cone's normal curvature across the
        ruling at distance r from A is k / r (dimensionless k)."""
        h = 1e-6
        _, e, _ = self.frames(theta)
        dn = (self.frames(theta + h)[2] - self.frames(theta - h)[2]) / (2.0 * h)
        return -np.einsum("ij,ij->i", dn, e)


def mitre_depth(side: SideMap, s_range: tuple[float, float]) -> float:
    """How far past each crease half (length, in its tangent plane) the sheet
    must continue for the cut at y = 0 to leave the whole mitre, with a margin
    of 5% of the thickness."""
    margin = 0.05 * abs(s_range[1] - s_range[0])
    depth = 0.0
    for end in (0, 1):
        _, e, n = side.crease_frame(end)
        into = e[1] if end == 0 else -e[1]  # y of the direction into this side's sheet
        if into <= 1e-9:
            raise InvalidParameterError(
                "alpha", "the fold is flat or folded through: the crease has no mitre"
            )
        depth = max(depth, max(s * n[1] for s in s_range) / into)
    return depth + margin


def min_hole_diameter(side: SideMap, s_range: tuple[float, float]) -> float:
    """The smallest relief hole (diameter, length) for a thick sheet with faces
    at the distances ``s_range`` from the reference surface: the offset faces
    stay regular (r > s k) and the crease's mitre stays clear of the apex."""
    k = side.curvature(np.linspace(1e-5, side.total - 1e-5, 721))
    worst = max(float(np.max(s * k)) for s in s_range)
    return 2.0 * max(worst, mitre_depth(side, s_range))


def sheet_offsets(material: Material) -> tuple[float, float]:
    """The sheet's two faces as signed distances from the reference surface
    along its top normal (length): INSIDE (-t, 0), OUTSIDE (0, t), MID (-t/2, t/2)."""
    lo, hi = _S_RANGE[material.sheet_surface]
    return lo * material.thickness, hi * material.thickness


def min_relief_hole(folded: FoldedSheet, material: Material) -> float:
    """The smallest relief hole diameter (length) for a solid of the material's
    thickness on this fold: :func:`min_hole_diameter` over both sides."""
    s_range = sheet_offsets(material)
    return max(min_hole_diameter(SideMap(folded, lower=lower), s_range) for lower in (False, True))


def slab_volume(
    folded: FoldedSheet, material: Material, hole_diameter: float, *, samples: int = 1200
) -> float:
    """The volume of the thick sheet that :mod:`onefold_cad.export.solid` builds
    (length^3), integrated numerically from the geometry, independently of the
    B-rep: a check on the CAD kernel's result.

    Per side (in the +y side's coordinates; the -y side is its mirror image),
    the slab between the offsets :func:`sheet_offsets` of the cone, from the
    relief hole to the sheet's edge, where it lies on its own side of the
    fold's plane of symmetry (y > 0), with the Jacobian ``r - s k(theta)`` of
    the map F; plus the kept part of the flat blocks that continue it past
    each crease half (the convex side of the mitre), each on its own side of
    the plane through the apex that bisects the two crease halves. Midpoint rules with
    ``samples`` angles, ``samples / 10`` radii and 24 offsets: relative error
    about 1e-4 (the edge of the mitre cuts through the cells).
    """
    s0, s1 = sheet_offsets(material)
    h = 0.5 * hole_diameter
    n_s = 24
    s = s0 + (np.arange(n_s) + 0.5) * (s1 - s0) / n_s
    ds = (s1 - s0) / n_s
    n_r = max(samples // 10, 20)
    rho = (np.arange(n_r) + 0.5) / n_r
    total = 0.0
    for lower in (False, True):
        side = SideMap(folded, lower=lower)
        dth = side.total / samples
        theta = (np.arange(samples) + 0.5) * dth
        u, _, n = side.frames(theta)
        k = side.curvature(theta)
        r_out = side.edge_radius(theta)
        r = h + rho[None, :] * (r_out - h)[:, None]  # (theta, r)
        dr = (r_out - h) / n_r
        y = side.apex[1] + r[:, :, None] * u[:, None, None, 1] + s * n[:, None, None, 1]
        jac = r[:, :, None] - s[None, None, :] * k[:, None, None]
        cell = (dth * dr)[:, None, None] * ds
        total += float(np.sum(np.where(y > 0.0, jac, 0.0) * cell))
        depth = mitre_depth(side, (s0, s1))
        u0, u1 = side.crease_frame(0)[0], side.crease_frame(1)[0]
        m = (u0 - u1) / np.linalg.norm(u0 - u1)
        for end, sign in ((0, 1.0), (1, -1.0)):
            uu, e, nn = side.crease_frame(end)
            into = e[1] if end == 0 else -e[1]
            away = -e if end == 0 else e
            length = float(side.edge_radius(np.array([0.0 if end == 0 else side.total]))[0])
            # kept past the crease: 0 <= d < min(depth, s n_y / into), x from the hole to the end
            d_max = np.clip(s * nn[1] / into, 0.0, depth)
            n_d = 200
            frac = (np.arange(n_d) + 0.5) / n_d
            d = d_max[:, None] * frac[None, :]
            x_in = np.sqrt(np.maximum(h * h - d * d, 0.0))
            # and on its own side of the plane bisecting the crease halves
            x_cut = -(d * (away @ m) + s[:, None] * (nn @ m)) / (uu @ m)
            x_from = np.maximum(x_in, x_cut) if sign * (uu @ m) > 0 else x_in
            kept = np.clip(length - x_from, 0.0, None)
            total += float(np.sum(kept * (d_max[:, None] / n_d)) * ds)
    return total
