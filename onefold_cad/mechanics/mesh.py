"""The triangulation of the flat sheet: topology, creases and the director numbering.

Lengths are in metres (the core's unit); the mesh lives in the flat sheet's plane.
Edge ``i`` of a triangle is the one opposite its vertex ``i``. Every edge is stored
in the direction it runs in its first face ``T0`` (counter-clockwise), so it runs
the other way in ``T1``; boundary edges have ``T1 = -1``.

Director angles (the bending model's extra unknowns, see ``energy``) are numbered
one per edge (``0 .. k-1``, by edge id) plus a second one for each crease edge
(``k .. k+kc-1``, in the order of ``crease_edges``): on a crease, ``T0`` uses the
first and ``T1`` the second.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from scipy.sparse.csgraph import connected_components

from onefold_cad.errors import InvalidParameterError

__all__ = ["BOUNDARY", "CREASE", "INTERIOR", "SheetMesh", "build_mesh", "mesh_sheet"]

INTERIOR, BOUNDARY, CREASE = 0, 1, 2
_OUTLINE_MARK, _HOLE_MARK, _CREASE_MARK = 1, 2, 10

SizeSpec = Callable[[NDArray[np.float64]], NDArray[np.float64]] | tuple[float, float, float]


@dataclass(frozen=True, eq=False)
class SheetMesh:
    """A triangulated flat sheet (values; build it with ``build_mesh`` or ``mesh_sheet``).

    Attributes:
        nodes: (n, 2) float, flat positions (m).
        triangles: (m, 3) int, counter-clockwise vertex indices.
        edges: (k, 2) int, end nodes, in the direction the edge runs in ``T0``.
        edge_faces: (k, 2) int, the faces ``T0, T1`` (``T1 = -1`` on the boundary).
        edge_kind: (k,) int8, ``INTERIOR``, ``BOUNDARY`` or ``CREASE``.
        face_edges: (m, 3) int, the edge opposite each vertex.
        face_edge_side: (m, 3) int8, 0 where the face is that edge's ``T0``, 1 for ``T1``.
        edge_opposite: (k, 2) int, the vertex opposite the edge in ``T0`` and ``T1`` (-1).
        crease_edges: (kc,) int, the crease edges' ids, in the order of their second
            director angle.
        face_side: (m,) int, the side (connected part once cut along the creases).
    """

    nodes: NDArray[np.float64]
    triangles: NDArray[np.int64]
    edges: NDArray[np.int64]
    edge_faces: NDArray[np.int64]
    edge_kind: NDArray[np.int8]
    face_edges: NDArray[np.int64]
    face_edge_side: NDArray[np.int8]
    edge_opposite: NDArray[np.int64]
    crease_edges: NDArray[np.int64]
    face_side: NDArray[np.int64]

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.nodes)

    @property
    def n_faces(self) -> int:
        """Number of triangles."""
        return len(self.triangles)

    @property
    def n_edges(self) -> int:
        """Number of edges."""
        return len(self.edges)

    @property
    def n_directors(self) -> int:
        """Number of director angles: one per edge plus one more per crease edge."""
        return len(self.edges) + len(self.crease_edges)

    @property
    def n_dofs(self) -> int:
        """Unknowns: ``3 n`` coordinates (node-major) then the director angles."""
        return 3 * len(self.nodes) + self.n_directors

    @property
    def n_sides(self) -> int:
        """Number of sides the creases cut the sheet into."""
        return int(self.face_side.max()) + 1 if len(self.face_side) else 0

    @cached_property
    def face_directors(self) -> NDArray[np.int64]:
        """(m, 3) int: the director angle each face uses on each of its edges."""
        fd = self.face_edges.copy()
        second = np.full(self.n_edges, -1, dtype=np.int64)
        second[self.crease_edges] = self.n_edges + np.arange(len(self.crease_edges))
        on_t1 = (self.face_edge_side == 1) & (self.edge_kind[self.face_edges] == CREASE)
        fd[on_t1] = second[self.face_edges[on_t1]]
        return fd

    @cached_property
    def face_wings(self) -> NDArray[np.int64]:
        """(m, 3) int: the vertex across each edge (in the neighbour face), -1 if none."""
        side = self.face_edge_side.astype(np.int64)
        return self.edge_opposite[self.face_edges, 1 - side]

    @cached_property
    def boundary_nodes(self) -> NDArray[np.int64]:
        """Sorted ids of the nodes on the outline or the hole."""
        return np.unique(self.edges[self.edge_kind == BOUNDARY])

    @cached_property
    def edge_lengths(self) -> NDArray[np.float64]:
        """(k,) flat edge lengths (m)."""
        d = self.nodes[self.edges[:, 1]] - self.nodes[self.edges[:, 0]]
        return np.hypot(d[:, 0], d[:, 1])

    @cached_property
    def face_areas(self) -> NDArray[np.float64]:
        """(m,) flat triangle areas (m^2)."""
        p = self.nodes[self.triangles]
        u, v = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        return 0.5 * _cross2(u, v)

    def min_angle_deg(self) -> float:
        """The smallest interior angle of any triangle (degrees)."""
        p = self.nodes[self.triangles]
        worst = math.pi
        for i in range(3):
            a, b = p[:, (i + 1) % 3] - p[:, i], p[:, (i + 2) % 3] - p[:, i]
            cos = np.einsum("ij,ij->i", a, b) / np.hypot(*a.T) / np.hypot(*b.T)
            worst = min(worst, float(np.arccos(np.clip(cos, -1, 1)).min()))
        return math.degrees(worst)


def _cross2(u: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    """z component of the cross product of (..., 2) vectors."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def build_mesh(
    nodes: ArrayLike, triangles: ArrayLike, crease_pairs: ArrayLike | None = None
) -> SheetMesh:
    """Build the topology of a flat triangulation.

    Args:
        nodes: (n, 2) flat positions (m).
        triangles: (m, 3) vertex indices; clockwise ones are reoriented.
        crease_pairs: (kc, 2) node pairs that are crease edges (each must be an
            interior edge of the triangulation).

    Raises:
        InvalidParameterError: degenerate or non-manifold triangles, or a crease
            pair that is not an interior edge.
    """
    xy = np.ascontiguousarray(np.asarray(nodes, dtype=float)[:, :2])
    tri = np.array(triangles, dtype=np.int64).reshape(-1, 3)
    n, m = len(xy), len(tri)
    if m == 0 or tri.min() < 0 or tri.max() >= n:
        raise InvalidParameterError("triangles", "indices must lie in 0 .. n-1")
    p = xy[tri]
    area2 = _cross2(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    scale = float(np.ptp(xy, axis=0).max()) ** 2
    if np.any(np.abs(area2) <= 1e-14 * scale):
        raise InvalidParameterError("triangles", "a triangle is degenerate")
    flip = area2 < 0
    tri[flip] = tri[flip][:, [0, 2, 1]]

    # Half-edges: local edge i of face f runs from vertex i+1 to vertex i+2.
    start = tri[:, [1, 2, 0]].T.ravel()
    end = tri[:, [2, 0, 1]].T.ravel()
    face = np.tile(np.arange(m), 3)
    local = np.repeat(np.arange(3), m)
    key = np.minimum(start, end) * n + np.maximum(start, end)
    order = np.argsort(key, kind="stable")
    uniq, first, inverse, counts = np.unique(
        key[order], return_index=True, return_inverse=True, return_counts=True
    )
    if np.any(counts > 2):
        raise InvalidParameterError("triangles", "an edge is shared by more than two triangles")
    k = len(uniq)
    h0 = order[first]
    h1 = np.where(counts == 2, order[np.minimum(first + 1, len(order) - 1)], -1)
    if np.any((h1 >= 0) & (start[np.maximum(h1, 0)] == start[h0])):
        raise InvalidParameterError("triangles", "neighbouring triangles are not oriented alike")
    edges = np.stack([start[h0], end[h0]], axis=1)
    edge_faces = np.stack([face[h0], np.where(h1 >= 0, face[np.maximum(h1, 0)], -1)], axis=1)
    edge_id = np.empty(3 * m, dtype=np.int64)
    edge_id[order] = inverse
    face_edges = edge_id.reshape(3, m).T.copy()
    side = np.zeros(3 * m, dtype=np.int8)
    side[h1[h1 >= 0]] = 1
    face_edge_side = side.reshape(3, m).T.copy()
    opp_vertex = tri[face, local]
    edge_opposite = np.stack(
        [opp_vertex[h0], np.where(h1 >= 0, opp_vertex[np.maximum(h1, 0)], -1)], axis=1
    )

    kind = np.where(counts == 2, INTERIOR, BOUNDARY).astype(np.int8)
    crease_edges = np.zeros(0, dtype=np.int64)
    if crease_pairs is not None and len(np.asarray(crease_pairs)):
        cp = np.asarray(crease_pairs, dtype=np.int64).reshape(-1, 2)
        ckey = np.minimum(cp[:, 0], cp[:, 1]) * n + np.maximum(cp[:, 0], cp[:, 1])
        pos = np.searchsorted(uniq, ckey)
        pos = np.minimum(pos, k - 1)
        if np.any(uniq[pos] != ckey) or np.any(kind[pos] != INTERIOR):
            raise InvalidParameterError("creases", "a crease pair is not an interior edge")
        crease_edges = np.unique(pos)
        kind[crease_edges] = CREASE

    # Sides: faces joined across non-crease interior edges.
    joined = kind == INTERIOR
    graph = sp.coo_matrix(
        (np.ones(int(joined.sum())), (edge_faces[joined, 0], edge_faces[joined, 1])), shape=(m, m)
    )
    _, face_side = connected_components(graph, directed=False)
    return SheetMesh(
        nodes=xy,
        triangles=tri,
        edges=edges,
        edge_faces=edge_faces,
        edge_kind=kind,
        face_edges=face_edges,
        face_edge_side=face_edge_side,
        edge_opposite=edge_opposite,
        crease_edges=crease_edges,
        face_side=face_side.astype(np.int64),
    )


def _size_function(size: SizeSpec, centre: NDArray[np.float64]) -> Callable:
    if callable(size):
        return size
    h_min, growth, h_max = (float(v) for v in size)
    if not (0 < h_min <= h_max) or growth < 0:
        raise InvalidParameterError("size", "need 0 < h_min <= h_max and growth >= 0")

    def graded(points: NDArray[np.float64]) -> NDArray[np.float64]:
        d = np.hypot(points[:, 0] - centre[0], points[:, 1] - centre[1])
        return np.clip(growth * d, h_min, h_max)

    return graded


def _on_segment(
    p: NDArray[np.float64], a: NDArray[np.float64], b: NDArray[np.float64], tol: float
) -> float | None:
    """The parameter of ``p`` on segment ``ab`` if it lies on it (within tol), else None."""
    d = b - a
    s = float(np.dot(p - a, d) / np.dot(d, d))
    if -1e-12 <= s <= 1 + 1e-12 and np.hypot(*(a + s * d - p)) <= tol:
        return min(max(s, 0.0), 1.0)
    return None


def mesh_sheet(
    outline: ArrayLike,
    *,
    size: SizeSpec,
    hole_radius: float = 0.0,
    hole_centre: ArrayLike = (0.0, 0.0),
    creases: Sequence[ArrayLike] = (),
    boundary_points: ArrayLike = (),
    min_angle: float = 28.0,
    max_passes: int = 20,
) -> SheetMesh:
    """Triangulate a flat sheet with the ``triangle`` library (quality, graded, conforming).

    Args:
        outline: (p, 2) the sheet's boundary polygon (m), either orientation, not closed.
        size: the target edge length (m) as a function of (q, 2) points returning (q,),
            or ``(h_min, growth, h_max)``: ``clip(growth * distance from hole_centre,
            h_min, h_max)`` (size proportional to the distance, floored and capped).
        hole_radius: radius of a circular hole (m, 0: none), cut as a polygon whose
            sides are at most the size at its rim.
        hole_centre: (2,) its centre (also the centre of the grading).
        creases: segments ``((x0, y0), (x1, y1))``; they are kept as mesh edges
            (no triangle crosses them). An end on the outline or the hole's rim
            becomes a vertex of it.
        boundary_points: (b, 2) points on the outline that must be mesh nodes
            (ground contacts, say).
        min_angle: Triangle's quality bound (degrees).
        max_passes: refinement passes allowed to reach the size everywhere.

    Returns:
        The mesh, its crease edges marked.
    """
    import triangle  # the meshing library; imported here to keep import time low

    poly = np.asarray(outline, dtype=float).reshape(-1, 2)
    if len(poly) < 3:
        raise InvalidParameterError("outline", "needs at least 3 vertices")
    if np.sum(_cross2(poly, np.roll(poly, -1, axis=0))) < 0:
        poly = poly[::-1]
    centre = np.asarray(hole_centre, dtype=float).reshape(2)
    h_of = _size_function(size, centre)
    diam = float(np.ptp(poly, axis=0).max())
    tol = 1e-9 * diam
    segs = [np.asarray(c, dtype=float).reshape(2, 2) for c in creases]
    marked = [p for s in segs for p in s]
    marked += list(np.asarray(boundary_points, dtype=float).reshape(-1, 2))

    # Outline: split its sides at crease ends and boundary points on them.
    pts: list[NDArray[np.float64]] = []
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        pts.append(a)
        hits = []
        for p in marked:
            t = _on_segment(p, a, b, tol)
            if t is not None and 0 < t < 1 and min(np.hypot(*(p - a)), np.hypot(*(p - b))) > tol:
                hits.append((t, p))
        pts.extend(p for _, p in sorted(hits, key=lambda h: h[0]))
    outline_pts = np.array(pts)
    vertices = [outline_pts]
    no = len(outline_pts)
    segments = [np.stack([np.arange(no), (np.arange(no) + 1) % no], axis=1)]
    marks = [np.full(no, _OUTLINE_MARK)]
    holes = []
    if hole_radius > 0:
        rim = float(h_of(centre[None, :] + [[hole_radius, 0.0]])[0])
        nh = max(12, math.ceil(2 * math.pi * hole_radius / rim))
        ang = list(2 * math.pi * np.arange(nh) / nh)
        for s in segs:
            for p in s:
                if abs(np.hypot(*(p - centre)) - hole_radius) <= 1e-6 * hole_radius:
                    ang.append(math.atan2(p[1] - centre[1], p[0] - centre[0]) % (2 * math.pi))
        ang_arr = np.unique(np.round(np.array(ang), 12))
        ring = centre + hole_radius * np.stack([np.cos(ang_arr), np.sin(ang_arr)], axis=1)
        base = sum(len(v) for v in vertices)
        vertices.append(ring)
        nr = len(ring)
        segments.append(base + np.stack([np.arange(nr), (np.arange(nr) + 1) % nr], axis=1))
        marks.append(np.full(nr, _HOLE_MARK))
        holes.append(centre)
    allv = np.concatenate(vertices)

    def vertex_id(p: NDArray[np.float64]) -> int:
        nonlocal allv
        d = np.hypot(*(allv - p).T)
        j = int(np.argmin(d))
        if d[j] <= max(tol, 1e-6 * hole_radius):
            return j
        allv = np.vstack([allv, p])
        return len(allv) - 1

    for j, s in enumerate(segs):
        a, b = vertex_id(s[0]), vertex_id(s[1])
        segments.append(np.array([[a, b]]))
        marks.append(np.array([_CREASE_MARK + j]))
    pslg = dict(
        vertices=allv,
        segments=np.concatenate(segments),
        segment_markers=np.concatenate(marks).reshape(-1, 1),
    )
    if holes:
        pslg["holes"] = np.array(holes)
    h_max = float(np.max(h_of(allv)))
    quality = f"q{min_angle:g}"
    try:
        out = triangle.triangulate(pslg, f"p{quality}a{0.433 * h_max**2:.17g}")
    except RuntimeError as exc:  # Triangle's own refusal of the outline
        raise InvalidParameterError("mesh", f"the sheet cannot be meshed ({exc})") from None
    for _ in range(max_passes):
        v, t = out["vertices"], out["triangles"]
        p = v[t]
        area = 0.5 * np.abs(_cross2(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]))
        target = 0.433 * h_of(p.mean(axis=1)) ** 2
        if np.all(area <= 1.05 * target):
            break
        out = triangle.triangulate(
            dict(
                vertices=v,
                segments=out["segments"],
                segment_markers=out["segment_markers"],
                triangles=t,
                triangle_max_area=np.minimum(area, target),
            ),
            f"rp{quality}a",
        )
    else:
        raise InvalidParameterError(
            "size", f"the mesh did not reach the size in {max_passes} passes"
        )
    smark = out["segment_markers"].ravel()
    crease_pairs = out["segments"][smark >= _CREASE_MARK]
    return build_mesh(out["vertices"], out["triangles"], crease_pairs)
