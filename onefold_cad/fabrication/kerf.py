"""The kerf's offset of the blank's outline: the cutting path.

Plain numpy: each corner of the offset outline is where the two offset edges
beside it meet (a mitred corner), so every edge moves exactly the offset.
tests/fabrication/test_kerf.py holds it to ezdxf's ``offset_vertices_2d``.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array

__all__ = ["offset_outline"]


def offset_outline(outline: Array, distance: float) -> Array:
    """``(n, 2)`` the closed counter-clockwise ``outline`` ``(n, 2)`` (no
    repeated closing vertex, no U-turn) offset outwards by ``distance``
    (length) with mitred corners: each edge moves exactly ``distance``.

    Corner i moves by ``distance (m + n) / (1 + m . n)``, with m and n the
    outward unit normals of the edges that end and start there.
    """
    p = np.asarray(outline, dtype=float)
    d = np.roll(p, -1, axis=0) - p  # edge i runs from vertex i to vertex i + 1
    d /= np.hypot(d[:, 0], d[:, 1])[:, None]
    n = np.stack([d[:, 1], -d[:, 0]], axis=-1)  # right of the edge: outwards
    m = np.roll(n, 1, axis=0)  # the edge that ends at vertex i
    return p + distance * (m + n) / (1.0 + np.einsum("ij,ij->i", m, n))[:, None]
