"""The exact model's pieces, evaluated many at once: a body's sheet-edge sectors
share one cone and one arc, its mitre walls one hole, so a search over many
pieces and brackets costs one numpy pass per family, not one per piece.

* :class:`Sectors`: per sheet edge (a member), the section corners of the
  side's slab (solid) or of the reference surface (shell) at arc parameters
  phi: the ruling direction u and top normal n from the arc
  (:class:`~onefold_cad.geometry.arc.ArcFrames`), the flat angle from the
  cone's node table (:meth:`~onefold_cad.geometry.cone.cone.ExactCone.theta_near`),
  kept within the edge's own flat angles, r from the hole to the sheet's
  edge, s across the thickness, cut at the plane y = 0
  (:func:`~onefold_cad.geometry.resting.pieces.clipped_rectangle`).
* :class:`Walls`: per mitre block (a member), the hole's wall as two corners
  (the s bounds of the block's polytope) over the distance d past the crease.

Both give ``(k, V, 3)`` corners (NaN where absent) for members ``(k,)`` and
parameters ``(k,)``, relative to the apex; the -y side's are mirrored in the
xz-plane. Lengths in the design unit.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.cone.cone import ExactCone
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.resting.pieces import clipped_rectangle
from onefold_cad.geometry.sheet import Sheet

__all__ = ["Sectors", "Walls"]


class Sectors:
    """The sheet edges' sectors of one exact fold (see the module docstring).

    Args:
        cone: the fold's cone (apex set).
        arc: its frames along the arc.
        sheet: the flat sheet.
        hole: the relief hole's radius (0: none).
        s_range: the faces' offsets (solid), or None (the shell).
        tol: the clipping tolerance (length).
    """

    def __init__(
        self,
        cone: ExactCone,
        arc: ArcFrames,
        sheet: Sheet,
        hole: float,
        s_range: tuple[float, float] | None,
        tol: float,
    ) -> None:
        self.cone, self.arc, self.sheet = cone, arc, sheet
        self.hole, self.s_range, self.tol = hole, s_range, tol
        self._rows: list[list[float]] = []
        self.lower = np.zeros(0, dtype=bool)
        self.t_lo = self.t_hi = np.zeros(0)

    def add(self, lower: bool, t_lo: float, t_hi: float, a: Array, b: Array) -> int:
        """A new member: the sheet edge from vertex ``a`` to ``b`` ``(2,)``, on
        the -y side (``lower``), between the flat angles ``t_lo`` and ``t_hi``
        of its side (``a``'s and ``b``'s, in either order); returns its index."""
        ex, ey = float(b[0] - a[0]), float(b[1] - a[1])
        ra, rb = float(np.hypot(*a)), float(np.hypot(*b))
        ta = abs(float(np.arctan2(a[1], a[0])))
        tb = abs(float(np.arctan2(b[1], b[0])))
        r_lo, r_hi = (ra, rb) if ta <= tb else (rb, ra)
        moment = float(a[0]) * ey - float(a[1]) * ex
        self._rows.append([float(lower), t_lo, t_hi, ex, ey, moment, r_lo, r_hi])
        rows = np.array(self._rows).T
        self.lower = rows[0] > 0.0
        self.t_lo, self.t_hi = rows[1], rows[2]
        self.edge = rows[3:]  # ex, ey, the moment a x e, the radii at t_lo and t_hi
        return len(self._rows) - 1

    def edge_radius(self, members: NDArray[np.int64], theta: Array) -> Array:
        """The distance from H to the members' edges along their flat angles
        ``theta`` (within their ranges): one line intersection, r = (a x e) /
        (d x e) for the ray's direction d, and the vertex's own distance at
        an end (an edge passing close to H would lose digits there)."""
        ex, ey, moment, r_lo, r_hi = self.edge[:, members]
        sin = np.sin(theta)
        sin[self.lower[members]] *= -1.0  # the -y side's polar angle is -theta
        # at an end of its range a ray may run along its edge (d x e = 0, an
        # edge pointing at H): there the quotient is inf or NaN, and the
        # vertex's own distance replaces it just below
        with np.errstate(divide="ignore", invalid="ignore"):
            r = moment / (np.cos(theta) * ey - sin * ex)
        r = np.where(theta <= self.t_lo[members], r_lo, r)
        return np.where(theta >= self.t_hi[members], r_hi, r)

    @property
    def corners(self) -> int:
        """Corners per section: 8 (solid), 2 (shell with a hole) or 1."""
        return 8 if self.s_range is not None else 2 if self.hole > 0.0 else 1

    def points(self, members: NDArray[np.int64], phi: Array) -> Array:
        """Section corners ``(k, V, 3)`` of ``members`` at arc parameters ``phi``."""
        return self.sections(members, phi)[0]

    def sections(
        self, members: NDArray[np.int64], phi: Array, box: bool = False
    ) -> tuple[Array, Array | None]:
        """:meth:`points`, and with ``box`` the corners ``(k, 4, 3)`` of each
        solid section's rectangle before the cut at y = 0 (r from the hole to
        the edge, s across the thickness: every point of the section lies
        within it; None for the shell)."""
        theta = np.minimum(
            np.maximum(self.cone.theta_near(phi), self.t_lo[members]), self.t_hi[members]
        )
        lower = self.lower[members]
        r_out = self.edge_radius(members, theta)
        u, _, n = self.arc.frames(phi)
        rho = self.hole
        rect = None
        # the -y side mirrored in the frames (a sign: the same products)
        flip = np.where(lower, -1.0, 1.0)
        if self.s_range is None:
            u[:, 1] *= flip
            out = r_out[:, None] * u
            return (np.stack([rho * u, out], axis=1) if rho > 0.0 else out[:, None, :]), None
        s0, s1 = self.s_range
        inner = np.full_like(r_out, rho)
        z = clipped_rectangle(inner, r_out, s0, s1, u[:, 1], n[:, 1], self.tol)
        u[:, 1] *= flip
        n[:, 1] *= flip
        out = np.empty((*z.shape[:2], 3))  # r u + s n, a coordinate at a time (faster)
        zr, zs = z[..., 0], z[..., 1]
        for j in range(3):
            np.multiply(zr, u[:, j : j + 1], out=out[..., j])
            out[..., j] += zs * n[:, j : j + 1]
        if box:
            rect = np.empty((len(r_out), 4, 3))
            for j, (r, s) in enumerate(((inner, s0), (r_out, s0), (r_out, s1), (inner, s1))):
                np.multiply(r[:, None], u, out=rect[:, j])
                rect[:, j] += s * n
        return out, rect


class Walls:
    """The mitre blocks' hole walls of one solid (see the module docstring).

    Args:
        hole: the relief hole's radius.
        s_range: the faces' offsets.
        tol: the tolerance of the s bounds (length).
    """

    def __init__(self, hole: float, s_range: tuple[float, float], tol: float) -> None:
        self.hole, self.s_range, self.tol = hole, s_range, tol
        self._rows: list[Array] = []
        self._offs: list[Array] = []
        self._basis: list[Array] = []
        self._mirror: list[Array] = []

    def add(self, rows: Array, offsets: Array, basis: Array, mirror: Array) -> int:
        """A new member: the block's two cutting constraints ``rows (2, 3) .
        (x, d, s) <= offsets (2,)``, its ``basis (3, 3)`` ((x, d, s) -> offset
        from the apex) and ``mirror (3,)``; returns its index."""
        self._rows.append(np.asarray(rows, dtype=float))
        self._offs.append(np.asarray(offsets, dtype=float))
        self._basis.append(np.asarray(basis, dtype=float))
        self._mirror.append(np.asarray(mirror, dtype=float))
        self.rows, self.offs = np.array(self._rows), np.array(self._offs)
        self.basis, self.mirror = np.array(self._basis), np.array(self._mirror)
        return len(self._rows) - 1

    def points(self, members: NDArray[np.int64], d: Array) -> Array:
        """The wall's corners ``(k, 2, 3)`` of ``members`` at distances ``d``
        past the crease (NaN where the block has none)."""
        rho, tol = self.hole, self.tol
        s0, s1 = self.s_range
        x = np.sqrt(np.maximum(rho * rho - d * d, 0.0))
        lo, hi = np.full_like(d, s0), np.full_like(d, s1)
        rows, offs = self.rows[members], self.offs[members]
        with np.errstate(divide="ignore", invalid="ignore"):
            for j in (0, 1):
                # rows . (x, d, s) <= off: a bound on s
                row = rows[:, j]
                rest = offs[:, j] - row[:, 0] * x - row[:, 1] * d
                bound = rest / row[:, 2]
                hi = np.where(row[:, 2] > 0.0, np.minimum(hi, bound), hi)
                lo = np.where(row[:, 2] < 0.0, np.maximum(lo, bound), lo)
                hi = np.where((row[:, 2] == 0.0) & (rest < -tol), -np.inf, hi)
        ok = lo <= hi + tol
        z = np.empty((len(d), 2, 3))
        z[:, :, 0] = x[:, None]
        z[:, :, 1] = d[:, None]
        z[:, 0, 2], z[:, 1, 2] = lo, hi
        pts = np.einsum("kvj,kij->kvi", z, self.basis[members]) * self.mirror[members][:, None, :]
        pts[~ok] = np.nan
        return pts
