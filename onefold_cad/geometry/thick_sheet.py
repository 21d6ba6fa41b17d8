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
from onefold_cad.geometry.frame import arc_points, arc_tangents
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
        self.frame = cone.frame
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
        phi = self.cone.phi_of_theta(np.atleast_1d(np.asarray(theta, dtype=float)))
        v = arc_points(self.frame, phi) - self.apex
        dp = arc_tangents(self.frame, phi)
        u = v / np.linalg.norm(v, axis=1, keepdims=True)
        e = dp - np.einsum("ij,ij->i", dp, u)[:, None] * u
        e /= np.linalg.norm(e, axis=1, keepdims=True)
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


def slab_volume(folded: FoldedSheet, material: Material, hole_diameter: float) -> float:
    """The volume of the thick sheet (length^3): both sides' slabs between the
    offsets :func:`sheet_offsets` of the cone, from the relief hole to the
    sheet's edge, plus the crease's mitre.

    The map F(theta, r, s) has Jacobian ``r - s k(theta)``, so a side's slab
    holds ``A t - (s1^2 - s0^2) / 2 * integral k(theta) (R(theta) - h) dtheta``;
    at each crease half the mitre adds ``tan(psi / 2) (s_convex^2 -
    s_concave^2)`` per unit length, psi the fold angle, to first order in t
    (the sheet's curvature next to the crease and the ends of the mitre are
    left out: they change the volume by O(t^3)).
    """
    s0, s1 = sheet_offsets(material)
    h = 0.5 * hole_diameter
    total = 0.0
    for lower in (False, True):
        side = SideMap(folded, lower=lower)
        theta = np.linspace(0.0, side.total, 4001)
        r_out = side.edge_radius(theta)
        k = side.curvature(np.clip(theta, 1e-6, side.total - 1e-6))
        flat = 0.5 * (r_out**2 - h * h) * (s1 - s0)
        bend = 0.5 * (s1 * s1 - s0 * s0) * k * (r_out - h)
        total += float(np.trapezoid(flat - bend, theta))
        for end in (0, 1):
            _, e, n = side.crease_frame(end)
            into = e[1] if end == 0 else -e[1]
            slope = abs(n[1]) / into  # tan(psi / 2)
            convex = max(s0 * np.sign(n[1]), s1 * np.sign(n[1]), 0.0)
            concave = max(-s0 * np.sign(n[1]), -s1 * np.sign(n[1]), 0.0)
            length = float(side.edge_radius(np.array([0.0 if end == 0 else side.total]))[0]) - h
            total += 0.5 * slope * (convex**2 - concave**2) * length
    return total
