"""Sparse assembly: the Hessian's pattern, computed once per mesh, and the scatter.

Every element contributes a dense block over its stencil (a list of global DOF
ids); the pattern is the union of the blocks, stored as CSC with both
triangles. ``Pattern.slots`` maps every block entry to its place in the CSC
data, so assembling is one ``np.bincount``.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from onefold_cad.mechanics.mesh import INTERIOR, SheetMesh

__all__ = ["Pattern", "crease_stencil", "face_stencil", "pattern_of"]

Ints = NDArray[np.int64]


def face_stencil(mesh: SheetMesh) -> tuple[Ints, Ints]:
    """The bending face stencil and where each edge's dihedral variables sit in it.

    Returns:
        stencil: (m, 21) DOF ids: own vertices (3 x 3), the vertices across the
            three edges (3 x 3; the face's own opposite vertex where there is none),
            the three director angles.
        psi_slots: (m, 3, 4) the vertex blocks (0-5) of the edge's ``(a, b, c, d)``.
    """
    tri = mesh.triangles
    m = len(tri)
    wings = mesh.face_wings
    wings = np.where(wings >= 0, wings, tri)
    verts = np.concatenate([tri, wings], axis=1)  # (m, 6)
    xyz = (3 * verts[:, :, None] + np.arange(3)).reshape(m, 18)
    stencil = np.concatenate([xyz, 3 * mesh.n_nodes + mesh.face_directors], axis=1)
    slots = np.empty((m, 3, 4), dtype=np.int64)
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        t0 = mesh.face_edge_side[:, i] == 0
        slots[:, i] = np.where(t0[:, None], [j, k, i, 3 + i], [k, j, 3 + i, i])
    return stencil, slots


def crease_stencil(mesh: SheetMesh) -> Ints:
    """(kc, 14) DOF ids of each crease edge: ``a, b, c, d`` (3 each), its two directors."""
    e = mesh.crease_edges
    verts = np.concatenate([mesh.edges[e], mesh.edge_opposite[e]], axis=1)
    xyz = (3 * verts[:, :, None] + np.arange(3)).reshape(len(e), 12)
    dirs = 3 * mesh.n_nodes + np.stack([e, mesh.n_edges + np.arange(len(e))], axis=1)
    return np.concatenate([xyz, dirs], axis=1)


@dataclass(frozen=True, eq=False)
class Pattern:
    """The CSC pattern of the Hessian and the scatter maps of the element blocks.

    Attributes:
        n: number of DOFs.
        indptr, indices: the CSC structure (both triangles).
        face_slots: (m, 21, 21) positions of the face blocks' entries in the data.
        edge_slots: (k_int, 12, 12) the same for the interior edges' dihedral blocks
            over ``(a, b, c, d)`` (inside their ``T0``'s face block).
        crease_slots: (kc, 14, 14) the same for the crease blocks.
        face_stencil, psi_slots, crease_stencil: as built by the functions above.
        interior: (k_int,) the interior edges' ids, in the order of ``edge_slots``.
    """

    n: int
    indptr: Ints
    indices: Ints
    face_slots: Ints
    edge_slots: Ints
    crease_slots: Ints
    face_stencil: Ints
    psi_slots: Ints
    crease_stencil: Ints
    interior: Ints

    @property
    def nnz(self) -> int:
        """Stored entries."""
        return len(self.indices)

    def matrix(
        self,
        face_blocks: NDArray[np.float64],
        edge_blocks: NDArray[np.float64],
        crease_blocks: NDArray[np.float64],
    ) -> sp.csc_matrix:
        """Assemble (m, 21, 21), (k_int, 12, 12) and (kc, 14, 14) blocks into the CSC matrix."""
        data = np.bincount(self.face_slots.ravel(), face_blocks.ravel(), minlength=self.nnz)
        if len(edge_blocks):
            data += np.bincount(self.edge_slots.ravel(), edge_blocks.ravel(), minlength=self.nnz)
        if len(crease_blocks):
            data += np.bincount(
                self.crease_slots.ravel(), crease_blocks.ravel(), minlength=self.nnz
            )
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))

    def vector(
        self, face_values: NDArray[np.float64], crease_values: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Assemble (m, 21) and (kc, 14) element vectors into an (n,) vector."""
        out = np.bincount(self.face_stencil.ravel(), face_values.ravel(), minlength=self.n)
        if len(crease_values):
            out += np.bincount(self.crease_stencil.ravel(), crease_values.ravel(), minlength=self.n)
        return out


_PATTERNS: weakref.WeakKeyDictionary[SheetMesh, Pattern] = weakref.WeakKeyDictionary()


def pattern_of(mesh: SheetMesh) -> Pattern:
    """The (cached) assembly pattern of a mesh."""
    cached = _PATTERNS.get(mesh)
    if cached is not None:
        return cached
    n = mesh.n_dofs
    fs, psi_slots = face_stencil(mesh)
    cs = crease_stencil(mesh)
    blocks = [(fs, 21), (cs, 14)]
    keys = [
        (
            np.repeat(s, w, axis=1).reshape(-1, w, w) + n * np.tile(s, (1, w)).reshape(-1, w, w)
        ).ravel()
        for s, w in blocks
    ]
    # key = row + n * col sorts as CSC.
    uniq, inverse = np.unique(np.concatenate(keys), return_inverse=True)
    rows, cols = uniq % n, uniq // n
    indptr = np.searchsorted(cols, np.arange(n + 1)).astype(np.int64)
    split = len(keys[0])
    face_slots = inverse[:split].reshape(-1, 21, 21)
    interior = np.flatnonzero(mesh.edge_kind == INTERIOR)
    t0 = mesh.edge_faces[interior, 0]
    local = np.argmax(mesh.face_edges[t0] == interior[:, None], axis=1)
    idx = (3 * psi_slots[t0, local][:, :, None] + np.arange(3)).reshape(-1, 12)
    edge_slots = face_slots[t0[:, None, None], idx[:, :, None], idx[:, None, :]]
    pattern = Pattern(
        n=n,
        indptr=indptr,
        indices=rows.astype(np.int64),
        face_slots=face_slots,
        edge_slots=edge_slots,
        crease_slots=inverse[split:].reshape(-1, 14, 14),
        face_stencil=fs,
        psi_slots=psi_slots,
        crease_stencil=cs,
        interior=interior,
    )
    _PATTERNS[mesh] = pattern
    return pattern
