"""How developable a fold is: the folded form measured against the flat sheet.

Every flat distance from H, every flat angle at H, every boundary length and
the area survive the fold (DESIGN.md, section 1); :func:`developability`
measures the differences on the folded surface, not on samples: the paper
model's boundary is straight between ruling ends and its triangles planar
(exact sums); the exact model's edge lengths and cone-patch areas are
extrapolated from chord sums along each folded edge to 1e-12
(:func:`edge_measures`). Lengths in the design unit, areas in unit^2, angles
in degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.geometry.arc import arc_range
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array, cross3, edge_lengths, sorted_unique

__all__ = ["Developability", "developability", "edge_measures"]


@dataclass(frozen=True)
class Developability:
    """Measured differences between the folded form and the flat sheet.

    Measured on the folded surface, not on samples: the paper model's
    boundary is straight between ruling ends and its triangles planar (exact
    sums); the exact model's edge lengths and cone-patch areas are
    extrapolated from chord sums along each folded edge to 1e-12
    (:func:`edge_measures`). Lengths in the design unit, areas in unit^2,
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


def _fan_area(ring: Array) -> float:
    """Area of the fan of triangles (apex, ring_i, ring_i+1) over a closed ring
    of vectors ``(p, 3)`` from the apex (:meth:`FoldedSheet.map_from_apex`:
    a sheet far smaller than its apex's height keeps its digits)."""
    a, b = ring, np.roll(ring, -1, axis=0)
    return float(np.sum(0.5 * np.linalg.norm(cross3(a, b), axis=1)))


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
    assert isinstance(cone, ExactCone)  # the paper's fan has planar pieces: no such rays
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


def edge_measures(folded: FoldedSheet) -> tuple[Array, Array]:
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
    edge_len = edge_lengths(v)
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


def developability(folded: FoldedSheet) -> Developability:
    """Developability measured on the folded result (see the module docstring)."""
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
        seg_flat = edge_lengths(b2)
        seg_3d = edge_lengths(b3)
        area3 = _fan_area(folded.map_from_apex(b2))
    else:  # the exact cone: integrated along each edge
        v = sheet.vertices
        seg_flat = edge_lengths(v)
        seg_3d, areas = edge_measures(folded)
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
