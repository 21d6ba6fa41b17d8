"""The body a form is written as: where its lowest point can lie, and its mass.

Two bodies, as the STEP adapter builds them (:mod:`onefold_cad.export.step`):

* ``shell``: the folded reference surface, with a relief hole of radius rho
  about the apex (none: the apex itself). Along a ruling the height is linear,
  so the extremes of a cone patch lie on its boundary: the sheet's edges mapped
  onto the cone and the hole's edge (or the apex); the paper model's edges are
  straight between the ruling ends, which are its extremes.
* ``solid``: the sheet of the material's thickness (exact model). Per side the
  slab ``F(theta, r, s) = A + r u + s n`` (u the ruling direction, n the top
  normal), r from the hole to the sheet's edge and s between the faces of
  :func:`~onefold_cad.geometry.thick_sheet.sheet_offsets`, where it lies on its
  own side of the fold's plane of symmetry; and past each crease half the
  mitre's flat block ``A + x u + d a + s n`` (a pointing away from the side's
  sheet) cut at that plane and at its mitre plane, the plane through the
  apex that bisects the crease halves moved a little towards its own half
  (:func:`~onefold_cad.geometry.thick_sheet.mitre_planes`, as
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

The centre of mass is integrated from the same description: area-weighted on
the reference surface for zero thickness, volume-weighted (Jacobian
``r - s k``, k the geodesic curvature of u, see
:mod:`onefold_cad.geometry.thick_sheet`) otherwise.

Points are relative to the apex (the fold frame moved by -A), so that a tiny
sheet on a large frame keeps its digits. Lengths are in the design unit;
angles in radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from itertools import combinations

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.frame import arc_points, arc_tangents
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.thick_sheet import SideMap, mitre_depth, mitre_planes, sheet_offsets
from onefold_cad.geometry.validate import cross3, sorted_unique

__all__ = ["Body", "Piece", "zoom_min", "BODIES"]

Array = NDArray[np.float64]
#: The bodies a form can be written as.
BODIES = ("shell", "solid")
_MIRROR = np.array([1.0, -1.0, 1.0])
#: Sample points of all pieces together, spread by flat edge length.
_SAMPLES = 1200
#: Largest step in the flat angle between samples of an edge (radians).
_MAX_ANGLE_STEP = math.pi / 180
_GRID = 33


@dataclass(frozen=True, eq=False)
class Piece:
    """A one-parameter family of points on which a body's extremes lie.

    Attributes:
        name: what it is (for messages), e.g. 'edge 3'.
        grid: ``(n,)`` increasing sample parameters, the first and last being
            the parameter range's ends.
        points: ``(k,)`` parameters -> ``(k, V, 3)`` corners of the section
            there (NaN for corners that are absent).
        step: the largest length along the piece between neighbouring
            samples, on the flat sheet for the sheet's edges (the fold keeps
            lengths: no point of the folded edge lies further than half of it
            from a sample); 0 to take the samples' 3D distances.
    """

    name: str
    grid: Array
    points: Callable[[Array], Array]
    step: float = 0.0

    def heights(self, t: Array, g: Array) -> Array:
        """The lowest corner's height along ``g`` ``(3,)`` at each parameter
        ``(k,)``; +inf where the section is empty."""
        h = self.points(np.asarray(t, dtype=float)) @ g
        return np.where(np.isnan(h), np.inf, h).min(axis=1)

    @property
    def t0(self) -> float:
        """The first parameter."""
        return float(self.grid[0])

    @property
    def t1(self) -> float:
        """The last parameter."""
        return float(self.grid[-1])

    def bracket(self, t_lo: float, t_hi: float) -> tuple[float, float]:
        """The grid's neighbours around [t_lo, t_hi] (one grid step beyond)."""
        g = self.grid
        i = int(np.searchsorted(g, t_lo, side="left"))
        j = int(np.searchsorted(g, t_hi, side="right")) - 1
        return float(g[max(i - 1, 0)]), float(g[min(j + 1, len(g) - 1)])

    def lowest(self, t: float, g: Array) -> Array:
        """The lowest corner ``(3,)`` along ``g`` at parameter ``t``."""
        pts = self.points(np.array([t]))[0]
        h = pts @ g
        return pts[int(np.argmin(np.where(np.isnan(h), np.inf, h)))]


def zoom_min(f: Callable[[Array], Array], lo: float, hi: float) -> tuple[float, float]:
    """The minimum ``(t, f(t))`` of a continuous ``f`` on [lo, hi].

    ``f`` maps ``(k,)`` parameters to ``(k,)`` values. A grid of 33 points is
    laid over the bracket, which shrinks to the best point's neighbours, until
    a parabola through the best point and its neighbours predicts the value
    at its vertex to 1e-3 of the variation there (f is locally quadratic: the
    vertex is the minimum to rounding), or the bracket is 1e-13 of the first
    one (a kink, or a minimum at an end of the bracket, which is a grid point).
    """
    span = hi - lo
    best_t, best_v = lo, math.inf
    at_end = 0
    for rounds in range(20):
        t = np.linspace(lo, hi, _GRID)
        v = f(t)
        i = int(np.argmin(v))
        if v[i] < best_v:
            best_t, best_v = float(t[i]), float(v[i])
        if not math.isfinite(best_v):
            break
        if 0 < i < _GRID - 1 and rounds >= 1:
            a, b, c = float(v[i - 1]), float(v[i]), float(v[i + 1])
            curv = a - 2.0 * b + c
            if curv > 0.0:
                tp = float(t[i]) + 0.5 * float(t[1] - t[0]) * (a - c) / curv
                predicted = b - (a - c) ** 2 / (8.0 * curv)
                vp = float(f(np.array([tp]))[0])
                if vp < best_v:
                    best_t, best_v = tp, vp
                if abs(vp - predicted) <= 1e-3 * (max(a, c) - b):
                    break
        at_end = at_end + 1 if i in (0, _GRID - 1) else 0
        lo, hi = float(t[max(i - 1, 0)]), float(t[min(i + 1, _GRID - 1)])
        if hi - lo <= 1e-13 * span or at_end >= 3:
            break
    return best_t, best_v


def _clipped_rectangle(
    r0: Array, r1: Array, s0: float, s1: float, cr: Array, cs: Array, tol: float
) -> Array:
    """Corners ``(k, 8, 2)`` of the rectangles [r0, r1] x [s0, s1] cut to
    ``cr r + cs s >= 0``: the four corners that satisfy it and the line's
    crossings with the four sides (NaN where absent)."""
    k = len(r0)
    r = np.empty((k, 8))
    s = np.empty((k, 8))
    ok = np.empty((k, 8), dtype=bool)
    r[:, 0], r[:, 1], r[:, 2], r[:, 3] = r0, r1, r1, r0  # the corners
    s[:, :2], s[:, 2:4] = s0, s1
    slack = tol * np.hypot(cr, cs)
    ok[:, :4] = cr[:, None] * r[:, :4] + cs[:, None] * s[:, :4] >= -slack[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        for j, sj in enumerate((s0, s1)):  # sides s = s0, s1: r = -cs s / cr
            r[:, 4 + j] = rj = -cs * sj / cr
            s[:, 4 + j] = sj
            ok[:, 4 + j] = (cr != 0.0) & (rj >= r0) & (rj <= r1)
        for j, rj in enumerate((r0, r1)):  # sides r = r0, r1: s = -cr r / cs
            s[:, 6 + j] = sj = -cr * rj / cs
            r[:, 6 + j] = rj
            ok[:, 6 + j] = (cs != 0.0) & (sj >= s0) & (sj <= s1)
    z = np.full((k, 8, 2), np.nan)
    z[ok, 0] = r[ok]
    z[ok, 1] = s[ok]
    return z


class _ArcFrames:
    """The exact cone's frames as functions of the arc parameter phi (no
    Newton inversion), in the +y side's coordinates: u = (P - A) / |P - A|
    with P the frame arc (:func:`onefold_cad.geometry.frame.arc_points`)."""

    def __init__(self, folded: FoldedSheet) -> None:
        self.frame = folded.solution.frame
        self.apex = folded.apex

    def frames(self, phi: Array, curvature: bool = False) -> tuple[Array, ...]:
        """u, e, n ``(k, 3)`` at arc parameters ``phi``; and, if asked, the
        geodesic curvature k = det(v, v', v'') |v|^3 / |v x v'|^3 of u (the k
        of ``r - s k``) and its speed |du/dphi| = |v x v'| / |v|^2 ``(k,)``,
        with v = P - A."""
        v = arc_points(self.frame, phi) - self.apex
        dv = arc_tangents(self.frame, phi)
        w = np.sqrt(np.einsum("ij,ij->i", v, v))
        u = v / w[:, None]
        e = dv - np.einsum("ij,ij->i", dv, u)[:, None] * u
        e /= np.sqrt(np.einsum("ij,ij->i", e, e))[:, None]
        n = cross3(u, e)
        if not curvature:
            return u, e, n
        r = self.frame.radius
        b = math.radians(self.frame.beta)
        ddv = np.stack(
            [-r * np.cos(phi), -r * np.sin(phi) * math.cos(b), -r * np.sin(phi) * math.sin(b)],
            axis=-1,
        )
        vxdv = cross3(v, dv)
        det = np.einsum("ij,ij->i", vxdv, ddv)
        cross = np.sqrt(np.einsum("ij,ij->i", vxdv, vxdv))
        k = det * w**3 / cross**3
        return u, e, n, k, cross / w**2


class _Crease:
    """A SideMap whose crease frames are computed once (the mitre asks often)."""

    def __init__(self, side: SideMap) -> None:
        self.side = side
        self.lower = side.lower
        self.total = side.total
        self._frames = {end: side.crease_frame(end) for end in (0, 1)}

    def crease_frame(self, end: int) -> tuple[Array, Array, Array]:
        return self._frames[end]

    def edge_radius(self, theta: Array) -> Array:
        return self.side.edge_radius(theta)


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
        arc = _ArcFrames(folded)
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
                side = _Crease(SideMap(folded, lower=lower))
                for end in (0, 1):
                    verts, wall = self._block(side, end)
                    fixed += list(verts)
                    self.pieces.append(wall)
        return fixed

    def _sector(
        self, arc: _ArcFrames, lower: bool, t_lo: float, t_hi: float
    ) -> Callable[[Array], Array]:
        """Section corners of one sector (one sheet edge) of one side, as a
        function of phi."""
        cone = self.folded.solution.surface
        assert isinstance(cone, ExactCone)
        sheet, rho, tol = self.folded.sheet, self.hole, self._tol
        mirror = _MIRROR if lower else np.ones(3)
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
            z = _clipped_rectangle(np.full_like(r_out, rho), r_out, s0, s1, u[:, 1], n[:, 1], tol)
            pts = z[..., :1] * u[:, None, :] + z[..., 1:] * n[:, None, :]
            return pts * mirror

        return points

    def _block(self, side: _Crease, end: int) -> tuple[Array, Piece]:
        """The mitre block past crease half ``end`` of one side: the vertices
        of its polytope outside the hole's disk ``(m, 3)``, and the hole's wall
        as a piece over the distance d past the crease."""
        s0, s1 = self.s_range
        rho, tol = self.hole, self._tol
        mirror = _MIRROR if side.lower else np.ones(3)
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

    # -- mass -----------------------------------------------------------------
    @cached_property
    def mass_properties(self) -> tuple[float, Array]:
        """The sheet's measure (area for zero thickness, else volume; length^2
        or length^3) and its centre of mass ``(3,)`` (relative to the apex).

        The thickness and reference surface are the material's whichever
        body is written (the part that stands is the thick sheet); the relief
        hole is left out; for the exact model the solid's mitre blocks count."""
        total = 0.0
        moment = np.zeros(3)
        folded = self.folded
        cone = folded.solution.surface
        for lower in (False, True):
            mirror = _MIRROR if lower else np.ones(3)
            up, lo = folded.sheet._side_angles
            breaks = np.clip(np.asarray(lo if lower else up, dtype=float), 0.0, cone.total_angle)
            # graded towards both crease ends: the cut at the crease (thick
            # sheet), and a sheet edge passing near H (r = d / sin(theta + psi):
            # a peak of width psi at theta = 0 or pi, e.g. a needle's tip)
            grade = 0.5 ** np.arange(3, 31)
            near = breaks[1] * grade
            far = breaks[-1] - (breaks[-1] - breaks[-2]) * grade
            breaks = sorted_unique(np.concatenate([breaks, near, far]))
            if self.exact:
                # the rule runs in the arc's phi (no inversion at every node):
                # dtheta = |du/dphi| dphi, theta being u's arc length
                assert isinstance(cone, ExactCone)
                phi, weights = _sector_rule(cone.phi_of_theta(breaks))
                theta = np.clip(cone.theta_of_phi(phi), breaks[0], breaks[-1])
                u, _, n, k, speed = _ArcFrames(folded).frames(phi, curvature=True)
                weights = weights * speed
            else:  # planar triangles: no curvature within them
                theta, weights = _sector_rule(breaks)
                u, e = cone.frames(theta)
                n, k = cross3(u, e), np.zeros(len(theta))
            vals = weights @ self._slab_moments(theta, lower, u, n, k)
            total += vals[0]
            moment += vals[1:] * mirror
            if self.thickness > 0.0 and self.exact:
                side = _Crease(SideMap(folded, lower=lower))
                for end in (0, 1):
                    vol, mom = self._block_moments(side, end)
                    total += vol
                    moment += mom * mirror
        return total, moment / total

    def _slab_moments(self, theta: Array, lower: bool, u: Array, n: Array, k: Array) -> Array:
        """Per flat angle ``(k,)`` (ruling direction u, top normal n and
        curvature k there): the section's measure and first moment ``(k, 4)``
        (per radian), in the +y side's coordinates."""
        rho = self.hole
        r_out = self.folded.sheet.ray_lengths(-theta if lower else theta)
        if self.thickness <= 0.0:
            i0 = 0.5 * (r_out**2 - rho**2)
            i1 = (r_out**3 - rho**3) / 3.0
            return np.column_stack([i0, u * i1[:, None]])
        s0, s1 = self.s_range
        uy, ny = u[:, 1], n[:, 1]
        # y = r u_y + s n_y >= 0 cuts r at -s n_y / u_y (u_y > 0 inside a side):
        # split s where that bound passes rho and r_out
        with np.errstate(divide="ignore", invalid="ignore"):
            s_b = np.where(ny != 0.0, -rho * uy / ny, s0)
            s_e = np.where(ny != 0.0, -r_out * uy / ny, s0)
        cuts = np.column_stack([np.full_like(uy, s0), s_b, s_e, np.full_like(uy, s1)])
        cuts = np.sort(np.clip(cuts, s0, s1), axis=1)
        out = np.zeros((len(theta), 4))
        nodes, weights = _GL3  # exact: degree 4 in s
        for j in range(3):
            lo, half = cuts[:, j], 0.5 * (cuts[:, j + 1] - cuts[:, j])
            for x, w in zip(nodes, weights, strict=True):
                s = lo + half * (1.0 + x)
                with np.errstate(divide="ignore", invalid="ignore"):
                    r_y = np.where(uy > 0.0, -s * ny / uy, np.where(s * ny >= 0.0, -np.inf, np.inf))
                r_lo = np.minimum(np.maximum(rho, r_y), r_out)
                sk = s * k
                i0 = (r_out**2 - r_lo**2) / 2.0 - sk * (r_out - r_lo)
                i1 = (r_out**3 - r_lo**3) / 3.0 - sk * (r_out**2 - r_lo**2) / 2.0
                ww = w * half
                out[:, 0] += ww * i0
                first = (s[:, None] * n) * i0[:, None] + u * i1[:, None]
                out[:, 1:] += ww[:, None] * first
        return out

    def _block_moments(self, side: _Crease, end: int) -> tuple[float, Array]:
        """Volume and first moment ``(3,)`` of the kept part of the mitre block
        past crease half ``end`` (+y side's coordinates): x integrated exactly,
        Gauss-Legendre in d and s."""
        s0, s1 = self.s_range
        rho = self.hole
        u, e, n = side.crease_frame(end)
        away = -e if end == 0 else e
        length = float(side.edge_radius(np.array([0.0 if end == 0 else side.total]))[0])
        depth = mitre_depth(side, self.s_range)
        m, c = mitre_planes(side, s1 - s0)[end]
        (xs, ws), (xd, wd) = _GL8, _GL48
        vol = 0.0
        mom = np.zeros(3)
        for si, wsi in zip(s0 + (s1 - s0) * 0.5 * (1.0 + xs), ws * 0.5 * (s1 - s0), strict=True):
            # y = d away_y + s n_y >= 0 (u_y = 0 on the crease): a bound on d
            if away[1] < 0.0:
                d_hi = min(depth, max(si * n[1] / -away[1], 0.0))
            else:
                d_hi = depth if si * n[1] >= 0.0 else 0.0
            if d_hi <= 0.0:
                continue
            d = 0.5 * d_hi * (1.0 + xd)
            wdd = wd * 0.5 * d_hi
            xa = np.sqrt(np.maximum(rho * rho - d * d, 0.0))
            xb = np.full_like(d, length)
            # (p - A) . m = x (u.m) + d (away.m) + s (n.m) >= c
            um, c0 = float(u @ m), d * float(away @ m) + si * float(n @ m) - c
            if um > 0.0:
                xa = np.maximum(xa, -c0 / um)
            elif um < 0.0:
                xb = np.minimum(xb, -c0 / um)
            else:
                xb = np.where(c0 >= 0.0, xb, xa)
            span = np.maximum(xb - xa, 0.0)
            sq = np.where(span > 0.0, 0.5 * (xb**2 - xa**2), 0.0)
            base = d[:, None] * away + si * n
            vol += wsi * float(wdd @ span)
            mom += wsi * ((wdd * span) @ base + float(wdd @ sq) * u)
        return vol, mom


_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(16)
#: The rules of a slab's section in s and of a mitre block in s and d.
_GL3 = np.polynomial.legendre.leggauss(3)
_GL8 = np.polynomial.legendre.leggauss(8)
_GL48 = np.polynomial.legendre.leggauss(48)
#: Panels of the 16-point Gauss-Legendre rule per sector between vertex rays.
_PANELS = 8


def _sector_rule(breaks: Array) -> tuple[Array, Array]:
    """Nodes and weights of a composite 16-point Gauss-Legendre rule over the
    sectors between consecutive ``breaks`` (the edge radius is smooth within
    each): up to 8 panels per sector, in proportion to its width.

    The caller also grades the breaks towards the crease (halving the
    distance 28 times): the cut at the fold's plane of symmetry leaves only
    r > C / theta of a thick sheet's concave side there, a feature on every
    scale from the hole's radius to the sheet's edge; and a sheet edge that
    passes near H along the crease peaks there on the scale of its angle."""
    lo, hi = breaks[:-1], breaks[1:]
    keep = hi > lo
    lo, hi = lo[keep], hi[keep]
    panels = np.clip(np.ceil(_PANELS * (hi - lo) / np.max(hi - lo)), 1, _PANELS).astype(int)
    owner = np.repeat(np.arange(len(lo)), panels)
    step = ((hi - lo) / panels)[owner]
    first = np.concatenate([[0], np.cumsum(panels)[:-1]])
    a = lo[owner] + (np.arange(len(owner)) - first[owner]) * step
    half = 0.5 * step
    nodes = ((a + half)[:, None] + half[:, None] * _GL_NODES).ravel()
    weights = (half[:, None] * _GL_WEIGHTS).ravel()
    return nodes, weights
