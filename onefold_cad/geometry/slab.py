"""The thick sheet's solid (exact model) as ruled patches between boundary
curves: the map past the creases, the cutting planes and where the faces
change.

:class:`Slab` holds the solid's description; :mod:`.slab_faces` lists its
faces as :class:`Patch` es, :mod:`.slab_volume` integrates its volume; the
B-rep is built from them in :mod:`onefold_cad.export.solid`. Numpy only.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.numeric import Array, Mask, sorted_unique
from onefold_cad.geometry.thick_map import SideMap, mitre_planes

__all__ = ["Boundary", "Patch", "Slab", "merge_angles"]


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

    def _past(self, theta: Array, region: int | None) -> tuple[Mask, Mask]:
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
            out = merge_angles(out, self.sides[side].vertex_angles, 0.0, self.total, _CREASE_GAP)
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
            base = merge_angles(self.kinks("in", side), self.kinks("out", side))
        return merge_angles(base, np.concatenate(parts) if parts else np.empty(0))


#: Angles closer than this (radians) are one break.
_ROOT_GAP = 1e-12


def _unique(t: Array, tol: float = _ROOT_GAP) -> Array:
    """Sorted ``t`` without values closer than ``tol`` (radians) to the one before."""
    t = np.sort(t)
    return t[np.concatenate([[True], np.diff(t) > tol])]


#: Sheet vertices closer than this (radians) to a crease ruling lie on it.
_CREASE_GAP = 1e-7


def merge_angles(
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
