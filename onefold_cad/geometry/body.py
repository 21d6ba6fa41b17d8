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

from onefold_cad.choices import Body
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body_families import Sectors, Walls
from onefold_cad.geometry.body_pieces import (
    MitreFrame,
    member_points,
    mitre_blocks,
    mitre_frames,
    paper_pieces,
)
from onefold_cad.geometry.body_samples import Sampled
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.edge_samples import edge_samples
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.pieces import Piece, zoom_min
from onefold_cad.geometry.thick_map import CreaseFrames, SideMap

__all__ = ["BODIES", "MIRROR", "FoldedBody"]

#: The bodies a form can be written as (the values of :class:`~onefold_cad.choices.Body`).
BODIES = tuple(b.value for b in Body)
#: The mirror image in the xz-plane (the -y side of the +y side).
MIRROR = np.array([1.0, -1.0, 1.0])
#: Sample points of all pieces together, spread by flat edge length.
_SAMPLES = 1200
#: Largest step in the flat angle between samples of an edge (radians).
_MAX_ANGLE_STEP = math.pi / 180


class FoldedBody(Sampled):
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

    def __init__(
        self, folded: FoldedSheet, material: Material | None = None, kind: Body = Body.SHELL
    ):
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
        # each edge sampled evenly on the flat sheet and evenly in its flat
        # angle (once per sheet, :mod:`.edge_samples`); the pieces run in phi
        edges = edge_samples(sheet, _SAMPLES, _MAX_ANGLE_STEP)
        flat_params = [(e.a, e.b) for e in edges]
        thetas = [e.theta.copy() for e in edges]
        steps = [e.step for e in edges]
        # the samples' arc parameters from the cone's table (to ~1e-10 rad:
        # where a sample lies need not be exact), the edge ends' exact: the
        # vertex rays' (the sheet's corners are extremes as they are)
        cuts = np.cumsum([len(t) for t in thetas])[:-1]
        phis = np.split(cone.phi_near(np.concatenate(thetas)), cuts)
        for k, ((a, b), theta, phi) in enumerate(zip(flat_params, thetas, phis, strict=True)):
            lower = bool(a[1] + b[1] < 0.0)
            for i in (0, -1):
                theta[i], phi[i] = self._vertex_ray(lower, float(theta[i]))
            inner = phi[1:-1]
            np.maximum(inner, min(phi[0], phi[-1]), out=inner)
            np.minimum(inner, max(phi[0], phi[-1]), out=inner)
            grid = np.maximum.accumulate(phi if phi[-1] >= phi[0] else phi[::-1])
            t_lo, t_hi = float(min(theta[0], theta[-1])), float(max(theta[0], theta[-1]))
            member = sectors.add(lower, t_lo, t_hi, a, b)
            fn = member_points(sectors, member)
            self.pieces.append(Piece(f"edge {k}", grid, fn, steps[k], sectors, member))
        if solid:
            walls = Walls(self.hole, self.s_range, self._tol)
            verts, pieces = mitre_blocks(
                self.mitre_frames, self.hole, self.s_range, self._tol, walls
            )
            fixed += list(verts)
            self.pieces += pieces
        return fixed

    @cached_property
    def crease_sides(self) -> tuple[CreaseFrames, CreaseFrames]:
        """The exact model's maps of the +y and the -y side (their crease
        frames, for the mitre blocks and their mass)."""
        return tuple(CreaseFrames(SideMap(self.folded, lower=lower)) for lower in (False, True))  # type: ignore[return-value]

    @cached_property
    def mitre_frames(self) -> list[MitreFrame]:
        """The solid's four mitre blocks' places (:func:`~.body_pieces.mitre_frames`)."""
        return mitre_frames(self.crease_sides, self.s_range)

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
