"""Which points lie within a tolerance of any of a set of targets, in memory
linear in the points.

The dense test (the ``(n, m, 2)`` array of every difference) needs
16 n m bytes: 6 GB for the 20 000 ruling ends of a 10 000-division paper
fan. Here the targets go into a hash grid of cells 2 tol wide; a point
within tol of a target differs from it by at most tol per coordinate, so
their cells differ by at most one (the factor 2 leaves room for the
rounding of the division), and only the targets of the 3 x 3 cells around
a point are measured. Memory O(n + m) (the candidate pairs are measured in
batches); time O(n + m) plus the pairs that share a neighbourhood (targets
within a few tol of each other: a few at most where a fan's rulings crowd
near H).
Numpy only; lengths in any one unit.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.numeric import Array

__all__ = ["near_any"]

#: Pairs measured at once (bounds the memory when many targets crowd a cell).
_BATCH = 1 << 16

_NEIGHBOURS = tuple((dx, dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1))


def near_any(points: Array, targets: Array, tol: float) -> NDArray[np.bool_]:
    """For each point, whether some target lies within ``tol`` of it
    (Euclidean distance ``<= tol``), as
    ``np.any(np.linalg.norm(points[:, None] - targets[None], axis=2) <= tol, axis=1)``
    computes it, without that ``(n, m, 2)`` array.

    Args:
        points: ``(n, 2)`` finite points.
        targets: ``(m, 2)`` finite points.
        tol: the distance (same unit, > 0 and finite).

    Returns:
        ``(n,)`` bool.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    targets = np.asarray(targets, dtype=float).reshape(-1, 2)
    out = np.zeros(len(points), dtype=bool)
    if not len(points) or not len(targets):
        return out
    if not (tol > 0.0 and math.isfinite(tol)):
        raise ValueError(f"tol must be > 0 and finite, got {tol!r}")
    width = 2.0 * tol
    grid: dict[tuple[int, int], list[int]] = {}
    for j, key in enumerate(map(tuple, np.floor(targets / width).tolist())):
        grid.setdefault((int(key[0]), int(key[1])), []).append(j)
    rows: list[int] = []
    cols: list[int] = []

    def measure() -> None:  # in batches: the pairs never exceed _BATCH at once
        i, j = np.array(rows, dtype=np.intp), np.array(cols, dtype=np.intp)
        hit = np.linalg.norm(points[i] - targets[j], axis=1) <= tol
        out[i[hit]] = True
        rows.clear()
        cols.clear()

    for i, (cx, cy) in enumerate(np.floor(points / width).tolist()):
        cx, cy = int(cx), int(cy)
        for dx, dy in _NEIGHBOURS:
            for j in grid.get((cx + dx, cy + dy), ()):
                rows.append(i)
                cols.append(j)
        if len(rows) >= _BATCH:
            measure()
    if rows:
        measure()
    return out
