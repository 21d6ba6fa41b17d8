"""Points of the frame curve (paper section 3.2) in the fold frame.

The arc is parametrised by its polar angle phi about the arc's centre,
phi in [-alpha, 180 + alpha] (radians inside the package): phi = -alpha is the
f-line's +x end, phi = 180 + alpha its -x end. A point at distance d from the
chord maps to (x, d cos(beta), d sin(beta)).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.params import FrameCurve

__all__ = ["arc_range", "arc_points", "arc_tangents", "division_angles"]


def arc_range(frame: FrameCurve) -> tuple[float, float]:
    """The arc parameter range ``(phi_start, phi_end)`` in radians."""
    a = math.radians(frame.alpha)
    return -a, math.pi + a


def arc_points(frame: FrameCurve, phi: ArrayLike) -> NDArray[np.float64]:
    """Frame-curve points ``(k, 3)`` at arc parameters ``phi`` (radians)."""
    ph = np.asarray(phi, dtype=float)
    r = frame.radius
    a, b = math.radians(frame.alpha), math.radians(frame.beta)
    x = -frame.h_c + r * np.cos(ph)
    d = r * math.sin(a) + r * np.sin(ph)
    return np.stack([x, d * math.cos(b), d * math.sin(b)], axis=-1)


def arc_tangents(frame: FrameCurve, phi: ArrayLike) -> NDArray[np.float64]:
    """Derivatives ``dP/dphi`` ``(k, 3)`` of the frame curve (length per radian)."""
    ph = np.asarray(phi, dtype=float)
    r = frame.radius
    b = math.radians(frame.beta)
    dd = r * np.cos(ph)
    return np.stack([-r * np.sin(ph), dd * math.cos(b), dd * math.sin(b)], axis=-1)


def division_angles(frame: FrameCurve) -> NDArray[np.float64]:
    """The ``divisions + 1`` equally spaced arc parameters of the paper's fan."""
    p0, p1 = arc_range(frame)
    n = frame.divisions
    phi = p0 + (p1 - p0) * (np.arange(n + 1) / n)
    phi[-1] = p1
    return phi
