"""Where a body samples the sheet's edges: on the flat sheet, so once per sheet.

Each edge is sampled evenly along its length and evenly in its flat angle
about H (an edge passing close to H sweeps a wide angle in a short length),
as :class:`onefold_cad.geometry.body.FoldedBody` lays out its sheet-edge pieces.
Nothing here depends on the fold: the samples are kept per sheet (a sweep
over the frame's angles folds one sheet many times). Lengths in the sheet's
unit; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from onefold_cad.geometry.numeric import Array, sorted_unique
from onefold_cad.geometry.sheet import Sheet

__all__ = ["EdgeSamples", "edge_samples"]


@dataclass(frozen=True)
class EdgeSamples:
    """One sheet edge's samples.

    Attributes:
        a, b: the edge's ends ``(2,)`` (vertices k and k + 1).
        theta: ``(m,)`` the samples' flat angles on their side (|polar
            angle|), from ``a`` to ``b`` (read-only).
        step: the longest distance between neighbouring samples (length).
    """

    a: Array
    b: Array
    theta: Array
    step: float


def _spread(s: Array) -> Array:
    """Fractions along an edge ``(m,)``, sorted, with 0 and 1 and no two closer
    than 1e-9: a sample within rounding of another (a ray's crossing on an
    even step) would leave the bracket about it no room on that side."""
    inner = sorted_unique(s[(s > 1e-9) & (s < 1.0 - 1e-9)])
    inner = inner[np.concatenate([[True], np.diff(inner) > 1e-9])] if len(inner) else inner
    return np.concatenate([[0.0], inner, [1.0]])


@lru_cache(maxsize=64)
def edge_samples(sheet: Sheet, count: int, max_angle_step: float) -> tuple[EdgeSamples, ...]:
    """The samples of every edge of ``sheet``: ``count`` in all spread by edge
    length (at least 16 an edge), and one at least every ``max_angle_step``
    (radians) of flat angle; kept per sheet and arguments."""
    v = sheet.vertices
    perimeter = sheet.perimeter
    out = []
    for k in range(len(v)):
        a, b = v[k], v[(k + 1) % len(v)]
        length = float(np.hypot(*(b - a)))
        n = max(16, math.ceil(count * length / perimeter))
        ta, tb = (abs(math.atan2(p[1], p[0])) for p in (a, b))
        ang = np.linspace(ta, tb, max(2, math.ceil(abs(tb - ta) / max_angle_step) + 1))
        psi = np.where(a[1] + b[1] < 0.0, -ang, ang)
        ray = sheet.ray_lengths(psi)[:, None] * np.column_stack([np.cos(psi), np.sin(psi)])
        along = np.minimum(np.maximum((ray - a) @ (b - a) / length**2, 0.0), 1.0)
        s_all = _spread(np.concatenate([np.linspace(0.0, 1.0, n), along]))
        q = a + s_all[:, None] * (b - a)
        theta = np.abs(np.arctan2(q[:, 1], q[:, 0]))  # the side's own flat angle
        theta.setflags(write=False)
        out.append(EdgeSamples(a, b, theta, float(np.max(np.diff(s_all))) * length))
    return tuple(out)
