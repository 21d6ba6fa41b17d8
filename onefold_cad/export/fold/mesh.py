"""The FOLD file's mesh: a paper fan's crease pattern triangulated for simulators.

A paper fan is planar between two neighbouring division rays (a *wedge*);
only the division rays (and the two crease halves among them) fold. The
rays the fold adds through polygon vertices lie inside a wedge and fold
nothing, so the mesh leaves them out (they would only cut the wedge into
slivers where they pass close to a division ray) and keeps the polygon
vertices as corners of the outline. Each wedge, clipped to the sheet (and
to the relief hole), is then triangulated with Shewchuk's Triangle
(constrained, quality): the division rays, the outline and the hole's
edges are segments no triangle crosses; Triangle may split them and add
points inside a wedge. Every vertex is folded by the fan's own map
(:meth:`FoldedSheet.map_points`), so a vertex on a division ray stays on
that ray and one inside a wedge stays in the wedge's plane: every face is
planar in the folded frame, the folded frame is isometric to the crease
pattern, and the dihedral angle across an edge on a division ray is that
ray's fold angle (:func:`onefold_cad.geometry.fan_folds.signed_fold_angles`),
0 across every other interior edge.

The relief hole (a circle about H) is cut as the polygon of its crossings
with the division rays only: every ray must end on the hole's boundary (a
fold cannot stop inside a face), and a vertex more would only shorten an
edge of it.

The bounds (see docs/formats.md, "NAME.fold"): Triangle is asked for no
angle below :data:`MIN_FACE_ANGLE_DEG`; it cannot raise an angle the input
makes itself: a wedge's apex angle at H (its ``gamma``), the angle at which
a ray or the hole meets the outline, a corner of the sheet, the angles
between the hole's edge and the rays. :func:`mesh_limits` names the
smallest of those, so a caller can tell the mesher's angles from the
design's. Lengths are in the design's unit, points in the fold frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.fan_folds import on_division_rays, ring_angles, signed_fold_angles
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = [
    "FACET",
    "HOLE",
    "MIN_EDGE",
    "MAX_STEINER",
    "MIN_FACE_ANGLE_DEG",
    "OUTLINE",
    "QUALITY_CAP_DEG",
    "RAY",
    "STEINER_PER_VERTEX",
    "FoldMesh",
    "division_rays",
    "face_angles_deg",
    "fold_mesh",
    "mesh_limits",
    "mesh_quality",
]

#: The smallest face angle the mesh may have (deg), where the design allows
#: it; see docs/formats.md.
MIN_FACE_ANGLE_DEG = 1.0
#: The largest quality (smallest angle, deg) Triangle is asked for: it is
#: asked for the design's own smallest angle (:func:`mesh_limits`), no more
#: than this, and no less than :data:`MIN_FACE_ANGLE_DEG`.
QUALITY_CAP_DEG = 20.0
#: The shortest edge the mesh may have, relative to the sheet's size
#: (:attr:`Sheet.size`), where the design allows it; see docs/formats.md.
MIN_EDGE = 1e-5

#: The most points Triangle may add to the input's (Steiner points), at least
#: this many and :data:`STEINER_PER_VERTEX` per input vertex: its quality
#: refinement of a wedge far thinner than it is long (a sliver of a sheet,
#: 1.4e-6 by 125 mm) would otherwise add points without end (4.9 GB after
#: two minutes); the shipped templates use 30 to 200.
MAX_STEINER = 20_000
STEINER_PER_VERTEX = 20

#: Edge kinds (``FoldMesh.edge_kind``).
OUTLINE, HOLE, RAY, FACET = "outline", "hole", "ray", "facet"
_OUTLINE_MARK, _HOLE_MARK, _RAY_MARK = 1, 2, 10


@dataclass(frozen=True, eq=False)
class FoldMesh:
    """The triangulated crease pattern of a paper fan and its folded vertices.

    Attributes:
        flat: ``(v, 2)`` the vertices on the flat sheet (fold frame; H is
            vertex 0 when there is no hole).
        folded: ``(v, 3)`` the same vertices folded (fold frame).
        faces: ``(f, 3)`` int, counter-clockwise on the flat sheet (seen from +z).
        edges: ``(e, 2)`` int, every edge of the faces once.
        edge_kind: ``(e,)`` 'outline', 'hole' (one face), 'ray' (on a
            division ray: a fold) or 'facet' (inside a wedge: flat).
        edge_ray: ``(e,)`` int, for a 'ray' edge the index of its ray in
            :attr:`ray_theta`, else -1.
        ray_theta: ``(n,)`` the division rays' flat polar angles (radians,
            in [0, 2 pi), counter-clockwise from the +x crease half).
        ray_angle_deg: ``(n,)`` each ray's signed fold angle (deg, valley
            positive; the crease halves' as the fan gives them).
        minus_x: the index in :attr:`ray_theta` of the -x crease half.
    """

    flat: Array
    folded: Array
    faces: NDArray[np.int64]
    edges: NDArray[np.int64]
    edge_kind: NDArray[np.object_]
    edge_ray: NDArray[np.int64]
    ray_theta: Array
    ray_angle_deg: Array
    minus_x: int


def face_angles_deg(points: Array, faces: NDArray[np.int64]) -> Array:
    """``(f, 3)`` the interior angles (deg) of triangles ``faces`` over
    ``points`` ``(v, 2)`` or ``(v, 3)``, at their vertices in order."""
    p = points[faces]
    out = np.empty(faces.shape)
    for i in range(3):
        u = p[:, (i + 1) % 3] - p[:, i]
        w = p[:, (i + 2) % 3] - p[:, i]
        if p.shape[2] == 2:
            cross = np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0])
        else:
            cross = np.linalg.norm(np.cross(u, w), axis=1)
        out[:, i] = np.degrees(np.arctan2(cross, np.einsum("ij,ij->i", u, w)))
    return out


def division_rays(fan: FoldedSheet) -> tuple[Array, NDArray[np.int64], Array, int]:
    """The division rays: their angles, their ends' indices in the outline
    ring (:attr:`FoldedSheet.boundary_flat`), their signed fold angles, and
    the index of the -x crease half among them."""
    theta, minus_x = ring_angles(fan)
    division = on_division_rays(theta, fan)
    division[0] = division[minus_x] = True
    index = np.flatnonzero(division)
    angle = signed_fold_angles(fan.apex, fan.boundary_3d[index])
    phi = np.where(np.arange(len(theta)) > minus_x, 2.0 * math.pi - theta, theta)
    return phi[index], index, angle, int(np.searchsorted(index, minus_x))


def mesh_limits(fan: FoldedSheet, hole_radius: float) -> tuple[float, float]:
    """The smallest angle (deg) and the shortest edge (length) the design
    itself puts into the mesh, whatever the mesher does: the wedges' apex
    angles, the angles between neighbouring outline edges and rays at the
    outline's vertices, the hole's corners; the outline's pieces between
    ray ends and corners, the hole's edges and the rays outside the hole."""
    theta, index, _, _ = division_rays(fan)
    ring = fan.boundary_flat
    gamma = np.diff(np.append(theta, theta[0] + 2.0 * math.pi))
    angles = [np.degrees(gamma)]
    nxt, prv = np.roll(ring, -1, axis=0) - ring, np.roll(ring, 1, axis=0) - ring
    corner = np.degrees(
        np.arctan2(np.abs(nxt[:, 0] * prv[:, 1] - nxt[:, 1] * prv[:, 0]), np.sum(nxt * prv, 1))
    )
    angles.append(corner)
    ends = ring[index]
    for side in (nxt[index], prv[index]):  # between the outline and the ray, at its end
        c = np.abs(side[:, 0] * ends[:, 1] - side[:, 1] * ends[:, 0])
        angles.append(np.degrees(np.arctan2(c, -np.sum(side * ends, 1))))
    lengths = [np.linalg.norm(nxt, axis=1)]
    if hole_radius > 0.0:
        angles.append(90.0 - np.degrees(gamma) / 2.0)
        lengths.append(2.0 * hole_radius * np.sin(gamma / 2.0))
        lengths.append(np.linalg.norm(ends, axis=1) - hole_radius)
    return float(np.concatenate(angles).min()), float(np.concatenate(lengths).min())


def fold_mesh(
    fan: FoldedSheet, hole_radius: float = 0.0, quality_deg: float | None = None
) -> FoldMesh:
    """Triangulate a paper fan's flat sheet for a FOLD file (see the module notes).

    Args:
        fan: a paper-model fold (its solution a :class:`PaperFan`).
        hole_radius: the relief hole's radius about H (length; 0: no hole),
            less than the distance from H to the outline.
        quality_deg: the smallest angle Triangle is asked for (deg); None:
            the design's own smallest angle (:func:`mesh_limits`) clipped to
            [:data:`MIN_FACE_ANGLE_DEG`, :data:`QUALITY_CAP_DEG`].
    """
    theta, index, angle, minus_x = division_rays(fan)
    ring = fan.boundary_flat
    n, m = len(theta), len(ring)
    direction = np.stack([np.cos(theta), np.sin(theta)], axis=1)
    if hole_radius > 0.0:
        inner = hole_radius * direction
        starts = m + np.arange(n)
        hole_segments = np.stack([starts, m + (np.arange(n) + 1) % n], axis=1)
    else:
        inner = np.zeros((1, 2))
        starts = np.full(n, m)
        hole_segments = np.zeros((0, 2), dtype=np.int64)
    outline = np.stack([np.arange(m), (np.arange(m) + 1) % m], axis=1)
    rays = np.stack([starts, index], axis=1)
    pslg: dict[str, Array] = {
        "vertices": np.vstack([ring, inner]),
        "segments": np.vstack([outline, hole_segments, rays]),
        "segment_markers": np.concatenate(
            [
                np.full(m, _OUTLINE_MARK),
                np.full(len(hole_segments), _HOLE_MARK),
                _RAY_MARK + np.arange(n),
            ]
        ).reshape(-1, 1),
    }
    if hole_radius > 0.0:
        pslg["holes"] = np.zeros((1, 2))
    if quality_deg is None:
        own = mesh_limits(fan, hole_radius)[0]
        quality_deg = min(max(0.9 * own, MIN_FACE_ANGLE_DEG), QUALITY_CAP_DEG)
    out = _triangulate(pslg, quality_deg)
    flat = np.asarray(out["vertices"], dtype=float)
    faces = np.asarray(out["triangles"], dtype=np.int64)
    p = flat[faces]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    cw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] < 0.0
    faces[cw] = faces[cw][:, [0, 2, 1]]
    edges, kind, ray = _edges(out, n)
    # H first when there is no hole (vertex m of the input): move it to 0.
    if hole_radius <= 0.0:
        order = np.concatenate([[m], np.delete(np.arange(len(flat)), m)])
        new = np.empty_like(order)
        new[order] = np.arange(len(order))
        flat, faces, edges = flat[order], new[faces], new[edges]
    folded = fan.map_points(flat)
    on_ray = ray >= 0
    # points on a ray fold along it exactly (their polar angle may have rounded off it)
    for e in np.flatnonzero(on_ray):
        for v in edges[e]:
            r = float(np.hypot(*flat[v]))
            folded[v] = fan.apex + r * _unit(fan, float(theta[ray[e]]))
    return FoldMesh(flat, folded, faces, edges, kind, ray, theta, angle, minus_x)


def _triangulate(pslg: dict[str, Array], quality_deg: float) -> dict[str, NDArray]:
    """Triangle's quality triangulation of ``pslg``, no angle below
    ``quality_deg`` where it reaches that; near a small input angle it may
    leave a smaller one, and then a lower quality (halved, down to
    :data:`MIN_FACE_ANGLE_DEG`) is tried, keeping the mesh whose smallest
    angle is largest. Triangle adds at most :data:`MAX_STEINER` points (or
    :data:`STEINER_PER_VERTEX` per input vertex): where the quality needs
    more, the mesh falls short of it (``onefold:mesh`` ``within_bounds``
    false) rather than growing without bound."""
    import triangle  # the meshing library (also the mechanics mesh's)

    best: tuple[float, dict[str, NDArray]] | None = None
    q = quality_deg
    steiner = max(MAX_STEINER, STEINER_PER_VERTEX * len(pslg["vertices"]))
    while True:
        out = triangle.triangulate(pslg, f"pq{q:.6f}QeS{steiner}")
        worst = float(face_angles_deg(out["vertices"], out["triangles"]).min())
        if best is None or worst > best[0]:
            best = (worst, out)
        if worst >= q * (1.0 - 1e-9) or q <= MIN_FACE_ANGLE_DEG:
            return best[1]
        q = max(q / 2.0, MIN_FACE_ANGLE_DEG)


def _unit(fan: FoldedSheet, phi: float) -> Array:
    """The folded unit direction of the ray at flat polar angle ``phi``."""
    return fan.map_points([[math.cos(phi), math.sin(phi)]])[0] - fan.apex


def _edges(
    out: dict[str, NDArray], n: int
) -> tuple[NDArray[np.int64], NDArray[np.object_], NDArray[np.int64]]:
    """Triangle's edges with their kinds and rays, from its segment markers."""
    edges = np.asarray(out["edges"], dtype=np.int64)
    marks = np.asarray(out["edge_markers"]).ravel()
    kind = np.full(len(edges), FACET, dtype=object)
    kind[marks == _OUTLINE_MARK] = OUTLINE
    kind[marks == _HOLE_MARK] = HOLE
    ray = np.where(marks >= _RAY_MARK, marks - _RAY_MARK, -1).astype(np.int64)
    ray[ray >= n] = -1
    kind[ray >= 0] = RAY
    return edges, kind, ray


def mesh_quality(mesh: FoldMesh, size: float) -> dict[str, float | bool]:
    """What the FOLD file records of its mesh (``onefold:mesh``): the
    smallest face angle (deg) and shortest edge (relative to ``size``, the
    sheet's), the bounds, and whether the mesh keeps them."""
    angle = float(face_angles_deg(mesh.flat, mesh.faces).min())
    e = mesh.edges
    edge = float(np.linalg.norm(mesh.flat[e[:, 1]] - mesh.flat[e[:, 0]], axis=1).min()) / size
    return {
        "min_face_angle_deg": angle,
        "min_edge_relative": edge,
        "bound_face_angle_deg": MIN_FACE_ANGLE_DEG,
        "bound_edge_relative": MIN_EDGE,
        "within_bounds": angle >= MIN_FACE_ANGLE_DEG and edge >= MIN_EDGE,
    }
