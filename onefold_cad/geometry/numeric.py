"""Small numeric helpers, one home per formula: the array alias, the 3-vector
cross product, sorted distinct values, a closed polygon's edges, edge lengths
and signed area, and composite Gauss-Legendre rules.

Numpy only; every function is exactly the arithmetic its callers used before
they shared it (the files written from its results are byte-identical).
"""

from __future__ import annotations

import functools

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "Array",
    "Mask",
    "cross2",
    "cross3",
    "edge_lengths",
    "edge_lengths_2d",
    "edge_vectors",
    "gauss_legendre",
    "panel_rule",
    "polygon_area",
    "roll_rows",
    "sorted_unique",
]

#: The float arrays of the package (shapes in each function's docstring).
Array = NDArray[np.float64]
#: The boolean arrays (masks) of the package.
Mask = NDArray[np.bool_]


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of 3-vectors along the last axis (numpy's np.cross without
    its axis-juggling overhead, which dominates for the small arrays here)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    shape = a.shape if a.shape == b.shape else np.broadcast_shapes(a.shape, b.shape)
    out = np.empty(shape)
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def roll_rows(a: np.ndarray, shift: int) -> np.ndarray:
    """``np.roll(a, shift, axis=0)`` (the same array) without its wrapper's
    overhead, which dominates for the few rows of a polygon."""
    n = len(a)
    if n == 0:
        return a.copy()
    k = -shift % n
    return np.concatenate((a[k:], a[:k]))


def sorted_unique(values: ArrayLike) -> np.ndarray:
    """``np.unique(values)`` of real numbers: the sorted distinct values of the
    flattened array (NaNs as one), computed as numpy computes it for floats
    (sort, then drop repeats; integers come out the same), without its first
    call's import of numpy.ma (10 ms, a fifth of ``onefold solve``'s own
    imports)."""
    aux = np.asarray(values).flatten()
    aux.sort()
    keep = np.empty(aux.shape, dtype=bool)
    keep[:1] = True
    if aux.size and aux.dtype.kind == "f" and np.isnan(aux[-1]):
        first_nan = int(np.searchsorted(aux, aux[-1], side="left"))
        if first_nan > 0:
            keep[1:first_nan] = aux[1:first_nan] != aux[: first_nan - 1]
        keep[first_nan] = True
        keep[first_nan + 1 :] = False
    else:
        keep[1:] = aux[1:] != aux[:-1]
    return aux[keep]


def cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The z component of the cross product of plane vectors along the last
    axis: a_x b_y - a_y b_x."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def edge_vectors(polygon: Array) -> Array:
    """``(n, d)`` the edges of a closed polygon ``(n, d)``: vertex i + 1 minus
    vertex i, the last edge back to vertex 0 (length)."""
    return roll_rows(polygon, -1) - polygon


def edge_lengths(polygon: Array) -> Array:
    """``(n,)`` the edge lengths of a closed polygon ``(n, d)`` in any dimension
    (``np.linalg.norm``: the square root of the rounded sum of squares; length)."""
    return np.linalg.norm(edge_vectors(polygon), axis=1)


def edge_lengths_2d(polygon: Array) -> Array:
    """``(n,)`` the edge lengths of a closed plane polygon ``(n, 2)`` by
    ``np.hypot`` (no intermediate rounding of the squares: the last bit can
    differ from :func:`edge_lengths`; the sheet's perimeter and the blank's
    checks have always used this one; length)."""
    return np.hypot(*edge_vectors(polygon).T)


def polygon_area(polygon: ArrayLike) -> float:
    """Signed shoelace area of a closed polygon ``(m, 2)`` (positive when
    counter-clockwise; length^2); 0 for fewer than 3 corners."""
    p = np.asarray(polygon, dtype=float).reshape(-1, 2)
    if len(p) < 3:
        return 0.0
    q = roll_rows(p, -1)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]))


@functools.cache
def gauss_legendre(n: int) -> tuple[Array, Array]:
    """The ``n``-point Gauss-Legendre rule on [-1, 1]: nodes and weights
    ``(n,)`` each (``numpy.polynomial.legendre.leggauss``, computed once;
    read-only)."""
    nodes, weights = np.polynomial.legendre.leggauss(n)
    nodes.setflags(write=False)
    weights.setflags(write=False)
    return nodes, weights


def panel_rule(mid: Array, half: Array, n: int) -> tuple[Array, Array]:
    """A composite ``n``-point Gauss-Legendre rule on panels of centres
    ``mid`` and half-widths ``half`` ``(p,)``: nodes and weights ``(p, n)``
    (ravel them for one rule over all the panels)."""
    x, w = gauss_legendre(n)
    return mid[:, None] + half[:, None] * x, half[:, None] * w
