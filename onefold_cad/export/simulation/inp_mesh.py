"""The shell mesh NAME.inp hands to CalculiX: the simulation's facets made
curved six-node triangles and split in four.

CalculiX expands each S6 shell into a 15-node wedge one thickness deep, and
on the simulation's own facets (flat triangles, edge midpoints on the chords)
its answer converges slowly and from below: patkau-one-fold's largest
movement under its weight was 51.60 mm on the normal mesh where ours is
57.58 (Kratos, mesh-converged: 55.46). Refining the flat facets alone (each
split in four: 53.73 mm) or curving them alone (51.38 mm) does little; both
together, on the normal mesh, bring CalculiX within 5 % of ours (see
docs/mechanics.md, "The structural check in CalculiX"). So:

- each edge's midpoint is lifted off its chord onto the cubic Hermite curve
  between its ends with tangents in the ends' tangent planes:
  ``m = (a + b) / 2 + ((d . n_b) n_b - (d . n_a) n_a) / 8``, ``d = b - a``,
  ``n`` the area-weighted mean normal of the node's facets on that side of
  the crease (on a circle of radius R through a and b the midpoint lands
  within O(|d|^4 / R^3) of the arc); the crease's edges, straight rulings of
  both sides, keep their chord midpoints;
- each curved S6 is split in four by its edge midpoints, the new nodes on its
  quadratic patch (so neighbours share them: a shared edge's curve depends
  only on its three nodes).

Nodes: the simulation's ``n`` corners first (same order), then one node per
edge (the midpoints, in the order the facets first meet the edges), two per
edge (its quarter points: near its lower-numbered end, every edge's, then
near the other end), three per facet (inside it: every facet's first, then
second, then third). Lengths in the positions' unit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["ShellMesh", "curved_midpoints", "shell_mesh", "unique_edges"]

Array = NDArray[np.float64]
Index = NDArray[np.int64]


@dataclass(frozen=True)
class ShellMesh:
    """The S6 mesh written to NAME.inp.

    Attributes:
        nodes: ``(N, 3)`` positions (the simulation's corners first).
        elements: ``(4 m, 6)`` 0-based S6 connectivity: corners counter-clockwise
            as the facets', then the midpoints of edges 1-2, 2-3, 3-1.
        flat: ``(N, 2)`` each node's place on the flat sheet (linear in each
            facet: the crease nodes are those with y = 0).
    """

    nodes: Array
    elements: Index
    flat: Array


def unique_edges(faces: Index) -> tuple[Index, Index]:
    """``(edges (E, 2) sorted pairs in the order the faces first meet them,
    face_edge (m, 3))``: face edge k runs from corner k to corner k + 1."""
    corner = np.stack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]], axis=1)
    keys = np.sort(corner.reshape(-1, 2), axis=1)
    uniq, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)
    rank = np.empty(len(uniq), dtype=np.int64)
    rank[order] = np.arange(len(uniq))
    return uniq[order], rank[inverse.reshape(-1)].reshape(-1, 3)


def curved_midpoints(x: Array, faces: Index, side: Index, straight: Array) -> Array:
    """``(E, 3)`` each edge's midpoint (edges as :func:`unique_edges` orders them)
    on the Hermite curve of the module docstring.

    Args:
        x: ``(n, 3)`` corner positions.
        faces: ``(m, 3)`` corners of each facet.
        side: ``(m,)`` 0 or 1, the facet's side of the crease (the normals of
            one side are averaged apart from the other's).
        straight: ``(E,)`` bool, edges kept straight (their chord midpoint).
    """
    edges, face_edge = unique_edges(faces)
    normal = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
    acc = np.zeros((len(x), 2, 3))
    for k in range(3):
        np.add.at(acc, (faces[:, k], side), normal)
    unit = acc / np.maximum(np.linalg.norm(acc, axis=2, keepdims=True), 1e-300)
    edge_side = np.zeros(len(edges), dtype=np.int64)
    edge_side[face_edge.ravel()] = np.repeat(side, 3)
    a, b = edges[:, 0], edges[:, 1]
    d = x[b] - x[a]
    na, nb = unit[a, edge_side], unit[b, edge_side]
    lift = (np.sum(d * nb, axis=1)[:, None] * nb - np.sum(d * na, axis=1)[:, None] * na) / 8.0
    return 0.5 * (x[a] + x[b]) + np.where(straight[:, None], 0.0, lift)


def _patch(c: Array, m: Array, xi: float, eta: float) -> Array:
    """The quadratic triangle through corners ``c`` ``(k, 3, D)`` and edge
    midpoints ``m`` ``(k, 3, D)`` at area coordinates ``(1 - xi - eta, xi, eta)``."""
    lam = (1.0 - xi - eta, xi, eta)
    out = np.zeros_like(c[:, 0])
    for i in range(3):
        out += lam[i] * (2.0 * lam[i] - 1.0) * c[:, i] + 4.0 * lam[i] * lam[(i + 1) % 3] * m[:, i]
    return out


def shell_mesh(x: Array, faces: Index, flat: Array) -> ShellMesh:
    """The curved, split S6 mesh of the facets ``faces`` of corners ``x``
    ``(n, 3)`` whose flat places are ``flat`` ``(n, 2)`` (the crease on the
    flat x axis)."""
    x, flat = np.asarray(x, dtype=float), np.asarray(flat, dtype=float)
    faces = np.asarray(faces, dtype=np.int64)
    n, m = len(x), len(faces)
    edges, fe = unique_edges(faces)
    e_count = len(edges)
    side = (flat[faces, 1].mean(axis=1) > 0).astype(np.int64)
    tol = 1e-12 * float(np.ptp(flat, axis=0).max())
    straight = (np.abs(flat[edges[:, 0], 1]) <= tol) & (np.abs(flat[edges[:, 1], 1]) <= tol)
    mids = curved_midpoints(x, faces, side, straight)
    flat_mids = 0.5 * (flat[edges[:, 0]] + flat[edges[:, 1]])
    # quarter points on each edge's quadratic curve: near edges[:, 0], then edges[:, 1]
    ends = [x[edges[:, 0]], x[edges[:, 1]]]
    quarter = [0.375 * ends[0] + 0.75 * mids - 0.125 * ends[1]]
    quarter.append(0.375 * ends[1] + 0.75 * mids - 0.125 * ends[0])
    f_ends = [flat[edges[:, 0]], flat[edges[:, 1]]]
    f_quarter = [0.75 * f_ends[0] + 0.25 * f_ends[1], 0.25 * f_ends[0] + 0.75 * f_ends[1]]
    # three points inside each facet, on its patch, between its edge midpoints
    corner_x, mid_x = x[faces], mids[fe]
    corner_f, mid_f = flat[faces], flat_mids[fe]
    inner = [_patch(corner_x, mid_x, *p) for p in _INNER]
    inner_f = [_patch(corner_f, mid_f, *p) for p in _INNER]
    nodes = np.vstack([x, mids, *quarter, *inner])
    flat_all = np.vstack([flat, flat_mids, *f_quarter, *inner_f])
    # node ids
    mid_id = n + fe  # (m, 3): midpoint of face edge k (corner k -> k + 1)
    q0 = n + e_count  # quarter points: q0 + edge (near edges[:, 0]), q0 + E + edge

    def near(k: int, corner: int) -> Index:
        """The quarter point of face edge ``k`` nearer the face's corner ``corner``."""
        e = fe[:, k]
        lower = edges[e, 0] == faces[:, corner]
        return np.where(lower, q0 + e, q0 + e_count + e)

    inner_id = n + 3 * e_count + np.arange(3)[:, None] * m + np.arange(m)[None, :]
    i_a, i_b, i_c = inner_id  # between (ab, ca), (ab, bc), (bc, ca)
    a, b, c = faces.T
    ab, bc, ca = mid_id.T
    subs = [
        (a, ab, ca, near(0, 0), i_a, near(2, 0)),
        (ab, b, bc, near(0, 1), near(1, 1), i_b),
        (ca, bc, c, i_c, near(1, 2), near(2, 2)),
        (ab, bc, ca, i_b, i_c, i_a),
    ]
    elements = np.stack([np.column_stack(s) for s in subs], axis=1).reshape(-1, 6)
    return ShellMesh(nodes, elements.astype(np.int64), flat_all)


#: The patch coordinates (xi, eta) of a facet's three inner nodes: between its
#: midpoints of edges (1-2, 3-1), (1-2, 2-3), (2-3, 3-1).
_INNER = ((0.25, 0.25), (0.5, 0.25), (0.25, 0.5))
