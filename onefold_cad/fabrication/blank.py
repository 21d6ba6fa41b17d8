"""The compensated blank's pieces in the fold frame: each side's outline moved
towards the fold line and cut at the bend zones, consecutive points merged,
and the ruling segments clipped to the flat flanges (numpy only; lengths in
the design's unit)."""

from __future__ import annotations

import math

import numpy as np

from onefold_cad.errors import FabricationError
from onefold_cad.geometry.numeric import Array, edge_lengths_2d

__all__ = ["at_height", "compensate", "dedupe", "ruling_segments"]


def at_height(a: Array, b: Array, c: float) -> Array:
    """The point of the line through ``a`` and ``b`` at height y = ``c`` (their
    midpoint when the line is level)."""
    if a[1] == b[1]:
        return (a + b) / 2.0
    s = (c - a[1]) / (b[1] - a[1])
    return np.array([a[0] + s * (b[0] - a[0]), c])


def clip_chain(chain: Array, c_start: float, c_end: float) -> Array:
    """One side's chain (y > 0 side, moved towards the fold line), from one
    fold-line end to the other, cut at the bend zones: ``[start, inner
    vertices..., end]``, where start is the first edge's crossing of
    y = ``c_start`` (or the moved crease end itself when it already lies outside
    the zone) and end likewise with ``c_end``. :func:`check_bends` has made
    sure that the inner vertices clear the zones."""
    y = chain[:, 1]
    if not (c_start < y[1] and c_end < y[-2]):
        raise FabricationError(
            "bend_radius", "the compensated outline is invalid: a corner next to a crease end "
            "lies in its bend zone"
        )  # fmt: skip
    first = chain[0] if y[0] >= c_start else at_height(chain[0], chain[1], c_start)
    last = chain[-1] if y[-1] >= c_end else at_height(chain[-1], chain[-2], c_end)
    return np.vstack([first, chain[1:-1], last])


def dedupe(p: Array, tol: float) -> Array:
    """Drop consecutive (cyclic) vertices closer than ``tol``."""
    keep = edge_lengths_2d(p) > tol
    return p[keep]


def compensate(
    vertices: Array, k: int, shift: float, c_plus: float, c_minus: float
) -> tuple[Array, Array]:
    """The compensated upper and lower outline pieces in the fold frame.

    Upper runs from the +x bridge to the -x bridge, lower from -x to +x (CCW).
    """
    mirror = np.array([1.0, -1.0])
    upper = vertices[: k + 1] - np.array([0.0, shift])
    lower = np.vstack([vertices[k:], vertices[:1]]) * mirror - np.array([0.0, shift])
    return (
        clip_chain(upper, c_plus, c_minus),
        clip_chain(lower, c_minus, c_plus) * mirror,
    )


def ruling_segments(ends: Array, shift: float, c: float, hole_r: float) -> tuple[Array, list[int]]:
    """Ruling segments (fold frame) moved with their side, clipped to the
    flat flanges (|y| >= c) and outside the hole (|p| >= hole_r), and the
    index in ``ends`` of each (a ruling left with nothing is dropped)."""
    out, kept = [], []
    for i, e in enumerate(ends):
        s = 1.0 if e[1] > 0.0 else -1.0
        p0, p1 = np.array([0.0, -s * shift]), e - np.array([0.0, s * shift])
        d = p1 - p0
        lo = 0.0
        if c > 0.0 or shift > 0.0:
            lo = (c - s * p0[1]) / (s * d[1])
        if hole_r > 0.0:  # |p0 + u d| >= hole_r
            a, b, cc = d @ d, 2.0 * (p0 @ d), p0 @ p0 - hole_r**2
            disc = b * b - 4.0 * a * cc
            if disc > 0.0:
                lo = max(lo, (-b + math.sqrt(disc)) / (2.0 * a))
        if lo < 1.0 - 1e-9:
            out.append([p0 + max(lo, 0.0) * d, p1])
            kept.append(i)
    return np.array(out, dtype=float).reshape(-1, 2, 2), kept
