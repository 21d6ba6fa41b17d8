"""Sparse assembly: the Hessian's pattern, computed once per mesh, and the scatter.

Every element contributes a dense block over its stencil (a list of global DOF
ids): a face its 9 coordinates and 3 director angles, a crease edge its two
director angles. The pattern is the union of the blocks, stored as CSC with
both triangles; ``Pattern.face_slots`` and ``crease_slots`` map every block entry
to its place in the CSC data, so assembling is one ``np.bincount``.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import cast

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from onefold_cad.mechanics.mesh import SheetMesh

__all__ = ["Pattern", "crease_stencil", "face_stencil", "pattern_of"]

Ints = NDArray[np.int64]


def face_stencil(mesh: SheetMesh) -> Ints:
    """(m, 12) DOF ids of each face: its vertices' coordinates, its 3 director angles."""
    m = mesh.n_faces
    xyz = (3 * mesh.triangles[:, :, None] + np.arange(3)).reshape(m, 9)
    return np.concatenate([xyz, 3 * mesh.n_nodes + mesh.face_directors], axis=1)


def crease_stencil(mesh: SheetMesh) -> Ints:
    """(kc, 2) DOF ids of each crease edge's two director angles (``T0``'s, ``T1``'s)."""
    kc = len(mesh.crease_edges)
    return 3 * mesh.n_nodes + np.stack([mesh.crease_edges, mesh.n_edges + np.arange(kc)], axis=1)


@dataclass(frozen=True, eq=False)
class Pattern:
    """The CSC pattern of the Hessian and the scatter maps of the element blocks.

    Attributes:
        n: number of DOFs.
        indptr, indices: the CSC structure (both triangles).
        face_slots: (m, 12, 12) positions of the face blocks' entries in the data.
        crease_slots: (kc, 2, 2) the same for the crease blocks.
        face_stencil, crease_stencil: as built by the functions above.
    """

    n: int
    indptr: Ints
    indices: Ints
    face_slots: Ints
    crease_slots: Ints
    face_stencil: Ints
    crease_stencil: Ints

    @property
    def nnz(self) -> int:
        """Stored entries."""
        return len(self.indices)

    def matrix(
        self, face_blocks: NDArray[np.float64], crease_blocks: NDArray[np.float64]
    ) -> sp.csc_matrix:
        """Assemble (m, 12, 12) and (kc, 2, 2) blocks into the (n, n) CSC matrix."""
        data = np.bincount(self.face_slots.ravel(), face_blocks.ravel(), minlength=self.nnz)
        if len(crease_blocks):
            data += np.bincount(
                self.crease_slots.ravel(), crease_blocks.ravel(), minlength=self.nnz
            )
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))

    def vector(
        self, face_values: NDArray[np.float64], crease_values: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Assemble (m, 12) and (kc, 2) element vectors into an (n,) vector."""
        out = cast(
            "NDArray[np.float64]",
            np.bincount(self.face_stencil.ravel(), face_values.ravel(), minlength=self.n),
        )
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
    fs, cs = face_stencil(mesh), crease_stencil(mesh)
    keys = [
        (s[:, :, None] + n * s[:, None, :]).ravel()  # row + n * col: sorts as CSC
        for s in (fs, cs)
    ]
    uniq, inverse = np.unique(np.concatenate(keys), return_inverse=True)
    cols = uniq // n
    split = len(keys[0])
    pattern = Pattern(
        n=n,
        indptr=np.searchsorted(cols, np.arange(n + 1)).astype(np.int64),
        indices=(uniq % n).astype(np.int64),
        face_slots=inverse[:split].reshape(-1, 12, 12),
        crease_slots=inverse[split:].reshape(-1, 2, 2),
        face_stencil=fs,
        crease_stencil=cs,
    )
    _PATTERNS[mesh] = pattern
    return pattern
