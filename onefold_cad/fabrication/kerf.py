"""The kerf's offset of the blank's outline: the cutting path.

Plain numpy: each corner of the offset outline is where the two offset edges
beside it meet (a mitred corner), so every edge moves exactly the offset.
tests/fabrication/test_kerf.py holds it to ezdxf's ``offset_vertices_2d``.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.numeric import Array

__all__ = ["offset_outline"]


def offset_outline(outline: Array, distance: float) -> Array:
    """``(n, 2)`` the closed counter-clockwise ``outline`` ``(n, 2)`` (no
    repeated closing vertex, no U-turn) offset outwards by ``distance``
    (length) with mitred corners: each edge moves exactly ``distance``.

    Corner i moves by ``distance (m + n) / (1 + m . n)``, with m and n the
    outward unit normals of the edges that end and start there, computed as
    ``2 distance (m + n) / |m + n|^2`` (the same, since ``|m + n|^2 = 2 (1 +
    m . n)``): at a needle-sharp corner ``1 + m . n`` is lost to rounding
    (a corner of 1e-8 rad leaves 5e-17 beside the 1) while ``m + n`` keeps
    its digits, so the mitre of a sliver's tip is finite and right.

    Raises:
        InvalidParameterError: ('kerf') a corner turns back on itself within
            the rounding of its normals (``m + n`` is 0): its mitre has no end.
    """
    p = np.asarray(outline, dtype=float)
    d = np.roll(p, -1, axis=0) - p  # edge i runs from vertex i to vertex i + 1
    d /= np.hypot(d[:, 0], d[:, 1])[:, None]
    n = np.stack([d[:, 1], -d[:, 0]], axis=-1)  # right of the edge: outwards
    m = np.roll(n, 1, axis=0)  # the edge that ends at vertex i
    s = m + n
    s2 = np.einsum("ij,ij->i", s, s)
    if distance != 0.0 and not np.all(s2 > 0.0):
        i = int(np.argmin(s2))
        raise InvalidParameterError(
            "kerf",
            f"the blank's corner at ({p[i, 0]:.6g}, {p[i, 1]:.6g}) turns back on itself "
            "(an angle of 0 within rounding): its kerf offset has no end",
        )
    return p + (2.0 * distance) * s / s2[:, None]
