"""The kerf's offset of the blank's outline: the cutting path.

The one exception to "no CAD library below :mod:`onefold_cad.export`": the
mitred offset is ezdxf's (``ezdxf.math.offset_vertices_2d``, its pure
geometry package, no document model or drawing back-end), imported here only
when a kerf is cut, so that every file written with a kerf keeps its bytes.
``onefold solve`` of a design without a kerf never imports it.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array

__all__ = ["offset_outline"]


def offset_outline(outline: Array, distance: float) -> Array:
    """``(n, 2)`` the closed counter-clockwise ``outline`` ``(n, 2)`` offset
    outwards by ``distance`` (length) with mitred corners: each edge moves
    exactly ``distance``."""
    from ezdxf.math import offset_vertices_2d  # noqa: TID251 (see the module docstring)

    return np.array([(p.x, p.y) for p in offset_vertices_2d(outline, -distance, True)])
