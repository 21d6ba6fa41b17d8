"""The body a form is written as: where its lowest point can lie, and its mass.

Two bodies, as the STEP adapter builds them (:mod:`onefold_cad.export.part`):

* ``shell``: the folded reference surface, with a relief hole of radius rho
  about the apex (none: the apex itself). Along a ruling the height is linear,
  so the extremes of a cone patch lie on its boundary: the sheet's edges mapped
  onto the cone and the hole's edge (or the apex); the paper model's edges are
  straight between the ruling ends, which are its extremes.
* ``solid``: the sheet of the material's thickness (exact model). Per side the
  slab ``F(theta, r, s) = A + r u + s n`` (u the ruling direction, n the top
  normal), r from the hole to the sheet's edge and s between the faces of
  :func:`~onefold_cad.geometry.material.sheet_offsets`, where it lies on its
  own side of the fold's plane of symmetry; and past each crease half the
  mitre's flat block ``A + x u + d a + s n`` (a pointing away from the side's
  sheet) cut at that plane and at its mitre plane, the plane through the
  apex that bisects the crease halves moved a little towards its own half
  (:func:`~onefold_cad.geometry.thick_map.mitre_planes`, as
  :func:`onefold_cad.export.solid.thick_solid` builds it).

For a fixed ruling the slab's section is a rectangle in (r, s), cut by one
line, on which the point depends affinely: a linear function is extreme at
its corners. A block is a polytope less the relief hole's disk: extreme at
the polytope's vertices outside the disk or on the hole's wall. A body is
therefore a list of :class:`Piece` s (one-parameter families of section
corners: the sheet edges' sectors, parametrised by the frame arc's angle phi;
the hole walls) and a set of fixed points (apex, ruling ends, polytope
vertices); its lowest point in a direction is the lowest corner over each
piece's parameter (:func:`zoom_min`).

The centre of mass is integrated from the same description
(:func:`onefold_cad.geometry.body_mass.mass_properties`).

Points are relative to the apex (the fold frame moved by -A), so that a tiny
sheet on a large frame keeps its digits. Lengths are in the design unit;
angles in radians.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from onefold_cad.choices import Body as BodyKind
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body_families import Sectors, Walls
from onefold_cad.geometry.body_pieces import member_points, mitre_block, paper_pieces
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.numeric import Array, sorted_unique
from onefold_cad.geometry.pieces import Piece, end_minimum, zoom_min
from onefold_cad.geometry.thick_map import CreaseFrames, SideMap
from onefold_cad.geometry.zoom import zoom_many

__all__ = ["BODIES", "MIRROR", "Body"]

#: The bodies a form can be written as (the values of :class:`~onefold_cad.choices.Body`).
BODIES = tuple(b.value for b in BodyKind)
#: The mirror image in the xz-plane (the -y side of the +y side).
MIRROR = np.array([1.0, -1.0, 1.0])
#: Sample points of all pieces together, spread by flat edge length.
_SAMPLES = 1200
#: Largest step in the flat angle between samples of an edge (radians).
_MAX_ANGLE_STEP = math.pi / 180


def _spread(s: Array) -> Array:
    """Fractions along an edge ``(m,)``, sorted, with 0 and 1 and no two closer
    than 1e-9: a sample within rounding of another (a ray's crossing on an
    even step) would leave the bracket about it no room on that side."""
    inner = sorted_unique(s[(s > 1e-9) & (s < 1.0 - 1e-9)])
    inner = inner[np.concatenate([[True], np.diff(inner) > 1e-9])] if len(inner) else inner
    return np.concatenate([[0.0], inner, [1.0]])


class Body:
    """A folded form as written: its extreme pieces and its centre of mass.

    Args:
        folded: the fold.
        material: thickness, reference surface and relief hole (its
            ``relief_hole_diameter``, as the STEP is built with it); None: a
            zero-thickness sheet without a hole.
        kind: 'shell' (the reference surface) or 'solid' (the thick sheet,
            exact model, thickness > 0).

    Attributes:
        pieces: the :class:`Piece` s.
        fixed: ``(m, 3)`` points that are extremes as they are (apex, ruling
            ends, mitre block vertices).
        origin: the apex ``(3,)`` (fold frame): the body's points are
            relative to it.
        size: the sheet's size (length), the scale of tolerances.
    """

    def __init__(self, folded: FoldedSheet, material: Material | None = None, kind: str = "shell"):
        if kind not in BODIES:
            raise InvalidParameterError("body", f"must be 'shell' or 'solid', got {kind!r}")
        self.folded = folded
        self.kind = kind
        self.size = folded.sheet.size
        self.origin = folded.apex.copy()
        self.hole = 0.5 * material.relief_hole_diameter if material is not None else 0.0
        self.thickness = material.thickness if material is not None else 0.0
        self.exact = isinstance(folded.solution.surface, ExactCone)
        if kind == "solid":
            if not self.exact:
                raise InvalidParameterError(
                    "model", "must be 'exact' for a solid of the sheet's thickness, got 'paper'"
                )
            if material is None or self.thickness <= 0.0 or self.hole <= 0.0:
                raise InvalidParameterError(
                    "body", "'solid' needs a material with thickness > 0 and a relief hole"
                )
        self.s_range = sheet_offsets(material) if material is not None else (0.0, 0.0)
        self._tol = 1e-12 * self.size
        self._lowest: dict[tuple[int, float, float, bytes], tuple[float, Array]] = {}
        self.pieces: list[Piece] = []
        fixed: list[Array] = []
        if not self.exact:
            pieces, more = paper_pieces(folded, self.hole)
            self.pieces += pieces
            fixed += more
        else:
            fixed += self._exact_pieces()
        self.fixed = np.array(fixed, dtype=float).reshape(-1, 3)

    # -- pieces -------------------------------------------------------------
    def _exact_pieces(self) -> list[Array]:
        """The exact model's sectors (one per sheet edge, parametrised by phi),
        and for the solid the mitre blocks."""
        folded = self.folded
        cone = folded.solution.surface
        assert isinstance(cone, ExactCone)
        arc = ArcFrames(folded.solution.frame, folded.apex)
        sheet = folded.sheet
        fixed: list[Array] = []
        if self.kind == "shell" and self.hole <= 0.0:
            fixed.append(np.zeros(3))
        solid = self.kind == "solid"
        sectors = Sectors(cone, arc, sheet, self.hole, self.s_range if solid else None, self._tol)
        v = sheet.vertices
        perimeter = sheet.perimeter
        # sample each edge evenly on the flat sheet and evenly in its flat
        # angle (an edge passing close to H sweeps a wide angle in a short
        # length); the pieces run in phi
        flat_params, thetas, steps = [], [], []
        for k in range(len(v)):
            a, b = v[k], v[(k + 1) % len(v)]
            length = float(np.hypot(*(b - a)))
            n = max(16, math.ceil(_SAMPLES * length / perimeter))
            ta, tb = (abs(math.atan2(p[1], p[0])) for p in (a, b))
            ang = np.linspace(ta, tb, max(2, math.ceil(abs(tb - ta) / _MAX_ANGLE_STEP) + 1))
            psi = np.where(a[1] + b[1] < 0.0, -ang, ang)
            ray = sheet.ray_lengths(psi)[:, None] * np.column_stack([np.cos(psi), np.sin(psi)])
            along = np.clip((ray - a) @ (b - a) / length**2, 0.0, 1.0)
            s_all = _spread(np.concatenate([np.linspace(0.0, 1.0, n), along]))
            q = a + s_all[:, None] * (b - a)
            flat_params.append((a, b))
            thetas.append(np.abs(np.arctan2(q[:, 1], q[:, 0])))  # the side's own flat angle
            steps.append(float(np.max(np.diff(s_all))) * length)
        # the samples' arc parameters from the cone's table (to ~1e-10 rad:
        # where a sample lies need not be exact), the edge ends' exact: the
        # vertex rays' (the sheet's corners are extremes as they are)
        cuts = np.cumsum([len(t) for t in thetas])[:-1]
        phis = np.split(cone.phi_near(np.concatenate(thetas)), cuts)
        for k, ((a, b), theta, phi) in enumerate(zip(flat_params, thetas, phis, strict=True)):
            lower = bool(a[1] + b[1] < 0.0)
            for i in (0, -1):
                theta[i], phi[i] = self._vertex_ray(lower, float(theta[i]))
            np.clip(phi[1:-1], min(phi[0], phi[-1]), max(phi[0], phi[-1]), out=phi[1:-1])
            grid = np.maximum.accumulate(phi if phi[-1] >= phi[0] else phi[::-1])
            t_lo, t_hi = float(min(theta[0], theta[-1])), float(max(theta[0], theta[-1]))
            member = sectors.add(lower, t_lo, t_hi, a, b)
            fn = member_points(sectors, member)
            self.pieces.append(Piece(f"edge {k}", grid, fn, steps[k], sectors, member))
        if solid:
            walls = Walls(self.hole, self.s_range, self._tol)
            for side in self.crease_sides:
                for end in (0, 1):
                    verts, wall = mitre_block(side, end, self.hole, self.s_range, self._tol, walls)
                    fixed += list(verts)
                    self.pieces.append(wall)
        return fixed

    @cached_property
    def crease_sides(self) -> tuple[CreaseFrames, CreaseFrames]:
        """The exact model's maps of the +y and the -y side (their crease
        frames, for the mitre blocks and their mass)."""
        return tuple(CreaseFrames(SideMap(self.folded, lower=lower)) for lower in (False, True))  # type: ignore[return-value]

    @cached_property
    def vertex_phis(self) -> tuple[Array, Array]:
        """The arc parameters ``(m,)`` of each side's vertex rays, the flat
        angles ``folded.sheet.side_angles`` within the cone's total angle
        (exact model; one inversion for both)."""
        cone = self.folded.solution.surface
        assert isinstance(cone, ExactCone)
        up, lo = self._vertex_angles
        both = cone.phi_of_theta(np.concatenate([up, lo]))
        return both[: len(up)], both[len(up) :]

    @cached_property
    def _vertex_angles(self) -> tuple[Array, Array]:
        """Each side's vertex angles within the cone's total angle."""
        total = self.folded.solution.surface.total_angle
        up, lo = self.folded.sheet.side_angles
        return np.clip(up, 0.0, total), np.clip(lo, 0.0, total)

    def _vertex_ray(self, lower: bool, theta: float) -> tuple[float, float]:
        """The vertex ray of one side at flat angle ``theta`` (an edge's end):
        its flat angle as the side's vertex angles give it and its arc
        parameter (:attr:`vertex_phis`)."""
        angles = self._vertex_angles[int(lower)]
        i = int(np.argmin(np.abs(angles - theta)))
        if abs(float(angles[i]) - theta) <= 1e-12:
            return float(angles[i]), float(self.vertex_phis[int(lower)][i])
        cone = self.folded.solution.surface
        assert isinstance(cone, ExactCone)
        return theta, float(cone.phi_of_theta(np.array([theta]))[0])

    # -- sampling -------------------------------------------------------------
    @cached_property
    def _groups(self) -> tuple[NDArray[np.int64], list[list[int]]]:
        """Per piece the group it is evaluated with (the pieces of one family,
        or the piece alone), and each group's pieces."""
        gid = np.zeros(len(self.pieces), dtype=np.int64)
        groups: list[list[int]] = []
        seen: dict[int, int] = {}
        for k, piece in enumerate(self.pieces):
            key = id(piece.family) if piece.family is not None else -1 - k
            if key not in seen:
                seen[key] = len(groups)
                groups.append([])
            gid[k] = seen[key]
            groups[gid[k]].append(k)
        return gid, groups

    def _corners(self, group: int, pieces: NDArray[np.int64], t: Array) -> Array:
        """Corners ``(k, V, 3)`` of ``pieces`` (all of one group) at ``t``."""
        first = self.pieces[int(pieces[0])]
        if first.family is None:
            return first.points(t)
        return first.family.points(self._members[pieces], t)

    @cached_property
    def _members(self) -> NDArray[np.int64]:
        """Each piece's index in its family."""
        return np.array([p.member for p in self.pieces], dtype=np.int64)

    @cached_property
    def stacked(self) -> tuple[Array, NDArray[np.int64], NDArray[np.int64]]:
        """Every piece's sections on one another: corners ``(M, V, 3)`` (V the
        most of any piece, NaN beyond a piece's own), the piece of each row and
        its index in that piece's grid ``(M,)``."""
        v = max((c.shape[1] for c in self.sections), default=1)
        rows = sum(len(c) for c in self.sections)
        out = np.full((rows, v, 3), np.nan)
        piece = np.empty(rows, dtype=np.int64)
        at = 0
        for k, c in enumerate(self.sections):
            out[at : at + len(c), : c.shape[1]] = c
            piece[at : at + len(c)] = k
            at += len(c)
        starts = np.concatenate([[0], np.cumsum([len(c) for c in self.sections])[:-1]])
        index = np.arange(rows) - np.repeat(starts, [len(c) for c in self.sections])
        return out, piece, index.astype(np.int64)

    @cached_property
    def stacked_params(self) -> Array:
        """The grid parameter of each row of :attr:`stacked` ``(M,)``."""
        return np.concatenate([p.grid for p in self.pieces]) if self.pieces else np.zeros(0)

    @cached_property
    def sections(self) -> list[Array]:
        """Per piece: the section corners ``(n, V, 3)`` at its grid (one
        evaluation per family)."""
        out: list[Array] = [np.zeros((0, 1, 3))] * len(self.pieces)
        for g, group in enumerate(self._groups[1]):
            grids = [self.pieces[k].grid for k in group]
            owner = np.repeat(np.array(group, dtype=np.int64), [len(x) for x in grids])
            corners = self._corners(g, owner, np.concatenate(grids))
            cuts = np.cumsum([len(x) for x in grids])[:-1]
            for k, part in zip(group, np.split(corners, cuts), strict=True):
                out[k] = part
        return out

    def lowest_corners(self, pieces: NDArray[np.int64], t: Array, g: Array) -> tuple[Array, Array]:
        """At each (piece, parameter, direction ``(k, 3)``): the lowest corner's
        height along the direction ``(k,)`` (+inf where the section is empty)
        and that corner ``(k, 3)``; one evaluation per family."""
        v = np.empty(len(t))
        p = np.empty((len(t), 3))
        gid = self._groups[0][pieces]
        for group in sorted_unique(gid):
            sel = np.flatnonzero(gid == group)
            pts = self._corners(int(group), pieces[sel], t[sel])
            h = np.einsum("kvj,kj->kv", pts, g[sel])
            h[np.isnan(h)] = np.inf
            i = np.argmin(h, axis=1)
            rows = np.arange(len(sel))
            v[sel] = h[rows, i]
            p[sel] = pts[rows, i]
        return v, p

    @cached_property
    def spacings(self) -> Array:
        """Per piece ``(n,)``: the largest distance between neighbouring
        samples (length), in 3D or along the piece (on the flat sheet), plus
        the thickness: no point of the piece lies further than that from its
        nearest sample (the thickness covers the offsets of a thick sheet)."""
        out = np.zeros(len(self.pieces))
        for i, (piece, corners) in enumerate(zip(self.pieces, self.sections, strict=True)):
            steps = np.linalg.norm(np.diff(corners, axis=0), axis=-1)
            steps = steps[~np.isnan(steps)]
            out[i] = max(piece.step, float(steps.max()) if len(steps) else 0.0)
        return out + self.thickness

    @cached_property
    def samples(self) -> tuple[Array, NDArray[np.int64], Array]:
        """Sample points ``(N, 3)`` of every piece and fixed point, with the
        piece each belongs to ``(N,)`` (-1: a fixed point) and its parameter."""
        pts = [self.fixed]
        owner = [np.full(len(self.fixed), -1, dtype=np.int64)]
        param = [np.zeros(len(self.fixed))]
        for i, (piece, p) in enumerate(zip(self.pieces, self.sections, strict=True)):
            ok = ~np.isnan(p[..., 0])
            pts.append(p[ok])
            owner.append(np.full(int(ok.sum()), i, dtype=np.int64))
            param.append(np.broadcast_to(piece.grid[:, None], ok.shape)[ok])
        return np.concatenate(pts), np.concatenate(owner), np.concatenate(param)

    def lowest(self, piece: int, lo: float, hi: float, g: Array) -> tuple[float, Array]:
        """The lowest point ``(3,)`` along ``g`` of piece ``piece`` for
        parameters in [lo, hi], and its parameter.

        Asked again for the same piece, bracket and direction (the ground
        plane's last look at its features, then its lowest points, then the
        bounds along it), it gives the first answer without zooming again."""
        # by value (+ 0.0: a zero's sign changes no height it compares)
        key = (piece, float(lo), float(hi), (np.asarray(g, dtype=float) + 0.0).tobytes())
        known = self._lowest.get(key)
        if known is None:
            p = self.pieces[piece]
            t, _ = zoom_min(lambda tt: p.heights(tt, g), lo, hi)
            known = self._lowest[key] = (t, p.lowest(t, g))
        return known[0], known[1].copy()

    def lowest_many(
        self,
        asks: list[tuple[int, float, float, Array]],
        group: NDArray[np.int64] | None = None,
        ceiling: Array | None = None,
        known: Array | None = None,
        margin: float = 0.0,
    ) -> list[tuple[float, Array]]:
        """:meth:`lowest` for many (piece, lo, hi, direction) at once: the zooms
        not known yet run together (:func:`~onefold_cad.geometry.zoom.zoom_many`),
        but for a bracket at a piece's end whose samples show the lowest point
        there (:func:`~onefold_cad.geometry.pieces.end_minimum`). With ``group``,
        ``ceiling`` and ``known`` (see ``zoom_many``), a zoom that cannot matter
        stops early: its answer is a point of the bracket, not kept."""
        keys = [
            (k, float(lo), float(hi), (np.asarray(g, dtype=float) + 0.0).tobytes())
            for k, lo, hi, g in asks
        ]
        todo: dict[tuple[int, float, float, bytes], int] = {}
        for i, key in enumerate(keys):
            if key in self._lowest or key in todo:
                continue
            k, lo, hi, g = asks[i]
            end = end_minimum(self.pieces[k].grid, self.sections[k], lo, hi, np.asarray(g))
            if end is not None:  # its samples show it at an end: no zoom
                self._lowest[key] = end
            else:
                todo[key] = i
        found: dict[tuple[int, float, float, bytes], tuple[float, Array]] = {}
        if todo:
            idx = list(todo.values())
            pieces = np.array([asks[i][0] for i in idx], dtype=np.int64)
            gs = np.array([asks[i][3] for i in idx], dtype=float).reshape(-1, 3)

            def f(jobs: NDArray[np.int64], t: Array) -> tuple[Array, Array]:
                return self.lowest_corners(pieces[jobs], t, gs[jobs])

            lo = np.array([asks[i][1] for i in idx], dtype=float)
            hi = np.array([asks[i][2] for i in idx], dtype=float)
            sub = None if group is None else np.asarray(group)[idx]
            t, _, p, done = zoom_many(f, lo, hi, sub, ceiling, known, margin)
            for j, key in enumerate(todo):
                (self._lowest if done[j] else found)[key] = (float(t[j]), p[j])
        out = []
        for key in keys:
            t, p = self._lowest[key] if key in self._lowest else found[key]
            out.append((t, p.copy()))
        return out
