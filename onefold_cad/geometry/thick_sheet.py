"""The thick sheet about the exact cone: the numbers and the faces a solid needs.

A flat point at polar angle theta about H, distance r from it, offset s along
the top normal, sits at ``F(theta, r, s) = A + r u(theta) + s n(theta)`` with
``u`` the ruling direction and ``n`` the top normal of the exact cone (constant
along a ruling). Past each crease half the map continues in the crease
ruling's tangent plane (:class:`SideMap`): the flat mitre block. The solid
of one side is F over r in [hole, edge], s over the thickness, kept where it
lies on its own side of the fold's plane of symmetry y = 0 (the mitre) and,
past crease half k, of a plane that keeps the two crease halves' mitre
blocks apart (:func:`mitre_planes`); the -y side is its mirror image.
:class:`Slab` lists that solid's faces as ruled patches and integrates its
volume; the B-rep is built in :mod:`onefold_cad.export.solid`.

The offset faces are regular only while ``r > s k(theta)``, ``k / r`` being
the cone's normal curvature across the rulings, and the mitre needs the
sheet continued ``mitre_depth`` past the crease clear of the apex: both, and
the mitre blocks' clearance at the crease, set the smallest relief hole of a
solid (:func:`min_hole_diameter`). Numpy only.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, SheetSurface
from onefold_cad.geometry.validate import sorted_unique

__all__ = [
    "SideMap",
    "Slab",
    "Patch",
    "Boundary",
    "MITRE_CLEARANCE",
    "mitre_depth",
    "mitre_planes",
    "mitre_reach",
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
        self._ends = (self._crease_end(0.0), self._crease_end(self.total))

    def _crease_end(self, theta: float) -> tuple[Array, Array, Array]:
        """u, e, n ``(3,)`` on the crease ruling at ``theta`` (0 or the total
        angle), with u exactly in the plane y = 0 where the crease lies."""
        u, e = (np.array(v) for v in self.cone.frame_at(theta))
        u[1] = 0.0
        u /= np.linalg.norm(u)
        e -= (e @ u) * u
        e /= np.linalg.norm(e)
        return u, e, np.cross(u, e)

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


def mitre_planes(side: SideMap, thickness: float) -> tuple[tuple[Array, float], ...]:
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


def min_hole_diameter(side: SideMap, s_range: tuple[float, float]) -> float:
    """The smallest relief hole (diameter, length) for a thick sheet with faces
    at the distances ``s_range`` from the reference surface: the offset faces
    stay regular (r > s k), the crease's mitre stays clear of the apex, and
    the two crease halves' mitre blocks stay clear of each other at the crease
    (:func:`mitre_planes`)."""
    k = side.curvature(np.linspace(1e-5, side.total - 1e-5, 721))
    worst = max(float(np.max(s * k)) for s in s_range)
    return 2.0 * max(worst, mitre_depth(side, s_range), _clearance_hole(side, s_range))


def sheet_offsets(material: Material) -> tuple[float, float]:
    """The sheet's two faces as signed distances from the reference surface
    along its top normal (length): INSIDE (-t, 0), OUTSIDE (0, t), MID (-t/2, t/2)."""
    lo, hi = _S_RANGE[material.sheet_surface]
    return lo * material.thickness, hi * material.thickness


def min_relief_hole(folded: FoldedSheet, material: Material) -> float:
    """The smallest relief hole diameter (length) for a solid of the material's
    thickness on this fold: :func:`min_hole_diameter`, which is the same for
    both sides (the -y side's map is the +y side's mirror image: its
    curvature and crease frames, all that it reads, are the +y side's)."""
    return min_hole_diameter(SideMap(folded), sheet_offsets(material))


def slab_volume(folded: FoldedSheet, material: Material, hole_diameter: float) -> float:
    """The volume of the thick sheet that :mod:`onefold_cad.export.solid` builds
    (length^3), integrated from the geometry, independently of the B-rep: a
    check on the CAD kernel's result.

    Per side, over the angle theta (the sheet and its mitre blocks past the
    crease halves, :class:`Slab`): the cross-section at theta is the
    rectangle r in [r_in, r_out], s in ``s_range`` clipped by the cutting
    planes (each a straight line in (r, s)), with the Jacobian
    ``r - s k(theta)`` of the map F (k = 0 on the flat blocks). That integral
    is exact (Gauss-Legendre on the pieces of s between the lines' crossings
    of r_in, r_out and each other, where the integrand is quadratic); theta
    is integrated by Gauss-Legendre on panels graded towards every break
    (where a face's bounds change: the corners' crossings of the planes, the
    sheet's vertices, the creases), where the integrand is smooth: relative
    error about 1e-12.
    """
    return Slab(folded, material, hole_diameter).volume()


_GL8 = np.polynomial.legendre.leggauss(8)
_GL2 = np.polynomial.legendre.leggauss(2)
#: Panel ends within a piece between breaks (as fractions), graded to both ends.
_PANELS = sorted_unique(
    np.concatenate([[0.0, 1.0], np.geomspace(1e-9, 0.5, 12), 1.0 - np.geomspace(1e-9, 0.5, 12)])
)


def _graded_rule(breaks: Array) -> tuple[Array, Array]:
    """Nodes and weights of composite 8-point Gauss-Legendre rules on panels
    graded towards both ends of every piece between ``breaks``."""
    ends = np.concatenate(
        [a + (b - a) * _PANELS[:-1] for a, b in zip(breaks[:-1], breaks[1:], strict=True)]
        + [breaks[-1:]]
    )
    half = 0.5 * np.diff(ends)
    mid = 0.5 * (ends[:-1] + ends[1:])
    x, w = _GL8
    return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()


# -- the solid's boundary, face by face ---------------------------------------
@dataclass(frozen=True)
class Boundary:
    """One boundary curve of a face of the solid, a function of the angle theta.

    Attributes:
        kind: 'C': r = R(theta) on the sheet face s = s_level (an edge of the
            slab); 'K': the sheet face s = s_level cut by a plane; 'W': the
            wall r = R(theta) cut by a plane.
        radius: 'in' (relief hole) or 'out' (the sheet's cut edge, or past a
            crease half the end of its mitre) for C and W.
        level: 0 or 1, the index of s in ``Slab.s_range``, for C and K.
        plane: the cutting plane for K and W: 'y' (the fold's plane of
            symmetry) or 'm0' / 'm1' (the mitre planes, :func:`mitre_planes`).
        side: 0 (+y) or 1 (-y); -1 for a curve on the plane y = 0 that both
            sides share (the -y side's map is the +y side's mirror image).
    """

    kind: str
    radius: str = ""
    level: int = -1
    plane: str = ""
    side: int = -1


@dataclass(frozen=True)
class Patch:
    """A ruled piece of the solid's boundary between two curves, theta in [t0, t1].

    Attributes:
        side: 0 (+y) or 1 (-y).
        face: 's0' or 's1' (the sheet's faces, offsets ``s_range``), 'in' (the
            relief hole's wall), 'out' (the cut edge's wall, or the end of the
            mitre past a crease half).
        t0, t1: the angle range (radians; < 0 or > total past the creases).
        low, high: its two boundary curves: at smaller r (sheet faces) or at
            smaller s (walls), and at larger r or s. Each ruling of the patch
            joins the two curves' points of the same theta.
    """

    side: int
    face: str
    t0: float
    t1: float
    low: Boundary
    high: Boundary


class Slab:
    """The boundary of the thick sheet (exact model) as ruled patches.

    Each side is the map ``F(theta, r, s)`` of :class:`SideMap` over
    r in [r_in(theta), r_out(theta)] and s in ``s_range``, continued past each
    crease half by its flat mitre block, and kept where it lies on the inner
    side of the cutting planes: the fold's plane of symmetry y = 0 everywhere,
    and past crease half k also its mitre plane (:func:`mitre_planes`). The
    -y side is the +y side's mirror image, built for the mirrored sheet. F is
    linear in r and in s, and so is every plane's equation, so each face is
    ruled: a sheet face between two curves in r, a wall between two curves in
    s, each curve either an edge of the slab or where the face or wall meets
    a plane (at a closed-form r or s along each ruling). :meth:`patches` lists
    them. The faces on the planes are left open for the B-rep builder to
    close: where y = 0 the two sides' sections coincide except where the
    sheet's edges at a crease end are not symmetric about it.

    Lengths in the design unit, angles in radians.

    Attributes:
        s_range: the two faces' offsets from the reference surface (length).
        hole: the relief hole's radius (length).
        sides: the two sides' maps (+y, -y).
        total: the developed angle of a side.
        lengths: the crease halves' lengths.
        depth: per crease half, how far past it the mitre reaches (0: none).
        domain: the angles covered, past both creases.
        planes: name -> ``(w, c)``: the plane ``w . (p - A) = c`` (+y side),
            the solid on the side ``w . (p - A) >= c``.
    """

    def __init__(self, folded: FoldedSheet, material: Material, hole_diameter: float) -> None:
        self.s_range = sheet_offsets(material)
        self.thickness = material.thickness
        self.hole = 0.5 * hole_diameter
        self.sides = (SideMap(folded), SideMap(folded, lower=True))
        side = self.sides[0]
        self.total = side.total
        self.lengths = side.edge_radius(np.array([0.0, side.total]))
        self.depth: list[float] = []
        tip = []
        for end in (0, 1):
            _, e, n = side.crease_frame(end)
            into = e[1] if end == 0 else -e[1]
            if into <= 1e-9:
                raise InvalidParameterError(
                    "alpha",
                    "the fold is flat or folded through: the crease has no mitre for a solid; "
                    "write the shell (--body shell)",
                )
            depth = max(0.0, max(s * n[1] for s in self.s_range) / into)
            if depth >= self.hole:
                raise InvalidParameterError(
                    "relief_hole", "the relief hole is too small to mitre the thick sheet"
                )
            self.depth.append(depth)
            tip.append(math.asin(depth / self.hole))
        self.domain = (-tip[0], self.total + tip[1])
        m0, m1 = mitre_planes(side, self.thickness)
        self.planes = {"y": (np.array([0.0, 1.0, 0.0]), 0.0), "m0": m0, "m1": m1}

    # -- the map and its bounds ------------------------------------------------
    def region(self, theta: Array) -> int:
        """-1, 0 or 1: where the middle of ``theta`` lies (past crease half 0,
        on the sheet, past crease half 1); a curve lies in one region."""
        mid = 0.5 * (float(np.min(theta)) + float(np.max(theta)))
        return -1 if mid < 0.0 else (1 if mid > self.total else 0)

    def _past(self, theta: Array, region: int | None) -> tuple[Array, Array]:
        """Masks of the angles past crease half 0 and past crease half 1 (all
        or none of them when ``region`` is given, for one-sided values at a
        crease)."""
        if region is None:
            return theta < 0.0, theta > self.total
        return np.full(len(theta), region == -1), np.full(len(theta), region == 1)

    def frames(self, theta: Array) -> tuple[Array, Array, Array]:
        """u, e, n ``(k, 3)`` of the +y side (the -y side's are mirror images)."""
        return self.sides[0].frames(theta)

    def plane_names(self, region: int) -> list[str]:
        """The cutting planes of a region (see :meth:`region`)."""
        return ["y"] + (["m0"] if region == -1 else ["m1"] if region == 1 else [])

    def coefficients(self, plane: str, theta: Array) -> tuple[Array, Array, float]:
        """``(alpha, beta, gamma)``: the plane's equation on the ruling at
        theta is ``alpha r + beta s + gamma >= 0``."""
        u, _, n = self.frames(theta)
        return self.plane_terms(plane, u, n)

    def plane_terms(self, plane: str, u: Array, n: Array) -> tuple[Array, Array, float]:
        """:meth:`coefficients` from the frames ``u``, ``n`` ``(k, 3)`` at the angles."""
        w, c = self.planes[plane]
        return u @ w, n @ w, -c

    def inner_radius(self, theta: Array, region: int | None = None) -> Array:
        """r_in: the relief hole's radius (``region`` unused: it is continuous)."""
        return np.full(len(np.atleast_1d(theta)), self.hole)

    def outer_radius(self, side: int, theta: Array, region: int | None = None) -> Array:
        """r_out: the sheet's edge (this side's); past a crease half the plane
        through its end perpendicular to it."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        r = self.sides[side].edge_radius(np.clip(t, 0.0, self.total))
        for end, mask in enumerate(self._past(t, region)):
            if np.any(mask):
                d = t[mask] - (0.0 if end == 0 else self.total)
                r[mask] = self.lengths[end] / np.cos(d)
        return r

    def radius(self, which: str, side: int, theta: Array, region: int | None = None) -> Array:
        """r_in (``which`` = 'in') or r_out ('out') at ``theta``."""
        if which == "in":
            return self.inner_radius(theta, region)
        return self.outer_radius(side, theta, region)

    def kinks(self, which: str, side: int) -> Array:
        """Sorted angles where r_in or r_out is not smooth, with the domain's
        ends and both crease halves: the curves are built between them."""
        out = _unique(np.array([self.domain[0], 0.0, self.total, self.domain[1]]))
        if which == "out":
            # a vertex on a crease ruling (angle 0 or pi; the cone's total angle
            # is pi only up to the solver's residual) is the crease's end
            out = _merge(out, self.sides[side].vertex_angles, 0.0, self.total, _CREASE_GAP)
        return out

    def points(self, side: int, theta: Array, r: Array, s: float | Array) -> Array:
        """F(theta, r, s) in the fold frame on ``side`` (the -y side mirrored), ``(k, 3)``."""
        u, _, n = self.frames(theta)
        return self._place(side, u, n, r, s)

    def _place(self, side: int, u: Array, n: Array, r: Array, s: float | Array) -> Array:
        """:meth:`points` from the +y side's frames ``u``, ``n`` at the angles."""
        p = self.sides[0].place(u, n, r, s)
        if side == 1:
            p[:, 1] *= -1.0
        return p

    def boundary_points(self, b: Boundary, side: int, theta: Array) -> Array:
        """Points ``(k, 3)`` of boundary curve ``b`` at ``theta``, fold frame
        (``side`` picks the sheet for curves that depend on it)."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        own = side if b.side < 0 else b.side
        where = self.region(t)
        u, _, n = self.frames(t)
        if b.kind == "C":
            r = self.radius(b.radius, own, t, where)
            return self._place(own, u, n, r, self.s_range[b.level])
        alpha, beta, gamma = self.plane_terms(b.plane, u, n)
        if b.kind == "K":
            s = self.s_range[b.level]
            p = self._place(own, u, n, -(beta * s + gamma) / alpha, s)
        else:
            r = self.radius(b.radius, own, t, where)
            p = self._place(own, u, n, r, -(alpha * r + gamma) / beta)
        if b.plane == "y":
            p[:, 1] = 0.0  # on the plane of symmetry
        return p

    # -- where the faces change ----------------------------------------------------
    def _evaluate(self, specs: list[tuple], label: NDArray[np.int64], theta: Array) -> Array:
        """The functions ``specs[label]`` at ``theta`` (see :meth:`_specs`)."""
        out = np.empty(len(theta))
        # the functions of a piece share its angles: the frames once per angle
        at, where = np.unique(theta, return_inverse=True)
        u, _, n = self.frames(at)
        u, n = u[where], n[where]
        for i in sorted_unique(label).tolist():
            spec = specs[i]
            m = label == i
            t, um, nm = theta[m], u[m], n[m]

            def coef(plane: str, um: Array = um, nm: Array = nm) -> tuple[Array, Array, float]:
                return self.plane_terms(plane, um, nm)

            kind = spec[0]
            if kind == "corner":  # a plane through an edge of the slab
                _, which, side, j, p = spec
                a, b, g = coef(p)
                out[m] = a * self.radius(which, side, t) + b * self.s_range[j] + g
            elif kind == "face":  # two planes meeting on a sheet face
                _, j, p, q = spec
                (ap, bp, gp), (aq, bq, gq) = coef(p), coef(q)
                s = self.s_range[j]
                out[m] = (bp * s + gp) * aq - (bq * s + gq) * ap
            else:  # "wall": two planes meeting on a wall
                _, which, side, p, q = spec
                (ap, bp, gp), (aq, bq, gq) = coef(p), coef(q)
                r = self.radius(which, side, t)
                out[m] = (ap * r + gp) * bq - (aq * r + gq) * bp
        return out

    def _specs(self) -> tuple[list[tuple], list[tuple[float, float]]]:
        """The functions whose zeros split the faces, each with the piece of
        theta (between kinks) it is searched on."""
        specs: list[tuple] = []
        pieces: list[tuple[float, float]] = []
        for side in (0, 1):
            for which in ("in", "out"):
                ks = self.kinks(which, side)
                for a, b in zip(ks[:-1], ks[1:], strict=True):
                    planes = self.plane_names(self.region(np.array([a, b])))
                    for j in (0, 1):
                        for p in planes:
                            specs.append(("corner", which, side, j, p))
                            pieces.append((a, b))
                    if len(planes) > 1 and which == "in" and side == 0:
                        for j in (0, 1):
                            specs.append(("face", j, *planes))
                            pieces.append((a, b))
                    if len(planes) > 1:
                        specs.append(("wall", which, side, *planes))
                        pieces.append((a, b))
        return specs, pieces

    @cached_property
    def roots(self) -> dict[tuple, Array]:
        """The zeros of each function of :meth:`_specs` (sorted, keyed by the
        spec): bracketed on a grid graded towards the pieces' ends, refined by
        bisection to machine precision, all at once."""
        specs, pieces = self._specs()
        ab = np.array(pieces)
        grid = ab[:, :1] + (ab[:, 1:] - ab[:, :1]) * _GRID  # (specs, g)
        every = np.repeat(np.arange(len(specs)), grid.shape[1])
        pos = (self._evaluate(specs, every, grid.ravel()) >= 0.0).reshape(grid.shape)
        k = pos[:, 1:] != pos[:, :-1]  # a sign change between neighbours
        lo, hi, up = grid[:, :-1][k], grid[:, 1:][k], pos[:, 1:][k]
        lab = np.broadcast_to(np.arange(len(specs))[:, None], k.shape)[k]
        for _ in range(64):
            mid = 0.5 * (lo + hi)
            if not np.any((mid > lo) & (mid < hi)):
                break
            right = (self._evaluate(specs, lab, mid) >= 0.0) == up
            hi = np.where(right, mid, hi)
            lo = np.where(right, lo, mid)
        r = 0.5 * (lo + hi)
        roots: dict[tuple, Array] = {}
        for i, spec in enumerate(specs):
            a, b = pieces[i]
            mine = r[lab == i]
            roots[spec] = np.sort(np.concatenate([roots.get(spec, np.empty(0)), mine]))
        return roots

    def breaks(self, side: int, face: str | None = None) -> Array:
        """The angles where a face of ``side`` changes (``face``: 's0', 's1',
        'in', 'out', or None for all): the kinks of its edges and the zeros of
        its functions (:meth:`_specs`), sorted."""
        parts = []
        for spec, rs in self.roots.items():
            kind = spec[0]
            if kind == "corner":
                _, which, s, j, _ = spec
                hit = s == side and (face is None or face in (f"s{j}", which))
            elif kind == "face":
                hit = face is None or face == f"s{spec[1]}"
            else:
                hit = spec[2] == side and (face is None or face == spec[1])
            if hit:
                parts.append(rs)
        if face in ("in", "out"):
            base = self.kinks(face, side)
        else:
            base = _merge(self.kinks("in", side), self.kinks("out", side))
        return _merge(base, np.concatenate(parts) if parts else np.empty(0))

    # -- the cross-sections ------------------------------------------------------
    def _active(self, theta: Array, u: Array, n: Array) -> list[tuple[Array, Array, Array]]:
        """``(alpha, beta, gamma)`` ``(k,)`` of every plane at ``theta`` (its
        frames ``u``, ``n``), a plane that does not cut there given as
        0 r + 0 s + 1 >= 0."""
        out = []
        for name in ("y", "m0", "m1"):
            a, b, g = self.plane_terms(name, u, n)
            g = np.full(len(theta), g)
            if name != "y":
                off = ~(theta < 0.0) if name == "m0" else ~(theta > self.total)
                a, b, g = np.where(off, 0.0, a), np.where(off, 0.0, b), np.where(off, 1.0, g)
            out.append((a, b, g))
        return out

    def section_integral(self, side: int, theta: Array) -> Array:
        """The integral of the Jacobian ``r - s k`` over the cross-section at
        each angle (r in [r_in, r_out], s in ``s_range``, inside every plane),
        ``(k,)`` (length^2): exact, the integrand being quadratic in s between
        the s where the planes' lines cross r = r_in, r = r_out and each other."""
        u, _, n, k = self.sides[0].frames_and_curvature(theta)
        r_in, r_out = self.inner_radius(theta), self.outer_radius(side, theta)
        s0, s1 = self.s_range
        planes = self._active(theta, u, n)
        cuts = [np.full(len(theta), s0), np.full(len(theta), s1)]
        with np.errstate(divide="ignore", invalid="ignore"):
            for a, b, g in planes:
                cuts += [-(a * r_in + g) / b, -(a * r_out + g) / b]
            for i, (ap, bp, gp) in enumerate(planes):
                for aq, bq, gq in planes[i + 1 :]:
                    cuts.append((gq * ap - gp * aq) / (bp * aq - bq * ap))
        ss = np.stack(cuts, axis=1)
        ss = np.sort(np.clip(np.where(np.isfinite(ss), ss, s0), s0, s1), axis=1)
        out = np.zeros(len(theta))
        x, w = _GL2
        for lo_s, hi_s in zip(ss.T[:-1], ss.T[1:], strict=True):
            half = 0.5 * (hi_s - lo_s)
            for xi, wi in zip(x, w, strict=True):
                s = 0.5 * (lo_s + hi_s) + half * xi
                lo, hi = r_in.copy(), r_out.copy()
                ok = np.ones(len(theta), dtype=bool)
                with np.errstate(divide="ignore", invalid="ignore"):
                    for a, b, g in planes:
                        rho = -(b * s + g) / a
                        lo = np.where(a > 0.0, np.maximum(lo, rho), lo)
                        hi = np.where(a < 0.0, np.minimum(hi, rho), hi)
                        ok &= (a != 0.0) | (b * s + g >= 0.0)
                ok &= hi > lo
                inner = 0.5 * (hi * hi - lo * lo) - s * k * (hi - lo)
                out += wi * half * np.where(ok, inner, 0.0)
        return out

    def volume(self) -> float:
        """The solid's volume (length^3): see :func:`slab_volume`."""
        total = 0.0
        for side in (0, 1):
            theta, weight = _graded_rule(self.breaks(side))
            total += float(weight @ self.section_integral(side, theta))
        return total

    # -- the patches --------------------------------------------------------------
    def patches(self) -> list[Patch]:
        """The ruled patches of both sides (see :class:`Patch`)."""
        out: list[Patch] = []
        for side in (0, 1):
            for j in (0, 1):
                out += self._sheet_face(side, j, self.breaks(side, f"s{j}"))
            for which in ("in", "out"):
                out += self._wall(side, which, self.breaks(side, which))
        return _share_symmetric_walls(self, out)

    def _cut(self, plane: str, side: int, past: bool, **kw: object) -> Boundary:
        """A cut curve: on y = 0 both sides share it (the cut edge's wall
        only past the creases, where it does not depend on the sheet)."""
        shared = plane == "y" and (kw.get("radius") != "out" or past)
        kind = "K" if "level" in kw else "W"
        return Boundary(kind, plane=plane, side=-1 if shared else side, **kw)  # type: ignore[arg-type]

    def _sheet_face(self, side: int, j: int, breaks: Array) -> list[Patch]:
        s = self.s_range[j]
        out = []
        for a, b in zip(breaks[:-1], breaks[1:], strict=True):
            mid = np.array([0.5 * (a + b)])
            region = self.region(np.array([a, b]))
            lo, hi = float(self.inner_radius(mid)[0]), float(self.outer_radius(side, mid)[0])
            low = Boundary("C", "in", j, side=side)
            high = Boundary("C", "out", j, side=side)
            empty = False
            for p in self.plane_names(region):
                al, be, ga = (float(np.asarray(v).ravel()[0]) for v in self.coefficients(p, mid))
                if al == 0.0:
                    empty |= be * s + ga < 0.0
                    continue
                rho = -(be * s + ga) / al
                cut = self._cut(p, side, region != 0, level=j)
                if al > 0.0 and rho > lo:
                    lo, low = rho, cut
                elif al < 0.0 and rho < hi:
                    hi, high = rho, cut
            if not empty and hi > lo:
                out.append(Patch(side, f"s{j}", float(a), float(b), low, high))
        return out

    def _wall(self, side: int, which: str, breaks: Array) -> list[Patch]:
        out = []
        for a, b in zip(breaks[:-1], breaks[1:], strict=True):
            mid = np.array([0.5 * (a + b)])
            region = self.region(np.array([a, b]))
            r = float(self.radius(which, side, mid)[0])
            lo, hi = self.s_range
            low = Boundary("C", which, 0, side=side)
            high = Boundary("C", which, 1, side=side)
            empty = False
            for p in self.plane_names(region):
                al, be, ga = (float(np.asarray(v).ravel()[0]) for v in self.coefficients(p, mid))
                if be == 0.0:
                    empty |= al * r + ga < 0.0
                    continue
                sig = -(al * r + ga) / be
                cut = self._cut(p, side, region != 0, radius=which)
                if be > 0.0 and sig > lo:
                    lo, low = sig, cut
                elif be < 0.0 and sig < hi:
                    hi, high = sig, cut
            if not empty and hi > lo:
                out.append(Patch(side, which, float(a), float(b), low, high))
        return out


#: Angles closer than this (radians) are one break.
_ROOT_GAP = 1e-12


def _unique(t: Array, tol: float = _ROOT_GAP) -> Array:
    """Sorted ``t`` without values closer than ``tol`` (radians) to the one before."""
    t = np.sort(t)
    return t[np.concatenate([[True], np.diff(t) > tol])]


#: Sheet vertices closer than this (radians) to a crease ruling lie on it.
_CREASE_GAP = 1e-7


def _merge(
    base: Array, extra: Array, lo: float = -np.inf, hi: float = np.inf, end_gap: float = _ROOT_GAP
) -> Array:
    """The sorted union of ``base`` and the values of ``extra`` more than
    ``end_gap`` inside (lo, hi) that are not within ``_ROOT_GAP`` of a value
    already in it (``base``'s values win: they are the exact kinks)."""
    out = np.sort(base)
    for t in np.sort(np.asarray(extra, dtype=float)):
        if lo + end_gap < t < hi - end_gap and np.min(np.abs(out - t)) > _ROOT_GAP:
            out = np.sort(np.append(out, t))
    return out


#: Relative grid for bracketing roots between kinks: uniform, and graded
#: towards both ends (the cuts at y = 0 lie within about t / (crease length)
#: of the creases). The kinks themselves are left out: there a function may
#: vanish exactly (the face s = 0 on a crease ruling) and its sign is noise.
_GRID = sorted_unique(
    np.concatenate(
        [
            np.linspace(0.0, 1.0, 129)[1:-1],
            np.geomspace(1e-12, 0.05, 48),
            1.0 - np.geomspace(1e-12, 0.05, 48),
        ]
    )
)


def _share_symmetric_walls(slab: Slab, patches: list[Patch]) -> list[Patch]:
    """Where both sides' cut-edge walls meet y = 0 along the same curve (the
    sheet's edges symmetric about a crease half there), let them share it."""

    def own_cut(p: Patch) -> bool:
        return p.face == "out" and any(
            b.kind == "W" and b.plane == "y" and b.side >= 0 for b in (p.low, p.high)
        )

    sides: dict[tuple[float, float], set[int]] = {}
    for p in patches:
        if own_cut(p):
            sides.setdefault((p.t0, p.t1), set()).add(p.side)
    shared = set()
    for (a, b), who in sides.items():
        t = np.linspace(a, b, 9)
        r0, r1 = slab.outer_radius(0, t), slab.outer_radius(1, t)
        if who == {0, 1} and np.max(np.abs(r0 - r1)) <= 1e-12 * np.max(r0):
            shared.add((a, b))
    cut = Boundary("W", "out", plane="y", side=-1)
    out = []
    for p in patches:
        if own_cut(p) and (p.t0, p.t1) in shared:
            p = replace(p, low=cut) if p.low.kind == "W" else replace(p, high=cut)
        out.append(p)
    return out
