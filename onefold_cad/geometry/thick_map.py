"""The thick sheet's map about the exact cone, and the smallest relief hole a
solid needs.

A flat point at polar angle theta about H, distance r from it, offset s along
the top normal, sits at ``F(theta, r, s) = A + r u(theta) + s n(theta)`` with
``u`` the ruling direction and ``n`` the top normal of the exact cone (constant
along a ruling). Past each crease half the map continues in the crease
ruling's tangent plane (:class:`SideMap`): the flat mitre block. The solid
of one side is F over r in [hole, edge], s over the thickness, kept where it
lies on its own side of the fold's plane of symmetry y = 0 (the mitre) and,
past crease half k, of a plane that keeps the two crease halves' mitre
blocks apart (:func:`mitre_planes`); the -y side is its mirror image.
:class:`onefold_cad.geometry.slab.Slab` lists that solid's faces as ruled
patches (:mod:`.slab_faces`) and integrates its volume (:mod:`.slab_volume`);
the B-rep is built in :mod:`onefold_cad.export.solid`.

The offset faces are regular only while ``r > s k(theta)``, ``k / r`` being
the cone's normal curvature across the rulings, and the mitre needs the
sheet continued ``mitre_depth`` past the crease clear of the apex: both, and
the mitre blocks' clearance at the crease, set the smallest relief hole of a
solid (:func:`min_hole_diameter`). Numpy only.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.numeric import Array, cross3

__all__ = [
    "MITRE_CLEARANCE",
    "CreaseFrames",
    "SideMap",
    "min_hole_diameter",
    "min_relief_hole",
    "mitre_depth",
    "mitre_planes",
    "mitre_reach",
]


class HasCreaseFrames(Protocol):
    """What the mitre blocks read of a side: its crease frames
    (:meth:`SideMap.crease_frame`; :class:`CreaseFrames` caches them)."""

    def crease_frame(self, end: int) -> tuple[Array, Array, Array]: ...


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
        self._ends = (self._crease_end(0.0), self._crease_end(self.total))

    def _crease_end(self, theta: float) -> tuple[Array, Array, Array]:
        """u, e, n ``(3,)`` on the crease ruling at ``theta`` (0 or the total
        angle), with u exactly in the plane y = 0 where the crease lies."""
        u, e = (np.array(v) for v in self.cone.frame_at(theta))
        u[1] = 0.0
        u /= np.linalg.norm(u)
        e -= (e @ u) * u
        e /= np.linalg.norm(e)
        return u, e, cross3(u, e)

    def frames(self, theta: Array) -> tuple[Array, Array, Array]:
        """Ruling direction u, in-surface direction e (of increasing theta) and
        top normal n ``(k, 3)`` at flat angles ``theta`` (radians).

        In [0, total] they are the cone's; past a crease half (theta < 0, or
        theta > total) the map continues in that crease ruling's tangent plane
        (the flat mitre block, C1 with the cone): u turns about n by the
        angle past the crease, n stays."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        u, e = self.cone.frames(np.clip(t, 0.0, self.total))
        n = np.cross(u, e)
        for end, past in ((0, t), (1, t - self.total)):
            mask = past < 0.0 if end == 0 else past > 0.0
            if np.any(mask):
                cu, ce, cn = self._ends[end]
                d = past[mask][:, None]
                u[mask] = np.cos(d) * cu + np.sin(d) * ce
                e[mask] = np.cos(d) * ce - np.sin(d) * cu
                n[mask] = cn
        return u, e, n

    def crease_frame(self, end: int) -> tuple[Array, Array, Array]:
        """u, e, n ``(3,)`` on crease half ``end`` (0: theta = 0, 1: theta = pi)."""
        return tuple(v.copy() for v in self._ends[end])  # type: ignore[return-value]

    def points(self, theta: Array, r: Array, s: float | Array) -> Array:
        """F(theta, r, s) ``(k, 3)`` (``s`` one offset, or one per angle)."""
        u, _, n = self.frames(theta)
        return self.place(u, n, r, s)

    def place(self, u: Array, n: Array, r: Array, s: float | Array) -> Array:
        """F = A + r u + s n ``(k, 3)`` from the frames ``u``, ``n`` ``(k, 3)``
        of :meth:`frames` at the angles in question (``s`` one offset, or one
        per angle)."""
        s = np.asarray(s, dtype=float)
        rr = np.asarray(r, dtype=float)[:, None]
        return self.apex + rr * u + (s[:, None] if s.ndim else s) * n

    def edge_radius(self, theta: Array) -> Array:
        """Distance from H to the sheet's edge along the flat angle ``theta``
        (measured from +x towards this side)."""
        return self.sheet.ray_lengths(-theta if self.lower else theta)

    def curvature(self, theta: Array) -> Array:
        """k(theta) = -(dn/dtheta) . e: the cone's normal curvature across the
        ruling at distance r from A is k / r (dimensionless k); 0 on the flat
        continuation past the creases."""
        return self.frames_and_curvature(theta)[3]

    def frames_and_curvature(self, theta: Array) -> tuple[Array, Array, Array, Array]:
        """u, e, n ``(k, 3)`` (:meth:`frames`) and k ``(k,)`` (:meth:`curvature`)
        at flat angles ``theta`` (radians), from one evaluation of the frames."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        h = 1e-6
        lo, hi = np.clip(t - h, 0.0, self.total), np.clip(t + h, 0.0, self.total)
        m = len(t)
        u, e, n = self.frames(np.concatenate([t, lo, hi]))
        span = np.where(hi > lo, hi - lo, 1.0)[:, None]
        k = -np.einsum("ij,ij->i", (n[2 * m :] - n[m : 2 * m]) / span, e[:m])
        k[(t < 0.0) | (t > self.total)] = 0.0
        return u[:m], e[:m], n[:m], k


def mitre_depth(side: HasCreaseFrames, s_range: tuple[float, float]) -> float:
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
                "alpha",
                "the fold is flat or folded through: the crease has no mitre for a solid; "
                "write the shell (--body shell)",
            )
        depth = max(depth, max(s * n[1] for s in s_range) / into)
    return depth + margin


def mitre_reach(side: SideMap, s_range: tuple[float, float]) -> tuple[tuple[float, float], ...]:
    """Per crease half (ends 0 and 1): ``(depth, reach)`` (length, in the
    crease ruling's tangent plane): how far past the crease the convex face
    continues to the fold's plane of symmetry (the mitre block), and how far
    into the sheet the concave face lies beyond it (cut off), i.e.
    max over the faces of +-s n_y / e_y; (t / 2) tan(psi / 2) each for MID at
    fold angle psi. 0 where there is none."""
    out = []
    for end in (0, 1):
        _, e, n = side.crease_frame(end)
        into = e[1] if end == 0 else -e[1]
        if into <= 1e-9:
            raise InvalidParameterError(
                "alpha",
                "the fold is flat or folded through: the crease has no mitre for a solid; "
                "write the shell (--body shell)",
            )
        depth = max(0.0, max(s * n[1] for s in s_range) / into)
        reach = max(0.0, max(-s * n[1] for s in s_range) / into)
        out.append((depth, reach))
    return tuple(out)


#: The mitre blocks of the two crease halves keep this fraction of the
#: thickness clear of the plane that bisects the crease halves.
MITRE_CLEARANCE = 0.05


def mitre_planes(side: HasCreaseFrames, thickness: float) -> tuple[tuple[Array, float], ...]:
    """The planes ``w . (p - A) >= c`` that bound the mitre block of each
    crease half (``(w (3,), c)`` for ends 0 and 1, +y side's coordinates).

    On sharp folds the crease halves are only 13-40 deg apart at the apex and
    the blocks that continue the sheet past them would run into each other
    (and through the sheet) next to the relief hole; each is cut by the plane
    through A that bisects the crease halves, moved ``MITRE_CLEARANCE * t``
    towards its own crease half, so the two never touch.
    """
    u0, u1 = side.crease_frame(0)[0], side.crease_frame(1)[0]
    m = (u0 - u1) / np.linalg.norm(u0 - u1)
    c = MITRE_CLEARANCE * thickness
    return (m, c), (-m, c)


def _clearance_hole(side: SideMap, s_range: tuple[float, float]) -> float:
    """The smallest hole radius for which each crease ruling's section (r from
    the hole, s from 0 to the convex face) lies clear of the other crease
    half's mitre plane, with a margin of 5%: the mitre planes then cut only
    the blocks past the creases, never the sheet."""
    need = 0.0
    for end, (w, c) in enumerate(mitre_planes(side, abs(s_range[1] - s_range[0]))):
        u, _, n = side.crease_frame(end)
        a = float(w @ u)
        s_c = max(s_range, key=lambda s: s * n[1])
        if s_c * n[1] <= 0.0:
            continue  # no block past this crease half
        need = max(need, 1.05 * (c - min(0.0, s_c * float(w @ n))) / a)
    return need


def _curvature_on_cone(side: SideMap, theta: Array) -> Array:
    """:meth:`SideMap.curvature` ``(k,)`` at flat angles ``theta`` within the
    cone (0, total), in closed form: the geodesic curvature of u at the arc
    parameters of ``theta`` (:meth:`~onefold_cad.geometry.arc.ArcFrames.frames`;
    one Newton step from the cone's table, the angles from its nodes). The
    finite difference of the normals gives the same to about 1e-10 (its own
    rounding over its step), at a twentieth of the work."""
    cone, arc = side.cone, ArcFrames(side.cone.frame, side.apex)
    phi = cone.phi_near(theta)
    speed = arc.frames(phi, curvature=True)[4]  # d theta / d phi
    phi -= (cone.theta_near(phi) - theta) / speed
    return arc.frames(phi, curvature=True)[3]


def min_hole_diameter(side: SideMap, s_range: tuple[float, float]) -> float:
    """The smallest relief hole (diameter, length) for a thick sheet with faces
    at the distances ``s_range`` from the reference surface: the offset faces
    stay regular (r > s k), the crease's mitre stays clear of the apex, and
    the two crease halves' mitre blocks stay clear of each other at the crease
    (:func:`mitre_planes`)."""
    k = _curvature_on_cone(side, np.linspace(1e-5, side.total - 1e-5, 721))
    worst = max(float(np.max(s * k)) for s in s_range)
    return 2.0 * max(worst, mitre_depth(side, s_range), _clearance_hole(side, s_range))


def min_relief_hole(folded: FoldedSheet, material: Material) -> float:
    """The smallest relief hole diameter (length) for a solid of the material's
    thickness on this fold: :func:`min_hole_diameter`, which is the same for
    both sides (the -y side's map is the +y side's mirror image: its
    curvature and crease frames, all that it reads, are the +y side's)."""
    return min_hole_diameter(SideMap(folded), sheet_offsets(material))


class CreaseFrames:
    """A :class:`SideMap` whose crease frames are computed once (the mitre
    blocks ask often)."""

    def __init__(self, side: SideMap) -> None:
        self.side = side
        self.lower = side.lower
        self.total = side.total
        self._frames = {end: side.crease_frame(end) for end in (0, 1)}

    def crease_frame(self, end: int) -> tuple[Array, Array, Array]:
        return self._frames[end]

    def edge_radius(self, theta: Array) -> Array:
        return self.side.edge_radius(theta)
