"""Where a sheet stands on the site: its resting placement (the fold frame to
the ground, :class:`~onefold_cad.geometry.resting.placement.RestingPlacement`)
followed by the site's turn about the vertical and its move on the ground.

``p_site = Rz(rotation) @ p_rest + (x, y, 0)``; lengths in the site's unit,
the rotation in degrees at the API (counter-clockwise seen from above).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.resting.placement import RestingPlacement

__all__ = ["SitePlacement"]


@dataclass(frozen=True)
class SitePlacement:
    """The rigid motion of a sheet from its resting frame onto the site.

    Attributes:
        x, y: where the resting frame's origin goes (site unit).
        rotation_deg: the turn about the vertical (deg, counter-clockwise
            seen from above).
    """

    x: float
    y: float
    rotation_deg: float

    @property
    def rotation(self) -> Array:
        """``(3, 3)`` the turn about z."""
        c, s = math.cos(math.radians(self.rotation_deg)), math.sin(math.radians(self.rotation_deg))
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    @property
    def translation(self) -> Array:
        """``(3,)`` the move on the ground (z = 0)."""
        return np.array([self.x, self.y, 0.0])

    @property
    def matrix(self) -> Array:
        """``(4, 4)`` homogeneous matrix of the motion."""
        out = np.eye(4)
        out[:3, :3], out[:3, 3] = self.rotation, self.translation
        return out

    def apply(self, points: ArrayLike) -> Array:
        """Resting-frame points ``(k, 3)`` (or ``(k, 2)`` on the ground) on the site."""
        p = np.asarray(points, dtype=float)
        if p.shape[-1] == 2:
            return p @ self.rotation[:2, :2].T + self.translation[:2]
        return p @ self.rotation.T + self.translation

    def compose(self, rest: RestingPlacement) -> Array:
        """``(4, 4)`` fold frame -> site: the resting placement, then this motion."""
        inner = np.eye(4)
        inner[:3, :3] = np.asarray(rest.rotation, dtype=float)
        inner[:3, 3] = np.asarray(rest.translation, dtype=float)
        return self.matrix @ inner
