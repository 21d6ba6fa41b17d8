"""A multifrontal sparse Cholesky factorisation with a geometric nested-dissection
ordering: dense fronts, so the work is done by LAPACK/BLAS-3.

The unknowns of a sheet sit at points of the flat sheet (nodes, edge midpoints);
bisecting the point set at medians, with the unknowns on one side that touch
the other as the separator, gives a nested dissection of the matrix graph. Each
tree node is a front: its own unknowns (pivots, eliminated together) and the
later unknowns they couple to (its update set). ``analyse`` does this once per
sparsity pattern; ``factor`` then takes any matrix with that pattern.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.linalg import solve_triangular

__all__ = ["Analysis", "Cholesky", "NotPositiveDefinite", "analyse"]

Ints = NDArray[np.int64]
F = NDArray[np.float64]


class NotPositiveDefinite(ArithmeticError):
    """The matrix has a pivot <= 0."""


@dataclass(frozen=True, eq=False)
class Analysis:
    """The ordering, the fronts and the scatter maps of one sparsity pattern.

    Attributes:
        n: the matrix order.
        pivots, updates: per front (postorder), the unknowns it eliminates and the
            later ones it updates.
        children: per front, its children's ids.
        entries: per front, the CSC data positions assembled into it, and ``local``
            their flat positions in the front (both triangles).
        child_maps: per front and child, where the child's update set sits in the front.
    """

    n: int
    pivots: list[Ints]
    updates: list[Ints]
    children: list[list[int]]
    entries: list[Ints]
    local: list[Ints]
    child_maps: list[list[Ints]]


def _neighbours_across(indptr: Ints, indices: Ints, rows: Ints, other: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """(len(rows),) bool: rows with a neighbour in ``other``."""
    starts, stops = indptr[rows], indptr[rows + 1]
    counts = stops - starts
    total = int(counts.sum())
    if total == 0:
        return np.zeros(len(rows), dtype=bool)
    offsets = np.repeat(starts - np.concatenate([[0], np.cumsum(counts)[:-1]]), counts)
    cols = indices[np.arange(total) + offsets]
    owner = np.repeat(np.arange(len(rows)), counts)
    return np.bincount(owner, weights=other[cols], minlength=len(rows)) > 0


def _dissect(indptr: Ints, indices: Ints, points: F, leaf: int) -> tuple[list[Ints], list[list[int]]]:
    """Fronts' pivots in postorder and their children, by recursive bisection."""
    n = len(points)
    pivots: list[Ints] = []
    children: list[list[int]] = []
    mask = np.zeros(n, dtype=bool)

    def visit(idx: Ints) -> int:
        if len(idx) <= leaf:
            pivots.append(idx)
            children.append([])
            return len(pivots) - 1
        p = points[idx]
        axis = int(np.argmax(np.ptp(p, axis=0)))
        order = np.argsort(p[:, axis], kind="stable")
        half = len(idx) // 2
        left, right = idx[order[:half]], idx[order[half:]]
        mask[right] = True
        across = _neighbours_across(indptr, indices, left, mask)
        mask[right] = False
        separator, left = left[across], left[~across]
        kids = [visit(part) for part in (left, right) if len(part)]
        if len(separator) == 0:  # disconnected halves: a front with no pivots
            separator = np.zeros(0, dtype=np.int64)
        pivots.append(separator)
        children.append(kids)
        return len(pivots) - 1

    visit(np.arange(n))
    return pivots, children


def analyse(matrix: sp.csc_matrix, points: F, leaf: int = 160) -> Analysis:
    """Order and analyse a symmetric pattern (both triangles stored).

    Args:
        matrix: (n, n) CSC with the pattern (values unused).
        points: (n, d) a position of every unknown (for the bisection).
        leaf: the most unknowns a front at the bottom of the tree eliminates.
    """
    n = matrix.shape[0]
    indptr, indices = matrix.indptr.astype(np.int64), matrix.indices.astype(np.int64)
    pivots, children = _dissect(indptr, indices, np.asarray(points, dtype=float), leaf)
    position = np.empty(n, dtype=np.int64)
    position[np.concatenate(pivots)] = np.arange(n)
    front_of = np.empty(n, dtype=np.int64)
    for f, piv in enumerate(pivots):
        front_of[piv] = f
        pivots[f] = piv[np.argsort(position[piv])]
    # Update sets, bottom-up: later unknowns coupled to the pivots or to the children's sets.
    updates: list[Ints] = []
    for f, piv in enumerate(pivots):
        if len(piv):
            end = position[piv[-1]]
            rows = np.concatenate([indices[indptr[i] : indptr[i + 1]] for i in piv])
        else:
            end, rows = -1, np.zeros(0, dtype=np.int64)
        if len(piv) == 0 and children[f]:
            end = max(position[pivots[c][-1]] if len(pivots[c]) else -1 for c in children[f])
        cand = np.concatenate([rows] + [updates[c] for c in children[f]])
        cand = np.unique(cand)
        cand = cand[position[cand] > end]
        updates.append(cand[np.argsort(position[cand], kind="stable")])
    # Where every matrix entry goes: the front that pivots its earlier unknown.
    cols = np.repeat(np.arange(n), np.diff(indptr))
    rows_all = indices
    first = np.where(position[rows_all] < position[cols], rows_all, cols)
    owner = front_of[first]
    by_front = np.argsort(owner, kind="stable")
    bounds = np.searchsorted(owner[by_front], np.arange(len(pivots) + 1))
    entries, local, child_maps = [], [], []
    for f in range(len(pivots)):
        members = np.concatenate([pivots[f], updates[f]])
        key = position[members]
        e = by_front[bounds[f] : bounds[f + 1]]
        r = np.searchsorted(key, position[rows_all[e]])
        c = np.searchsorted(key, position[cols[e]])
        entries.append(e)
        local.append(r * len(members) + c)
        child_maps.append([np.searchsorted(key, position[updates[c]]) for c in children[f]])
    return Analysis(n, pivots, updates, children, entries, local, child_maps)


class Cholesky:
    """``A = L L^T`` of a symmetric positive definite matrix with an analysed pattern."""

    def __init__(self, analysis: Analysis, matrix: sp.csc_matrix) -> None:
        """Factor ``matrix`` (same CSC structure as analysed).

        Raises:
            NotPositiveDefinite: a pivot is not positive.
        """
        an = analysis
        data = matrix.data
        self.analysis = an
        self._l11: list[F] = []
        self._l21: list[F] = []
        pending: dict[int, F] = {}
        for f in range(len(an.pivots)):
            p, u = len(an.pivots[f]), len(an.updates[f])
            front = np.zeros((p + u, p + u))
            front.flat[an.local[f]] = data[an.entries[f]]
            for c, where in zip(an.children[f], an.child_maps[f], strict=True):
                front[np.ix_(where, where)] += pending.pop(c)
            if p == 0:
                l11, l21 = np.zeros((0, 0)), np.zeros((u, 0))
                update = front
            else:
                try:
                    l11 = np.linalg.cholesky(front[:p, :p])
                except np.linalg.LinAlgError as err:
                    raise NotPositiveDefinite(str(err)) from err
                l21 = solve_triangular(l11, front[p:, :p].T, lower=True, check_finite=False).T
                update = front[p:, p:] - l21 @ l21.T
            self._l11.append(l11)
            self._l21.append(np.ascontiguousarray(l21))
            if u:
                pending[f] = update

    def solve(self, b: F) -> F:
        """``A^-1 b`` for (n,) ``b``."""
        an = self.analysis
        x = np.array(b, dtype=float)
        for f in range(len(an.pivots)):
            piv, upd = an.pivots[f], an.updates[f]
            if len(piv) == 0:
                continue
            y = solve_triangular(self._l11[f], x[piv], lower=True, check_finite=False)
            x[piv] = y
            if len(upd):
                x[upd] -= self._l21[f] @ y
        for f in range(len(an.pivots) - 1, -1, -1):
            piv, upd = an.pivots[f], an.updates[f]
            if len(piv) == 0:
                continue
            y = x[piv] - (self._l21[f].T @ x[upd] if len(upd) else 0.0)
            x[piv] = solve_triangular(self._l11[f], y, lower=True, trans="T", check_finite=False)
        return x
