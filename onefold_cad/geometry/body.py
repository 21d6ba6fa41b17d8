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
from collections.abc import Callable
from functools import cached_property
from itertools import combinations

import numpy as np
from numpy.typing import NDArray

from onefold_cad.choices import Body as BodyKind
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.numeric import Array, sorted_unique
from onefold_cad.geometry.pieces import Piece, clipped_rectangle, zoom_min
from onefold_cad.geometry.thick_map import CreaseFrames, SideMap, mitre_depth, mitre_planes

__all__ = ["BODIES", "MIRROR", "Body"]

#: The bodies a form can be written as (the values of :class:`~onefold_cad.choices.Body`).
BODIES = tuple(b.value for b in BodyKind)
#: The mirror image in the xz-plane (the -y side of the +y side).
MIRROR = np.array([1.0, -1.0, 1.0])
#: Sample points of all pieces together, spread by flat edge length.
_SAMPLES = 1200
#: Largest step in the flat angle between samples of an edge (radians).
_MAX_ANGLE_STEP = math.pi / 180


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
            fixed += self._paper_pieces()
        else:
            fixed += self._exact_pieces()
        self.fixed = np.array(fixed, dtype=float).reshape(-1, 3)

    # -- pieces -------------------------------------------------------------
    def _paper_pieces(self) -> list[Array]:
        """The paper model's shell: straight between the ruling ends and the
        sheet's vertices, which are its extremes; the hole's edge is a circular
        arc per triangle.

        The vertices count on their own: a vertex within 1e-12 rad of a fan
        division has no ruling of its own (the division's is used), and where
        the edge beside it runs almost through H the division's ruling end
        lies measurably short of the vertex (1.5e-7 of the size for an edge
        passing 5e-10 of it from H): the folded corner, in that triangle's
        plane, can be the lowest point."""
        folded, rho = self.folded, self.hole
        corners = folded.map_points(folded.sheet.vertices) - folded.apex
        fixed = list(folded.rulings_3d[:, 1] - folded.apex) + list(corners)
        if rho <= 0.0:
            return [np.zeros(3), *fixed]
        for side, thetas in enumerate(folded.ruling_angles):
            sign = 1.0 if side == 0 else -1.0
            for a, b in zip(thetas[:-1], thetas[1:], strict=True):
                self.pieces.append(
                    Piece(f"hole arc {side}", np.linspace(a, b, 4), self._paper_arc(rho, sign))
                )
        return fixed

    def _paper_arc(self, rho: float, sign: float) -> Callable[[Array], Array]:
        def points(theta: Array) -> Array:
            psi = sign * theta
            flat = rho * np.stack([np.cos(psi), np.sin(psi)], axis=-1)
            return (self.folded.map_points(flat) - self.folded.apex)[:, None, :]

        return points

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
        v = sheet.vertices
        # sample each edge evenly on the flat sheet and evenly in its flat
        # angle (an edge passing close to H sweeps a wide angle in a short
        # length); the pieces run in phi
        flat_params, thetas, steps = [], [], []
        for k in range(len(v)):
            a, b = v[k], v[(k + 1) % len(v)]
            length = float(np.hypot(*(b - a)))
            n = max(16, math.ceil(_SAMPLES * length / sheet.perimeter))
            ta, tb = (abs(math.atan2(p[1], p[0])) for p in (a, b))
            ang = np.linspace(ta, tb, max(2, math.ceil(abs(tb - ta) / _MAX_ANGLE_STEP) + 1))
            psi = np.where(a[1] + b[1] < 0.0, -ang, ang)
            ray = sheet.ray_lengths(psi)[:, None] * np.column_stack([np.cos(psi), np.sin(psi)])
            along = np.clip((ray - a) @ (b - a) / length**2, 0.0, 1.0)
            s_all = sorted_unique(np.concatenate([np.linspace(0.0, 1.0, n), along]))
            q = a + s_all[:, None] * (b - a)
            flat_params.append((a, b))
            thetas.append(np.abs(np.arctan2(q[:, 1], q[:, 0])))  # the side's own flat angle
            steps.append(float(np.max(np.diff(s_all))) * length)
        cuts = np.cumsum([len(t) for t in thetas])[:-1]
        phis = np.split(cone.phi_of_theta(np.concatenate(thetas)), cuts)
        for k, ((a, b), theta, phi) in enumerate(zip(flat_params, thetas, phis, strict=True)):
            lower = a[1] + b[1] < 0.0
            grid = np.maximum.accumulate(phi if phi[-1] >= phi[0] else phi[::-1])
            t_lo, t_hi = float(min(theta[0], theta[-1])), float(max(theta[0], theta[-1]))
            fn = self._sector(arc, lower, t_lo, t_hi)
            self.pieces.append(Piece(f"edge {k}", grid, fn, steps[k]))
        if self.kind == "solid":
            for lower in (False, True):
                side = CreaseFrames(SideMap(folded, lower=lower))
                for end in (0, 1):
                    verts, wall = self._block(side, end)
                    fixed += list(verts)
                    self.pieces.append(wall)
        return fixed

    def _sector(
        self, arc: ArcFrames, lower: bool, t_lo: float, t_hi: float
    ) -> Callable[[Array], Array]:
        """Section corners of one sector (one sheet edge) of one side, as a
        function of phi."""
        cone = self.folded.solution.surface
        assert isinstance(cone, ExactCone)
        sheet, rho, tol = self.folded.sheet, self.hole, self._tol
        mirror = MIRROR if lower else np.ones(3)
        s0, s1 = self.s_range
        solid = self.kind == "solid"

        def points(phi: Array) -> Array:
            theta = np.clip(cone.theta_of_phi(phi), t_lo, t_hi)
            r_out = sheet.ray_lengths(-theta if lower else theta)
            if not solid:
                u = arc.frames(phi)[0]
                out = r_out[:, None] * u
                if rho > 0.0:
                    out = np.stack([rho * u, out], axis=1)
                else:
                    out = out[:, None, :]
                return out * mirror
            u, _, n = arc.frames(phi)
            z = clipped_rectangle(np.full_like(r_out, rho), r_out, s0, s1, u[:, 1], n[:, 1], tol)
            pts = z[..., :1] * u[:, None, :] + z[..., 1:] * n[:, None, :]
            return pts * mirror

        return points

    def _block(self, side: CreaseFrames, end: int) -> tuple[Array, Piece]:
        """The mitre block past crease half ``end`` of one side: the vertices
        of its polytope outside the hole's disk ``(m, 3)``, and the hole's wall
        as a piece over the distance d past the crease."""
        s0, s1 = self.s_range
        rho, tol = self.hole, self._tol
        mirror = MIRROR if side.lower else np.ones(3)
        depth = mitre_depth(side, self.s_range)
        u, e, n = side.crease_frame(end)
        away = -e if end == 0 else e
        length = float(side.edge_radius(np.array([0.0 if end == 0 else side.total]))[0])
        m, c = mitre_planes(side, s1 - s0)[end]
        basis = np.stack([u, away, n], axis=1)  # (x, d, s) -> offset from the apex
        x_in = math.sqrt(max(rho * rho - depth * depth, 0.0))
        # the polytope {a . (x, d, s) <= b}
        a = np.array(
            [
                [-1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, -1.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, -1.0],
                [0.0, 0.0, 1.0],
                -(basis[1]),  # y >= 0
                -(m @ basis),  # (p - A) . m >= c
            ]
        )
        b = np.array([-x_in, length, 0.0, depth, -s0, s1, 0.0, -c])
        triples = np.array(list(combinations(range(len(a)), 3)))
        mats = a[triples]
        ok = np.abs(np.linalg.det(mats)) > 1e-12
        z = np.linalg.solve(mats[ok], b[triples[ok]][..., None])[..., 0]
        inside = np.all(z @ a.T - b <= tol, axis=1)
        inside &= z[:, 0] ** 2 + z[:, 1] ** 2 >= rho * rho - tol * rho
        verts = (z[inside] @ basis.T) * mirror

        def wall(d: Array) -> Array:
            x = np.sqrt(np.maximum(rho * rho - d * d, 0.0))
            lo, hi = np.full_like(d, s0), np.full_like(d, s1)
            for row, off in ((a[6], b[6]), (a[7], b[7])):
                # row . (x, d, s) <= off: a bound on s
                rest = off - row[0] * x - row[1] * d
                if row[2] > 0.0:
                    hi = np.minimum(hi, rest / row[2])
                elif row[2] < 0.0:
                    lo = np.maximum(lo, rest / row[2])
                else:
                    hi = np.where(rest >= -tol, hi, -np.inf)
            ok = lo <= hi + tol
            s = np.stack([lo, hi], axis=1)
            xx, dd = np.broadcast_to(x[:, None], s.shape), np.broadcast_to(d[:, None], s.shape)
            z = np.stack([xx, dd, s], axis=-1)
            pts = (z @ basis.T) * mirror
            return np.where(ok[:, None, None], pts, np.nan)

        name = f"mitre {end} {'lower' if side.lower else 'upper'} hole wall"
        return verts, Piece(name, np.linspace(0.0, depth, 24), wall)

    # -- sampling -------------------------------------------------------------
    @cached_property
    def sections(self) -> list[Array]:
        """Per piece: the section corners ``(n, V, 3)`` at its grid."""
        return [piece.points(piece.grid) for piece in self.pieces]

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
