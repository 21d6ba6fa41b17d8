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
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.cone import ExactCone, PaperFan
from onefold_cad.geometry.frame import arc_range
from onefold_cad.geometry.sheet import Sheet
from onefold_cad.geometry.solver import Solution
from onefold_cad.geometry.validate import cross3, sorted_unique

if TYPE_CHECKING:  # placement builds on this module
    from onefold_cad.geometry.placement import RestingPlacement

__all__ = ["CreaseHalf", "Developability", "FoldedSheet", "fold"]

Array = NDArray[np.float64]
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


@dataclass(frozen=True)
class Developability:
    """Measured differences between the folded form and the flat sheet.

    Measured on the folded surface, not on samples: the paper model's
    boundary is straight between ruling ends and its triangles planar (exact
    sums); the exact model's edge lengths and cone-patch areas are
    extrapolated from chord sums along each folded edge to 1e-12
    (:func:`_edge_measures`). Lengths in the design unit, areas in unit^2,
    angles in degrees.
    """

    max_ruling_length_error: float
    max_boundary_segment_error: float
    boundary_length_flat: float
    boundary_length_3d: float
    area_flat: float
    area_3d: float
    angle_sum_deg: float

    @property
    def boundary_length_rel_error(self) -> float:
        """|3D - flat| / flat boundary length."""
        return abs(self.boundary_length_3d - self.boundary_length_flat) / self.boundary_length_flat

    @property
    def area_rel_error(self) -> float:
        """|3D - flat| / flat area."""
        return abs(self.area_3d - self.area_flat) / self.area_flat


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

    The exact model's sampled boundary, the metrics and the resting placement
    are derived on first access (and cached), so folding stays cheap when only
    rulings are needed; :func:`fold` fills in the paper model's boundary (the
    ruling ends) itself.
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
            return self.rulings_flat[:, 1].take(_ring(self.ruling_angles), axis=0)
        pts, _ = self.sheet.sample_boundary(self.sheet.perimeter / self.boundary_samples)
        return pts

    @cached_property
    def boundary_3d(self) -> Array:
        """``(p, 3)`` the boundary points folded (paper model: the ruling ends)."""
        if isinstance(self.solution.surface, PaperFan):
            return self.rulings_3d[:, 1].take(_ring(self.ruling_angles), axis=0)
        return self.map_points(self.boundary_flat)

    @cached_property
    def metrics(self) -> Developability:
        """Developability measured on the folded result."""
        return _measure(self)

    @cached_property
    def resting(self) -> RestingPlacement:
        """The placement that stands the zero-thickness shell on the ground
        (z = 0), without a relief hole: :func:`~onefold_cad.geometry.placement.rest_form`
        (which also places a thick sheet, its solid, or a shell with a hole)."""
        from onefold_cad.geometry.placement import rest_form

        return rest_form(self)

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
        r, theta, lower = self._polar(xy)
        u, _ = self.solution.surface.frames(theta)
        u = np.where(lower[:, None], u * _MIRROR, u)
        return self.apex + r[:, None] * u

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
            pts = (s[None, :, None] * rho[:, None, None]) * np.stack(
                [np.cos(psi), np.sin(psi)], axis=-1
            )[:, None, :]
            nt = len(theta)
            verts.append(self.map_points(pts.reshape(-1, 2)))
            idx = base + np.arange(nt * radial).reshape(nt, radial)
            a, b = idx[:-1, :-1], idx[1:, :-1]
            c, d = idx[1:, 1:], idx[:-1, 1:]
            quads = np.stack([a, c, b, a, d, c], axis=-1).reshape(-1, 3)  # top side: u x e
            fan = np.stack([np.zeros(nt - 1, dtype=np.int64), idx[:-1, 0], idx[1:, 0]], axis=-1)
            tri = np.concatenate([fan, quads])
            faces.append(tri if side == 0 else tri[:, ::-1])
            base += nt * radial
        return np.concatenate(verts), np.concatenate(faces).astype(np.int64)


def _ring(angles: tuple[Array, Array]) -> NDArray[np.int64]:
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


def _fan_area(apex: Array, ring: Array) -> float:
    """Area of the fan of triangles (apex, ring_i, ring_i+1) over a closed ring."""
    a, b = ring, np.roll(ring, -1, axis=0)
    return float(np.sum(0.5 * np.linalg.norm(cross3(a - apex, b - apex), axis=1)))


#: Romberg levels (each halving the chords) before an edge piece that does not
#: converge is cut in two, and the relative change at which it stops.
_ROMBERG_LEVELS = 8
_ROMBERG_RTOL = 1e-12
#: At most this many pieces per fold (each up to 1025 points).
_MAX_PIECES = 256


def _sharp_rays(folded: FoldedSheet) -> Array:
    """Flat polar angles ``(k,)`` (radians, both sides: +theta and -theta) of
    the exact cone's rulings where it bends most sharply: those through the
    frame arc's points whose tangent line passes through the apex's
    projection A' onto the frame plane. There u = (P - A) / |P - A| stalls
    (|du/dphi| is the apex's distance from that tangent line over |P - A|^2):
    as beta nears 90 deg the apex nears the plane and the cone folds back on
    itself along such a ruling, a crease of 180 deg whose width in theta
    shrinks like (h cos beta)^2. Chords that straddle it lose up to twice
    their length, so the edge measures break there.

    In the frame plane (x along the f-line, d across it) the arc is
    P(phi) = C + R (cos phi, sin phi), C = (-h_c, R sin alpha), and
    A' = (0, h sin beta); P - A' is tangent at cos(phi - psi) = -R / |C - A'|,
    psi the direction of C - A' (no such point when A' lies inside the
    circle)."""
    frame = folded.solution.frame
    cone = folded.solution.surface
    r = frame.radius
    wx = -frame.h_c
    wd = r * math.sin(math.radians(frame.alpha)) - float(folded.apex[2]) * math.sin(
        math.radians(frame.beta)
    )
    dist = math.hypot(wx, wd)
    if dist <= r:
        return np.zeros(0)
    psi = math.atan2(wd, wx)
    turn = math.acos(-r / dist)
    p0, p1 = arc_range(frame)
    phi = np.array([psi - turn, psi + turn])
    phi = (phi - p0) % (2.0 * math.pi) + p0  # into [p0, p0 + 2 pi)
    phi = phi[phi <= p1]
    theta = cone.theta_of_phi(phi) if len(phi) else np.zeros(0)
    theta = theta[(theta > 0.0) & (theta < cone.total_angle)]
    return np.concatenate([theta, -theta])


def _graded(marks: list[float], at: float, start: float) -> None:
    """Append to ``marks`` the fractions at ± start, 2 start, 4 start ... (< 1)
    around ``at``."""
    step = max(start, 1e-12)
    while step < 1.0:
        marks += [at - step, at + step]
        step *= 2.0


def _edge_pieces(a: Array, b: Array, rays: Array | None = None) -> Array:
    """Break points (fractions of the edge from ``a`` to ``b``) graded towards
    the edge's point nearest H: the fold map varies on the scale of the
    distance from H, so each piece is smooth on its own length. The edge is
    also broken where it crosses a ray from H at a flat polar angle in
    ``rays`` (:func:`_sharp_rays`), with pieces graded towards the crossing
    from 1e-12 of the edge up."""
    d = b - a
    length2 = float(d @ d)
    foot = float(np.clip(-(a @ d) / length2, 0.0, 1.0))
    near = float(np.hypot(*(a + foot * d))) / math.sqrt(length2)  # distance from H / length
    marks = [0.0, 1.0, foot]
    _graded(marks, foot, near)
    for ray in [] if rays is None else rays.tolist():
        c, s = math.cos(ray), math.sin(ray)
        across = d[0] * s - d[1] * c  # d x (cos, sin)
        if across == 0.0:
            continue
        t = -(a[0] * s - a[1] * c) / across  # a + t d on the ray's line
        if 0.0 < t < 1.0 and (a[0] + t * d[0]) * c + (a[1] + t * d[1]) * s > 0.0:
            marks.append(t)
            _graded(marks, t, 0.0)
    m = sorted_unique(np.clip(marks, 0.0, 1.0))
    return m[np.concatenate([[True], np.diff(m) > 1e-15])]


@dataclass
class _Piece:
    """A piece of a sheet edge being measured: its flat ends, the folded
    points at its current chords and the Romberg rows so far."""

    edge: int
    p: Array
    q: Array
    pts: Array
    rows: list[list[Array]]


def _romberg_row(piece: _Piece, apex: Array, floor: Array) -> bool:
    """Add the chord sum and chord-fan area at the piece's current points to
    its Romberg table; True when the last two extrapolations agree to 1e-12
    or to ``floor`` ``(2,)`` (length, area: the rounding of the whole)."""
    p = piece.pts
    chords = float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())
    fan = float(0.5 * np.linalg.norm(cross3(p[:-1] - apex, p[1:] - apex), axis=1).sum())
    row = [np.array([chords, fan])]
    for j, prev in enumerate(piece.rows[-1] if piece.rows else []):
        row.append(row[j] + (row[j] - prev) / (4.0 ** (j + 1) - 1.0))
    piece.rows.append(row)
    if len(piece.rows) < 3:
        return False
    last, before = piece.rows[-1][-1], piece.rows[-2][-1]
    return bool(np.all(np.abs(last - before) <= np.maximum(_ROMBERG_RTOL * np.abs(last), floor)))


def _edge_measures(folded: FoldedSheet) -> tuple[Array, Array]:
    """Per sheet edge: the length of its fold on the surface and the area of
    the cone patch between it and the apex, each extrapolated (Romberg) from
    chord sums and chord-fan areas of the folded edge at halving steps until
    two estimates agree to 1e-12 (the chord errors run in even powers of the
    step on each smooth piece of the edge). Pieces are graded towards the
    edge's point nearest H and towards its crossings with the rulings along
    which the cone bends most sharply (:func:`_sharp_rays`: a fold of 180 deg
    as beta nears 90 deg, which no chord may straddle); a piece that does not converge in
    :data:`_ROMBERG_LEVELS` halvings (the cone bends sharply there, as beta
    nears 90 deg) is cut in two and measured again, down to 1e-9 of its edge
    and :data:`_MAX_PIECES` pieces in all."""
    v = folded.sheet.vertices
    apex = folded.apex
    lengths, areas = np.zeros(len(v)), np.zeros(len(v))
    frac = np.arange(9) / 8.0

    def start(edge: int, p: Array, q: Array) -> _Piece:
        return _Piece(edge, p, q, p + frac[:, None] * (q - p), [])

    live: list[_Piece] = []
    rays = _sharp_rays(folded)
    for k in range(len(v)):
        a, b = v[k], v[(k + 1) % len(v)]
        m = _edge_pieces(a, b, rays)
        ends = zip(m[:-1], m[1:], strict=True)
        live += [start(k, a + m0 * (b - a), a + m1 * (b - a)) for m0, m1 in ends]
    mapped = folded.map_points(np.concatenate([c.pts for c in live]))
    for c, pts in zip(live, np.split(mapped, len(live)), strict=True):
        c.pts = pts
    edge_len = np.linalg.norm(np.roll(v, -1, axis=0) - v, axis=1)
    # below 1e-14 of the perimeter, and of the perimeter times the size for the
    # fan of long thin triangles from the apex, the changes are rounding
    perimeter = float(edge_len.sum())
    floor = 1e-14 * perimeter * np.array([1.0, folded.sheet.size])
    pieces = len(live)
    while live:
        halve: list[_Piece] = []
        split: list[_Piece] = []
        for c in live:
            if _romberg_row(c, apex, floor):
                lengths[c.edge] += c.rows[-1][-1][0]
                areas[c.edge] += c.rows[-1][-1][1]
            elif len(c.rows) < _ROMBERG_LEVELS:
                halve.append(c)
            elif pieces < _MAX_PIECES and np.linalg.norm(c.q - c.p) > 1e-9 * edge_len[c.edge]:
                split.append(c)
                pieces += 1
            else:  # as fine as it gets: keep the best estimate
                lengths[c.edge] += c.rows[-1][-1][0]
                areas[c.edge] += c.rows[-1][-1][1]
        fresh = [
            start(c.edge, *ends)
            for c in split
            for ends in ((c.p, 0.5 * (c.p + c.q)), (0.5 * (c.p + c.q), c.q))
        ]
        # one map call for every new point: the midpoints of the pieces
        # halved, and the points of the new halves
        mids = []
        for c in halve:
            n = len(c.pts) - 1
            mids.append(c.p + ((np.arange(n) + 0.5) / n)[:, None] * (c.q - c.p))
        mids += [c.pts for c in fresh]
        if not mids:
            break
        cuts = np.cumsum([len(x) for x in mids])[:-1]
        new = np.split(folded.map_points(np.concatenate(mids)), cuts)
        for c, m in zip(halve, new[: len(halve)], strict=True):
            both = np.empty((2 * len(m) + 1, 3))
            both[0::2], both[1::2] = c.pts, m
            c.pts = both
        for c, m in zip(fresh, new[len(halve) :], strict=True):
            c.pts = m
        live = halve + fresh
    return lengths, areas


def _measure(folded: FoldedSheet) -> Developability:
    sheet = folded.sheet
    flat_r, rulings3 = folded.rulings_flat, folded.rulings_3d
    ruling_err = float(
        np.max(
            np.abs(
                np.linalg.norm(rulings3[:, 1] - rulings3[:, 0], axis=1)
                - np.linalg.norm(flat_r[:, 1] - flat_r[:, 0], axis=1)
            )
        )
    )
    if isinstance(folded.solution.surface, PaperFan):
        # planar triangles between the ruling ends, straight edges between them
        b2, b3 = folded.boundary_flat, folded.boundary_3d
        seg_flat = np.linalg.norm(np.roll(b2, -1, axis=0) - b2, axis=1)
        seg_3d = np.linalg.norm(np.roll(b3, -1, axis=0) - b3, axis=1)
        area3 = _fan_area(folded.apex, b3)
    else:  # the exact cone: integrated along each edge
        v = sheet.vertices
        seg_flat = np.linalg.norm(np.roll(v, -1, axis=0) - v, axis=1)
        seg_3d, areas = _edge_measures(folded)
        area3 = float(np.sum(areas))
    return Developability(
        max_ruling_length_error=ruling_err,
        max_boundary_segment_error=float(np.max(np.abs(seg_3d - seg_flat))),
        boundary_length_flat=sheet.perimeter,
        boundary_length_3d=float(np.sum(seg_3d)),
        area_flat=sheet.area,
        area_3d=area3,
        angle_sum_deg=folded.solution.angle_sum_deg,
    )


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
        order), the metrics and the resting placement on first access.
    """
    t0 = time.perf_counter()
    surface = solution.surface
    fan = isinstance(surface, PaperFan)
    if fan:
        assert isinstance(surface, PaperFan)
        theta, u, mu = _fan_rays(surface, sheet._side_angles)
        crease_frames = surface.crease_frames()
    else:
        vert_up, vert_lo = sheet._side_angles
        mu = len(vert_up)
        theta = np.concatenate((vert_up, vert_lo))
        u = surface.directions_at(theta)
        crease_frames = (surface.frame_at(0.0), surface.frame_at(surface.total_angle))
    m = len(theta)
    # the flat polar angles in [0, 2 pi): the -y side's run clockwise from +x
    ang = theta.copy()
    np.subtract(_TWO_PI, theta[mu:], out=ang[mu:])
    ang[mu] = 0.0
    rho, cos, sin = sheet._rays_at(ang)
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
