"""The driven path of the CalculiX forming benchmark (``calculix_forming.py``),
pure numpy: how far ccx's linear ramp between two driven forms strains the
sheet in its plane, the rigid motion between forms removed, and the steps
graded until that strain is far below the yield strain.

Between two driven forms ``a`` and ``b`` (node positions of one mesh) ccx
moves every node linearly, so at the step's midpoint a chord ``c`` of the
sheet is ``(c_a + c_b) / 2`` and

    |c_mid|^2 = (|c_a|^2 + |c_b|^2) / 2 - |c_b - c_a|^2 / 4,

shorter than the forms' own chords by about ``|c_b - c_a|^2 / (8 |c|)``
(for chords of equal length exactly ``L (1 - cos(phi / 2))``, ``phi`` the
angle the chord turns in the step): a membrane strain that no isometric
forming has. :func:`ramp_strain` measures it per chord (relative to the mean
of the two forms' chords, so a form's own chord error on a curved surface,
which the quadratic element's curved edge does not see, is left out).
:func:`align_chain` removes the rigid turn between forms (each form
best-fitted onto the one before: the rigid motion is part of every chord's
turn); :func:`graded_steps` halves each step until its ramp strain is below a
bound.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


def half_edges(tri6: IntArray) -> IntArray:
    """``(k, 2)`` the S6 elements' half-edges (corner to edge midpoint, each
    once), the chords along which the quadratic element's strain is measured."""
    t = np.asarray(tri6, dtype=np.int64)
    pairs = np.concatenate(
        [t[:, [0, 3]], t[:, [3, 1]], t[:, [1, 4]], t[:, [4, 2]], t[:, [2, 5]], t[:, [5, 0]]]
    )
    return np.unique(np.sort(pairs, axis=1), axis=0)


def corner_edges(tri6: IntArray) -> IntArray:
    """``(k, 2)`` the S6 elements' corner-to-corner edges (each once): the
    chords between driven nodes when only the corners are driven."""
    t = np.asarray(tri6, dtype=np.int64)
    pairs = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    return np.unique(np.sort(pairs, axis=1), axis=0)


def ramp_strain(a: Array, b: Array, edges: IntArray) -> Array:
    """``(k,)`` the strain of each chord at the midpoint of a linear ramp from
    form ``a`` to form ``b`` (``(n, 3)`` each): ``|c_mid| / mean(|c_a|, |c_b|)
    - 1`` (negative: shortened; zero for a pure translation, and for any
    motion that keeps every chord's direction)."""
    ca = a[edges[:, 1]] - a[edges[:, 0]]
    cb = b[edges[:, 1]] - b[edges[:, 0]]
    la, lb = np.linalg.norm(ca, axis=1), np.linalg.norm(cb, axis=1)
    lm = np.linalg.norm(0.5 * (ca + cb), axis=1)
    return lm / (0.5 * (la + lb)) - 1.0


def kabsch(p: Array, q: Array, w: Array) -> tuple[Array, Array]:
    """``(rotation, translation)``: the proper rigid motion that brings points
    ``p`` closest to ``q`` (``(n, 3)``) with weights ``w`` (Kabsch's method)."""
    w = np.asarray(w, dtype=float) / np.sum(w)
    pc, qc = w @ p, w @ q
    h = (p - pc).T @ ((q - qc) * w[:, None])
    u, _, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(vt.T @ u.T)) or 1.0
    rot = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    return rot, qc - rot @ pc


def align_chain(start: Array, forms: Sequence[Array], weights: Array) -> list[Array]:
    """Each form moved rigidly onto the one before it (the first onto
    ``start``, the flat sheet): the forms' shapes unchanged, the rigid motion
    between consecutive forms removed in the weighted least-squares sense."""
    out: list[Array] = []
    prev = np.asarray(start, dtype=float)
    for f in forms:
        rot, tr = kabsch(np.asarray(f, dtype=float), prev, weights)
        prev = np.asarray(f, dtype=float) @ rot.T + tr
        out.append(prev)
    return out


@dataclass(frozen=True)
class Path:
    """A driven path: the step ends and each step's worst ramp strain.

    Attributes:
        s: ``(k,)`` the forms' parameters, increasing to 1 (0 is the flat sheet).
        forms: ``(k, n, 3)`` the node positions of each form (aligned when
            built with ``align=True``), in the unit the form function returns.
        worst: ``(k,)`` the largest ``|ramp_strain|`` of the step ending at
            each form (dimensionless).
    """

    s: Array
    forms: Array
    worst: Array


def graded_steps(
    form: Callable[[float], Array],
    flat: Array,
    edges: IntArray,
    weights: Array,
    *,
    bound: float,
    start: int = 10,
    align: bool = True,
    max_steps: int = 400,
) -> Path:
    """The forms ``form(s)`` on a grid of s that starts with ``start`` equal
    steps and halves every step whose ramp strain exceeds ``bound``, until
    none does (or ``max_steps`` forms: then the worst is left above the bound,
    and :attr:`Path.worst` shows it). With ``align``, every form is moved
    rigidly onto the one before it (:func:`align_chain`) before the ramp is
    measured."""
    cache: dict[float, Array] = {}

    def at(s: float) -> Array:
        if s not in cache:
            cache[s] = np.asarray(form(s), dtype=float)
        return cache[s]

    s = list(np.linspace(0.0, 1.0, start + 1)[1:])
    while True:
        raw = [at(v) for v in s]
        forms = align_chain(flat, raw, weights) if align else raw
        prev = [np.asarray(flat, dtype=float), *forms[:-1]]
        worst = np.array(
            [np.abs(ramp_strain(a, b, edges)).max() for a, b in zip(prev, forms, strict=True)]
        )
        bad = np.flatnonzero(worst > bound)
        if not len(bad) or len(s) + len(bad) > max_steps:
            return Path(np.array(s), np.array(forms), worst)
        lo = [0.0, *s[:-1]]
        s = sorted(set(s) | {0.5 * (lo[k] + s[k]) for k in bad})


#: the in-plane integration points of ccx's 6-node triangles (area coordinates)
S6_POINTS = ((1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3))


def s6_membrane_strain(flat: Array, x: Array, tri6: IntArray) -> Array:
    """``(m,)`` the largest ``|E_ij|`` of the Green membrane strain over each
    S6 element's three in-plane points, with the element's nodes at ``x``
    ``(n, 3)`` and its flat shape ``flat`` ``(n, 2)`` (corners 1-3, then the
    midpoints of edges 1-2, 2-3, 3-1). Nodes placed on an isometric form
    strain the quadratic element nonetheless, by about (kappa h)^2 / 8: what
    driving every node forces on it."""
    tri6 = np.asarray(tri6, dtype=np.int64)
    x_e, f_e = np.asarray(x)[tri6], np.asarray(flat)[tri6][:, :, :2]
    worst = np.zeros(len(tri6))
    for r, s in S6_POINTS:
        t = 1.0 - r - s
        dr = [1 - 4 * t, 4 * r - 1, 0.0, 4 * (t - r), 4 * s, -4 * s]
        ds = [1 - 4 * t, 0.0, 4 * s - 1, -4 * r, 4 * r, 4 * (t - s)]
        d = np.array([dr, ds])
        j0 = np.einsum("ij,ejk->eik", d, f_e)
        jx = np.einsum("ij,ejk->eik", d, x_e)
        f = np.linalg.solve(j0, jx)  # dx/dX, (m, 2, 3)
        e = 0.5 * (np.einsum("eik,ejk->eij", f, f) - np.eye(2))
        worst = np.maximum(worst, np.abs(e).max(axis=(1, 2)))
    return worst
