"""Wind on a free-standing sheet after EN 1991-1-4 (recommended values).

Peak velocity pressure (clause 4.5, Eq. 4.8) at the reference height ``z``:
``q_p = (1 + 7 I_v) 1/2 rho v_m^2`` with ``v_m = c_r c_o v_b`` (4.3),
``c_r = k_r ln(z / z_0)`` (4.4, ``z`` at least ``z_min``),
``k_r = 0.19 (z_0 / 0.05)^0.07`` (4.5), ``I_v = k_I / (c_o ln(z / z_0))``
(4.7, ``k_I = 1``), ``c_o = 1`` (flat terrain), ``rho = 1.25 kg/m^3`` and
``v_b = c_dir c_season v_b,0`` with both factors 1 (4.2). The terrain
categories' ``z_0`` and ``z_min`` are Table 4.1's.

The net pressure (assumption, stated in the report): the sheet is taken as a
canopy roof (clause 7.3: a roof without walls), its net pressure being its
overall force coefficient ``c_f`` of Table 7.6 (monopitch canopy, pitch 0,
empty underneath: ``phi = 0``) times ``q_p``: +0.2 down, -0.5 up (fully
blocked underneath, ``phi = 1``: -1.3). It acts normal to the surface, and
its centre of pressure lies a quarter of the sheet's plan depth from the
windward edge (clause 7.3(6), Figure 7.16's recommended location): along the
wind, at plan position ``s`` (0 at the windward edge, 1 at the leeward one),
the pressure is ``3 (1 - s)^2`` times its mean, whose centroid is at
``s = 1/4``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.loads.surface import pressure_load

__all__ = [
    "AIR_DENSITY",
    "CANOPY_CF",
    "TERRAIN",
    "Terrain",
    "peak_velocity_pressure",
    "terrain",
    "wind_load",
    "windward_weights",
]

#: Air density (kg/m^3), EN 1991-1-4 4.5(1) NOTE 2.
AIR_DENSITY = 1.25
#: Table 7.6's overall force coefficients c_f of a monopitch canopy at pitch 0:
#: ``down`` for all phi, ``up`` for phi = 0 (empty) and phi = 1 (blocked).
CANOPY_CF = {"down": 0.2, "up": -0.5, "up_blocked": -1.3}


@dataclass(frozen=True)
class Terrain:
    """A terrain category of EN 1991-1-4 Table 4.1.

    Attributes:
        name: '0', 'I', 'II', 'III' or 'IV'.
        z0: the roughness length (m).
        z_min: the minimum height (m).
        description: Table 4.1's words.
    """

    name: str
    z0: float
    z_min: float
    description: str


TERRAIN = {
    t.name: t
    for t in (
        Terrain("0", 0.003, 1.0, "sea or coastal area exposed to the open sea"),
        Terrain("I", 0.01, 1.0, "lakes or flat and horizontal area with negligible vegetation"),
        Terrain("II", 0.05, 2.0, "low vegetation, isolated obstacles (open country)"),
        Terrain("III", 0.3, 5.0, "regular cover of vegetation or buildings (suburbs, forest)"),
        Terrain("IV", 1.0, 10.0, "at least 15 % of the surface built over 15 m high (town)"),
    )
}


def terrain(name: str) -> Terrain:
    """The category named ``name`` (``0``, ``I`` ... ``IV``; ``2`` for ``II``).

    Raises:
        InvalidParameterError: an unknown category (``terrain``).
    """
    key = str(name).strip().upper()
    roman = {"1": "I", "2": "II", "3": "III", "4": "IV"}
    key = roman.get(key, key)
    if key not in TERRAIN:
        raise InvalidParameterError(
            "terrain",
            f"must be one of EN 1991-1-4's terrain categories {', '.join(TERRAIN)}, got {name!r}",
        )
    return TERRAIN[key]


def peak_velocity_pressure(v_b: float, z: float, category: Terrain) -> float:
    """``q_p(z)`` (Pa) for the basic wind velocity ``v_b`` (m/s) at height ``z`` (m)."""
    ze = max(float(z), category.z_min)
    k_r = 0.19 * (category.z0 / 0.05) ** 0.07
    log = math.log(ze / category.z0)
    v_m = k_r * log * v_b
    i_v = 1.0 / log
    return (1.0 + 7.0 * i_v) * 0.5 * AIR_DENSITY * v_m**2


def windward_weights(x: Array, triangles: Array, direction_deg: float) -> Array:
    """``(m,)`` each face's pressure relative to the mean, ``3 (1 - s)^2`` with
    ``s`` its centroid's plan position along the wind (0 windward, 1 leeward);
    ``direction_deg``: where the wind blows towards, from +x counter-clockwise."""
    a = math.radians(direction_deg)
    along = x[triangles].mean(axis=1)[:, :2] @ np.array([math.cos(a), math.sin(a)])
    proj = x[:, :2] @ np.array([math.cos(a), math.sin(a)])
    lo, hi = float(proj.min()), float(proj.max())
    s = (along - lo) / (hi - lo)
    return 3.0 * (1.0 - s) ** 2


def wind_load(x: Array, triangles: Array, q_p: float, c: float, direction_deg: float) -> Array:
    """``(n, 3)`` the nodal forces (N) of the wind on nodes ``x`` (m):
    ``c q_p`` (Pa; ``c`` > 0 pushes down on the upper side) distributed by
    :func:`windward_weights`."""
    return pressure_load(x, triangles, c * q_p * windward_weights(x, triangles, direction_deg))
