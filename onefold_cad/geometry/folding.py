"""Fold a flat sheet onto the solved direction-surface (paper sections 3.3-3.4).

Flat fold frame: H at the origin, fold line on the x axis, the sheet's top
side facing +z. A flat point at polar coordinates (r, psi) folds to
``A + r * u(theta)`` with theta = psi on the +y side and theta = -psi on the
-y side (whose directions are the mirror image in the xz-plane). Distances
from H and angles at H are kept, so the fold is an isometry of the sheet.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.arc import arc_range
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.numeric import Array, cross3, sorted_unique
from onefold_cad.geometry.sheet import Sheet
from onefold_cad.geometry.solver import Solution

__all__ = ["CreaseHalf", "FoldedSheet", "fold"]

_MIRROR = np.array([1.0, -1.0, 1.0])
_TWO_PI = np.array(2.0 * math.pi)  # a 0-d array: cheaper than a float in a ufunc call


@dataclass(frozen=True)
class CreaseHalf:
    """One half of the fold line, from the apex to the sheet's edge.

    Attributes:
        name: 'plus_x' (towards +x in the flat fold frame) or 'minus_x'.
        length: its length, flat and folded alike (length).
        end_flat: ``(2,)`` its end on the flat sheet's boundary, fold frame.
        end_3d: ``(3,)`` that end on the folded form, fold frame.
        fold_angle_deg: the angle between the two sides' top normals along
            it (deg); 0 when flat, constant along the half.
        bend: 'UP' when the two sides rotate towards the flat sheet's top (+z)
            side (the top faces end inside the fold), 'DOWN' otherwise.
    """

    name: str
    length: float
    end_flat: Array
    end_3d: Array
    fold_angle_deg: float
    bend: str


@dataclass(frozen=True, eq=False)
class FoldedSheet:
    """The folded surface of a sheet, in the fold frame (apex above H).

    Attributes:
        solution: the solved direction-surface.
        sheet: the flat sheet.
        ruling_angles: ``(2,)`` tuple of ``(m_i,)`` flat angles theta (radians)
            of the rulings of the +y and -y sides, from +x (theta = 0) to -x
            (theta = pi): the paper model's division rays plus one through
            every polygon vertex; the exact model's vertex rays.
        rulings_flat: ``(m, 2, 2)`` the rulings on the flat sheet (from H).
        rulings_3d: ``(m, 2, 3)`` the rulings on the folded form (from A).
        crease: the two halves ('plus_x', 'minus_x').
        time_final_surface: wall time of the fold (s).

    The exact model's sampled boundary is derived on first access (and
    cached), so folding stays cheap when only rulings are needed; :func:`fold`
    fills in the paper model's boundary (the ruling ends) itself. What is
    measured on a fold lives elsewhere: its developability
    (:func:`onefold_cad.geometry.developability.developability`), how it stands
    (:func:`onefold_cad.geometry.placement.rest_form`).
    """

    solution: Solution
    sheet: Sheet
    ruling_angles: tuple[Array, Array]
    rulings_flat: Array
    rulings_3d: Array
    crease: tuple[CreaseHalf, CreaseHalf]
    time_final_surface: float
    boundary_samples: int = 4000

    @cached_property
    def boundary_flat(self) -> Array:
        """``(p, 2)`` closed flat boundary, counter-clockwise from the +x crossing:
        every vertex and ruling end (paper model, where the folded boundary is
        straight between them) or ``boundary_samples`` points (exact model)."""
        if isinstance(self.solution.surface, PaperFan):
            return self.rulings_flat[:, 1].take(ring_order(self.ruling_angles), axis=0)
        pts, _ = self.sheet.sample_boundary(self.sheet.perimeter / self.boundary_samples)
        return pts

    @cached_property
    def boundary_3d(self) -> Array:
        """``(p, 3)`` the boundary points folded (paper model: the ruling ends)."""
        if isinstance(self.solution.surface, PaperFan):
            return self.rulings_3d[:, 1].take(ring_order(self.ruling_angles), axis=0)
        return self.map_points(self.boundary_flat)

    @property
    def apex(self) -> Array:
        """The apex ``(3,)`` in the fold frame."""
        return self.solution.apex

    # -- the fold map -----------------------------------------------------
    def _polar(self, xy: ArrayLike) -> tuple[Array, Array, Array]:
        p = np.atleast_2d(np.asarray(xy, dtype=float))
        r = np.hypot(p[:, 0], p[:, 1])
        psi = np.arctan2(p[:, 1], p[:, 0])
        lower = psi < 0.0
        theta = np.clip(np.abs(psi), 0.0, self.solution.surface.total_angle)
        return r, theta, lower

    def map_points(self, xy: ArrayLike) -> Array:
        """Fold flat fold-frame points ``(k, 2)`` to 3D points ``(k, 3)``."""
        return self.apex + self.map_from_apex(xy)

    def map_from_apex(self, xy: ArrayLike) -> Array:
        """The folded points of flat points ``(k, 2)`` as vectors ``(k, 3)`` from
        the apex, ``r u``: what :meth:`map_points` adds to the apex, before the
        apex's magnitude rounds away the digits of a sheet much smaller than
        the frame (a sheet 1e-9 wide under an apex 100 high keeps 1e-5 of its
        width there, here all of it)."""
        r, theta, lower = self._polar(xy)
        u, _ = self.solution.surface.frames(theta)
        u = np.where(lower[:, None], u * _MIRROR, u)
        return r[:, None] * u

    def frames_at(self, xy: ArrayLike) -> tuple[Array, Array, Array]:
        """Ruling direction, in-surface direction of increasing flat polar
        angle, and top-side normal ``(k, 3)`` each, at flat points ``(k, 2)``."""
        _, theta, lower = self._polar(xy)
        u, e = self.solution.surface.frames(theta)
        n = cross3(u, e)
        u = np.where(lower[:, None], u * _MIRROR, u)
        e = np.where(lower[:, None], -e * _MIRROR, e)
        n = np.where(lower[:, None], n * _MIRROR, n)
        return u, e, n

    def unfold(self, points: ArrayLike) -> tuple[Array, Array]:
        """Inverse of :meth:`map_points` for the exact model.

        Each point ``(k, 3)`` is projected centrally from the apex onto the
        frame curve's plane, which names its ruling; the result is the flat
        point ``(k, 2)`` of that ruling at the point's distance along it, and
        the point's distance ``(k,)`` from the cone measured along the cone's
        normal on that ruling (first-order exact; lengths in the design unit).
        The projection is well-conditioned while the apex stands clear of the
        frame plane (its distance h cos(beta) well above the rounding of the
        points): beta near 90 deg puts the apex in that plane.

        Raises:
            NotImplementedError: for the paper model (use the exact model).
        """
        surface = self.solution.surface
        if not isinstance(surface, ExactCone):
            raise NotImplementedError("unfold is defined for the exact model only")
        p = np.atleast_2d(np.asarray(points, dtype=float))
        lower = p[:, 1] < 0.0
        q = np.where(lower[:, None], p * _MIRROR, p)
        w = q - self.apex
        frame = self.solution.frame
        b = math.radians(frame.beta)
        plane_n = np.array([0.0, -math.sin(b), math.cos(b)])
        s = -self.apex[2] * math.cos(b) / (w @ plane_n)
        hit = self.apex + s[:, None] * w
        d = hit @ np.array([0.0, math.cos(b), math.sin(b)])
        r0 = frame.radius * math.sin(math.radians(frame.alpha))
        phi = np.arctan2(d - r0, hit[:, 0] + frame.h_c)
        p0, p1 = arc_range(frame)
        phi = np.where(phi < p0 - 0.5 * (p0 + 2 * math.pi - p1), phi + 2 * math.pi, phi)
        phi = np.clip(phi, p0, p1)
        theta = surface.theta_of_phi(phi)
        u, e = surface.frames(theta)
        n = cross3(u, e)
        r = np.einsum("ij,ij->i", w, u)
        off = np.abs(np.einsum("ij,ij->i", w, n))
        psi = np.where(lower, -theta, theta)
        return np.stack([r * np.cos(psi), r * np.sin(psi)], axis=-1), off

    def normals(self, xy: ArrayLike) -> Array:
        """Unit top-side normals ``(k, 3)`` of the folded surface at flat points."""
        return self.frames_at(xy)[2]

    def mesh(self, angular: int = 180, radial: int = 24) -> tuple[Array, NDArray[np.int64]]:
        """A triangle mesh of the folded surface for previews.

        Returns ``(vertices (k, 3), faces (m, 3) int)``; both sides, the rays
        through every polygon vertex included, apex shared.
        """
        total = self.solution.surface.total_angle
        verts: list[Array] = [self.apex[None, :]]
        faces: list[NDArray[np.int64]] = []
        base = 1
        for side, vertex_theta in enumerate(self.ruling_angles):
            theta = sorted_unique(
                np.concatenate([np.linspace(0.0, total, angular + 1), vertex_theta])
            )
            psi = theta if side == 0 else -theta
            rho = self.sheet.ray_lengths(psi)
            s = np.arange(1, radial + 1) / radial
            # each ray is straight on the cone: map its end once, scale along it
            ends = rho[:, None] * np.stack([np.cos(psi), np.sin(psi)], axis=-1)
            u = self.map_points(ends) - self.apex
            u /= np.where(rho > 0.0, rho, 1.0)[:, None]
            nt = len(theta)
            ray = (s[None, :, None] * rho[:, None, None]) * u[:, None, :]
            verts.append((self.apex + ray).reshape(-1, 3))
            idx = base + np.arange(nt * radial).reshape(nt, radial)
            a, b = idx[:-1, :-1], idx[1:, :-1]
            c, d = idx[1:, 1:], idx[:-1, 1:]
            quads = np.stack([a, c, b, a, d, c], axis=-1).reshape(-1, 3)  # top side: u x e
            fan = np.stack([np.zeros(nt - 1, dtype=np.int64), idx[:-1, 0], idx[1:, 0]], axis=-1)
            tri = np.concatenate([fan, quads])
            faces.append(tri if side == 0 else tri[:, ::-1])
            base += nt * radial
        return np.concatenate(verts), np.concatenate(faces).astype(np.int64)


def ring_order(angles: tuple[Array, Array]) -> NDArray[np.int64]:
    """Indices of the ruling ends in boundary order (counter-clockwise from the +x
    crossing): the +y side's from +x to -x, then the -y side's back, without
    the two crease ends again."""
    mu, m = len(angles[0]), len(angles[0]) + len(angles[1])
    return np.concatenate((np.arange(mu), np.arange(m - 2, mu, -1)))


def _crease_half(
    name: str, length: float, end3: Array, u: list[float], e: list[float]
) -> CreaseHalf:
    """The crease half ``name`` from the ruling direction ``u`` and the in-surface
    direction ``e`` of the +y side on it (3-vectors as floats: few enough that
    plain Python beats numpy)."""
    n0 = u[1] * e[2] - u[2] * e[1]  # the +y side's normal n = u x e
    n1 = u[2] * e[0] - u[0] * e[2]
    n2 = u[0] * e[1] - u[1] * e[0]
    # the -y side's normal is the mirror image (n0, -n1, n2): the angle between
    # the two is twice that of n from the xz-plane
    angle = math.degrees(2.0 * math.atan2(abs(n1), math.hypot(n0, n2)))
    into = e[0] * n0 - e[1] * n1 + e[2] * n2  # the +y side, entered from the crease
    if name == "minus_x":
        into = -into
    end = np.array((length if name == "plus_x" else -length, 0.0))
    return CreaseHalf(name, length, end, end3.copy(), angle, "UP" if into > 0.0 else "DOWN")


def _fan_rays(
    surface: PaperFan, vertices: tuple[Array, Array], tol: float = 1e-12
) -> tuple[Array, Array, int]:
    """Both sides' ruling angles and the +y side's directions of their rays:
    the fan's division rays with every sheet vertex ray between them inserted
    (a vertex closer than ``tol`` to a division gives that division its
    flat angle). Returns
    ``(angles (m,), directions (m, 3), mu)``: the upper side's ``mu`` rays,
    then the lower side's, each from theta = 0 to pi."""
    assert surface.thetas is not None and surface.directions is not None
    fan, dirs = surface.thetas, surface.directions
    n = len(fan) - 1
    top = fan[n]  # pi up to rounding; the -x crease is set to pi exactly
    angles: list[Array | tuple[float]] = []
    pieces: list[Array | tuple[list[float]]] = []
    mu = 0
    for vert in vertices:
        start = 0
        inner = vert[1:-1]
        side = fan
        if len(inner):
            for v, k in zip(inner.tolist(), fan.searchsorted(inner).tolist(), strict=True):
                if k > n or top - v <= tol:  # at or past the last division
                    continue
                lo = fan.item(k - 1)
                near = k - 1 if v - lo <= tol else k if fan.item(k) - v <= tol else -1
                if near >= 0:
                    # the division's ruling ends at the vertex: its flat angle
                    # is the vertex's (its direction, 1e-12 rad off, is kept),
                    # so the ruling runs to the vertex, not to wherever the
                    # outline meets the division 1e-12 rad away (far, where an
                    # edge passes close to H)
                    if 0 < near < n:
                        side = side.copy() if side is fan else side
                        side[near] = v
                    continue
                angles += (side[start:k], (v,))
                pieces += (dirs[start:k], (surface.direction1(k - 1, v - lo),))
                start = k
        angles += (side[start:n], (math.pi,))
        pieces.append(dirs[start:])
        if not mu:
            mu = sum(map(len, angles))
    return np.concatenate(angles), np.concatenate(pieces), mu


def fold(solution: Solution, sheet: Sheet, *, boundary_samples: int = 4000) -> FoldedSheet:
    """Fold ``sheet`` onto the solved direction-surface.

    Args:
        solution: from :func:`onefold_cad.geometry.solver.solve`.
        sheet: the flat sheet in the fold frame.
        boundary_samples: exact model only: about how many points sample the
            boundary for :attr:`FoldedSheet.boundary_3d` and the metrics (the
            paper model's boundary is exact: straight between ruling ends).

    Returns:
        The :class:`FoldedSheet`: the rulings (flat and in 3D) and the crease
        computed now; the boundary (the paper model's: the ruling ends, in
        order) on first access.

    Raises:
        Nothing of its own: the sheet and the solution are checked when they
        are made (:class:`Sheet`, :func:`~onefold_cad.geometry.solver.solve`).
    """
    t0 = time.perf_counter()
    surface = solution.surface
    fan = isinstance(surface, PaperFan)
    if fan:
        assert isinstance(surface, PaperFan)
        theta, u, mu = _fan_rays(surface, sheet.side_angles)
        crease_frames = surface.crease_frames()
    else:
        vert_up, vert_lo = sheet.side_angles
        mu = len(vert_up)
        theta = np.concatenate((vert_up, vert_lo))
        u = surface.directions_at(theta)
        crease_frames = (surface.frame_at(0.0), surface.frame_at(surface.total_angle))
    m = len(theta)
    # the flat polar angles in [0, 2 pi): the -y side's run clockwise from +x
    ang = theta.copy()
    np.subtract(_TWO_PI, theta[mu:], out=ang[mu:])
    ang[mu] = 0.0
    rho, cos, sin = sheet.rays_at(ang)
    flat_r = np.zeros((m, 2, 2))
    np.multiply(rho, cos, out=flat_r[:, 1, 0])
    np.multiply(rho, sin, out=flat_r[:, 1, 1])
    h = solution.apex_height
    rulings3 = np.empty((m, 2, 3))
    rulings3[:, 0] = 0.0
    ends3 = rulings3[:, 1]
    np.multiply(rho[:, None], u, out=ends3)
    lower = ends3[mu:, 1]
    np.negative(lower, out=lower)  # the -y side: the mirror image
    rulings3[:, :, 2] += h  # from the apex (0, 0, h)
    xp, xm = sheet.crease_lengths
    crease = (
        _crease_half("plus_x", xp, ends3[0], *crease_frames[0]),
        _crease_half("minus_x", xm, ends3[mu - 1], *crease_frames[1]),
    )
    elapsed = time.perf_counter() - t0
    folded = FoldedSheet(
        solution,
        sheet,
        (theta[:mu], theta[mu:]),
        flat_r,
        rulings3,
        crease,
        elapsed,
        int(boundary_samples),
    )
    return folded
