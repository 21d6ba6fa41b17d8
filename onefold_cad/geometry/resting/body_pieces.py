"""The pieces a body is made of beyond its sheet edges' sectors: the paper
fan's hole arcs and fixed points, the solid's mitre blocks (their polytope's
vertices and their hole walls), and a family's member as a piece of its own
(:mod:`onefold_cad.geometry.resting.body`). Points relative to the apex; lengths in
the design unit.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from itertools import combinations

import numpy as np

from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array, cross3
from onefold_cad.geometry.resting.body_families import Walls
from onefold_cad.geometry.resting.pieces import Family, Piece
from onefold_cad.geometry.thick.thick_map import CreaseFrames, mitre_depth, mitre_planes

__all__ = ["MitreFrame", "member_points", "mitre_blocks", "mitre_frames", "paper_pieces"]

#: The mirror image in the xz-plane (the -y side of the +y side).
_MIRROR = np.array([1.0, -1.0, 1.0])
#: The triples of a mitre block's eight planes (its polytope's vertices).
_TRIPLES = np.array(list(combinations(range(8), 3)))
#: The first six of them: x, d and s between bounds.
_BOX = np.array([[-1.0, 0, 0], [1.0, 0, 0], [0, -1.0, 0], [0, 1.0, 0], [0, 0, -1.0], [0, 0, 1.0]])


def member_points(family: Family, member: int) -> Callable[[Array], Array]:
    """Piece ``member`` of ``family`` alone: parameters -> corners."""

    def points(t: Array) -> Array:
        t = np.asarray(t, dtype=float)
        return family.points(np.full(len(t), member, dtype=np.int64), t)

    return points


def paper_pieces(folded: FoldedSheet, rho: float) -> tuple[list[Piece], list[Array]]:
    """The paper model's shell: straight between the ruling ends and the
    sheet's vertices, which are its extremes; the hole's edge is a circular
    arc per triangle.

    The vertices count on their own: a vertex within 1e-12 rad of a fan
    division has no ruling of its own (the division's is used), and where
    the edge beside it runs almost through H the division's ruling end
    lies measurably short of the vertex (1.5e-7 of the size for an edge
    passing 5e-10 of it from H): the folded corner, in that triangle's
    plane, can be the lowest point. Returns the pieces (the hole's arcs,
    radius ``rho``; none without a hole) and the fixed points (relative to
    the apex)."""
    corners = folded.map_points(folded.sheet.vertices) - folded.apex
    fixed = list(folded.rulings_3d[:, 1] - folded.apex) + list(corners)
    if rho <= 0.0:
        return [], [np.zeros(3), *fixed]
    pieces = []
    for side, thetas in enumerate(folded.ruling_angles):
        sign = 1.0 if side == 0 else -1.0
        for a, b in zip(thetas[:-1], thetas[1:], strict=True):
            arc = _paper_arc(folded, rho, sign)
            pieces.append(Piece(f"hole arc {side}", np.linspace(a, b, 4), arc, radius=rho))
    return pieces, fixed


def _paper_arc(folded: FoldedSheet, rho: float, sign: float) -> Callable[[Array], Array]:
    """The hole's edge on one side of the paper fan (``sign`` -1: the -y
    side) as a function of the flat angle."""

    def points(theta: Array) -> Array:
        psi = sign * theta
        flat = rho * np.stack([np.cos(psi), np.sin(psi)], axis=-1)
        return (folded.map_points(flat) - folded.apex)[:, None, :]

    return points


#: A mitre block's place: its side, its crease half (0, 1), the crease
#: ruling's u, the direction ``away`` from the side's sheet and the top
#: normal n ``(3,)``, the crease half's length, the block's depth past it
#: and its mitre plane ``(m (3,), c)`` (:func:`~onefold_cad.geometry.thick.thick_map.mitre_planes`).
MitreFrame = tuple[CreaseFrames, int, Array, Array, Array, float, float, Array, float]


def mitre_frames(
    sides: tuple[CreaseFrames, CreaseFrames], s_range: tuple[float, float]
) -> list[MitreFrame]:
    """The four mitre blocks' places (:data:`MitreFrame`; the +y side's
    crease halves 0 and 1, then the -y side's) for faces at ``s_range``."""
    s0, s1 = s_range
    out = []
    for side in sides:
        depth = mitre_depth(side, s_range)
        planes = mitre_planes(side, s1 - s0)
        lengths = side.edge_radius(np.array([0.0, side.total]))
        for end in (0, 1):
            u, e, n = side.crease_frame(end)
            m, c = planes[end]
            out.append((side, end, u, -e if end == 0 else e, n, float(lengths[end]), depth, m, c))
    return out


def mitre_blocks(
    frames: list[MitreFrame],
    rho: float,
    s_range: tuple[float, float],
    tol: float,
    walls: Walls,
) -> tuple[Array, list[Piece]]:
    """The mitre blocks at ``frames`` (:func:`mitre_frames`; faces at
    ``s_range``, hole radius ``rho``): the vertices of their polytopes outside
    the hole's disk ``(m, 3)`` (within ``tol``, length), and each block's
    hole wall as a piece over the distance d past the crease, a member of
    ``walls``. The four polytopes' vertices are solved together."""
    s0, s1 = s_range
    blocks = []
    for side, end, u, away, n, length, depth, m, c in frames:
        basis = np.stack([u, away, n], axis=1)  # (x, d, s) -> offset from the apex
        x_in = math.sqrt(max(rho * rho - depth * depth, 0.0))
        # the polytope {a . (x, d, s) <= b}
        a = np.empty((8, 3))
        a[:6] = _BOX
        a[6] = -basis[1]  # y >= 0
        a[7] = -(m @ basis)  # (p - A) . m >= c
        b = np.array([-x_in, length, 0.0, depth, -s0, s1, 0.0, -c])
        blocks.append((side, end, depth, basis, a, b))
    a = np.array([blk[4] for blk in blocks])  # (4, 8, 3)
    b = np.array([blk[5] for blk in blocks])  # (4, 8)
    # each triple of planes meets where Cramer's rule puts it (rows i, j, k)
    ai, aj, ak = (a[:, _TRIPLES[:, i]] for i in range(3))  # (4, 56, 3)
    jk, ki, ij = cross3(aj, ak), cross3(ak, ai), cross3(ai, aj)
    det = np.einsum("bij,bij->bi", ai, jk)
    bt = b[:, _TRIPLES]  # (4, 56, 3)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = (bt[..., :1] * jk + bt[..., 1:2] * ki + bt[..., 2:] * ij) / det[..., None]
    ok = np.abs(det) > 1e-12
    inside = ok & np.all(np.einsum("bkj,bij->bki", z, a) - b[:, None, :] <= tol, axis=2)
    inside &= z[..., 0] ** 2 + z[..., 1] ** 2 >= rho * rho - tol * rho
    verts, pieces = [], []
    reach = math.sqrt(rho * rho + max(s0 * s0, s1 * s1))  # x^2 + d^2 = rho^2 on the wall
    for k, (side, end, depth, basis, ak_, bk) in enumerate(blocks):
        mirror = _MIRROR if side.lower else np.ones(3)
        verts.append((z[k][inside[k]] @ basis.T) * mirror)
        member = walls.add(ak_[6:], bk[6:], basis, mirror)
        name = f"mitre {end} {'lower' if side.lower else 'upper'} hole wall"
        grid = np.linspace(0.0, depth, 24)
        fn = member_points(walls, member)
        pieces.append(Piece(name, grid, fn, 0.0, walls, member, reach))
    return np.concatenate(verts), pieces
