"""Snow on the sheet after EN 1991-1-3 (persistent design situation).

``s = mu_1 C_e C_t s_k`` (clause 5.2(3), Eq. 5.1) on the horizontal projection
of every face, ``mu_1`` from the face's slope ``alpha`` (Table 5.2: 0.8 up to
30 deg, ``0.8 (60 - alpha) / 30`` up to 60 deg, 0 beyond), ``C_e`` the
exposure coefficient (Table 5.1: 0.8 windswept, 1.0 normal, 1.2 sheltered),
``C_t`` the thermal coefficient (1.0, 5.2(8)). The undrifted
arrangement only: drifts against the fold are not modelled.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.loads.surface import face_vectors, projected_load

__all__ = ["EXPOSURE", "shape_coefficient", "snow_load"]

#: Table 5.1's exposure coefficients C_e.
EXPOSURE = {"windswept": 0.8, "normal": 1.0, "sheltered": 1.2}


def shape_coefficient(alpha_deg: Array) -> Array:
    """Table 5.2's ``mu_1`` for roof slopes ``alpha_deg`` (deg)."""
    a = np.asarray(alpha_deg, dtype=float)
    return np.clip(0.8 * (60.0 - a) / 30.0, 0.0, 0.8)


def snow_load(x: Array, triangles: Array, s_k: float, c_e: float = 1.0, c_t: float = 1.0) -> Array:
    """``(n, 3)`` the nodal forces (N) of the snow ``s_k`` (Pa, on the ground)
    on the sheet's nodes ``x`` (m)."""
    normal = face_vectors(x, triangles)[1]
    slope = np.degrees(np.arccos(np.clip(np.abs(normal[:, 2]), 0.0, 1.0)))
    return projected_load(x, triangles, shape_coefficient(slope) * c_e * c_t * s_k)
