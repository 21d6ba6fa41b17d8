"""The direction-surface interface shared by the paper's fan and the exact cone.

A direction-surface describes one side (y >= 0) of the fold as a map from the
flat polar angle theta in [0, pi] (radians, counter-clockwise from +x) to a
unit ruling direction ``u(theta)`` and the unit in-surface direction
``e(theta)`` perpendicular to it, towards increasing theta. A flat point at
polar coordinates (r, theta) folds to ``A + r * u(theta)``; its
neighbourhood's top-side normal is ``u x e``.

The angle condition. With the apex A = (0, 0, h), S(h) is the developed angle
of one side (the sum of the fan's apex angles, or the length of the cone's
spherical image). Both are evaluated in the plane of the frame curve: A's foot
there is F = (0, h sin(beta)) (x along the f-line, d away from it) and A lies
t = h cos(beta) off the plane, so with p = P - F the in-plane vector from F to
a frame point P, the apex angle of P_i, P_i+1 is

    atan2(sqrt((p_i x e_i)^2 + t^2 |e_i|^2), p_i . p_i+1 + t^2),  e_i = P_i+1 - P_i,

where every factor is a product of differences of exactly placed points (no
cancellation). Heights passed to :meth:`DirectionSurface.excess` and its
siblings are in units of R; the public :meth:`DirectionSurface.angle_sum`
takes lengths.

For a tiny excess S - pi (beta near 0, where max S - pi is of the order of
sin(beta)^2), :meth:`DirectionSurface.excess_accurate` splits S - pi into the
in-plane sweep of the frame curve seen from F, which is pi + atan(h sin(beta)
/ L+) + atan(h sin(beta) / L-) exactly when F lies inside it, minus the
deficits phi_i - gamma_i of the lifted angles, each computed to a relative
rounding error: S - pi then keeps its relative accuracy however small it is.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.geometry.frame_curve import ArcGeometry, FrameCurve
from onefold_cad.geometry.numeric import Array

__all__ = ["EPS", "DirectionSurface"]

#: The double-precision unit roundoff 2^-52.
EPS = 2.0**-52


class DirectionSurface(ABC):
    """One side's direction-surface over a frame curve, apex at (0, 0, h).

    Attributes:
        frame: the frame curve.
        geometry: its scalars in units of R (:class:`ArcGeometry`).
        height: the apex height h once :meth:`set_apex` was called (length).
    """

    def __init__(self, frame: FrameCurve) -> None:
        self.frame = frame
        self.geometry: ArcGeometry = frame.geometry
        self.height: float | None = None

    # -- the angle condition (heights in units of R) ---------------------------
    @abstractmethod
    def excess(self, h: float) -> float:
        """S(h) - pi (radians) for the apex at height ``h`` (units of R)."""

    @abstractmethod
    def excesses(self, h: Array) -> Array:
        """:meth:`excess` at several heights ``(k,)`` (units of R) at once."""

    @abstractmethod
    def excess_bound(self) -> float:
        """A bound on the rounding error of :meth:`excess` (radians)."""

    @abstractmethod
    def excess_accurate(self, h: float) -> tuple[float, float]:
        """S(h) - pi and a bound on its error (radians), the bound relative to
        the size of the terms of S - pi (see the module docstring)."""

    @abstractmethod
    def excess_and_slope(self, h: float) -> tuple[float, float]:
        """S(h) - pi (radians) and dS/dh (radians per unit of R), analytically."""

    @abstractmethod
    def verify(self, target: float = 0.0) -> tuple[float, float]:
        """At the apex set by :meth:`set_apex`: S(h) - pi evaluated independently
        of :meth:`excess` (another formula or another quadrature), and a bound on
        that value's error, rounding and the inputs' own rounding included
        (radians). A cheaper, looser bound may be returned when it still proves
        ``|S(h) - pi| <= target``."""

    # -- public, in lengths ---------------------------------------------------
    def angle_sum(self, h: float) -> float:
        """Sum of the apex angles of one side (radians) for the apex at height h."""
        return math.pi + self.excess(float(h) / self.geometry.radius)

    def angle_sums(self, h: ArrayLike) -> Array:
        """S(h) for many apex heights at once: ``(m,)`` heights -> ``(m,)`` radians."""
        hh = np.asarray(h, dtype=float) / self.geometry.radius
        return math.pi + self.excesses(hh)

    def angle_sum_and_slope(self, h: float) -> tuple[float, float]:
        """S(h) (radians) and dS/dh (radians per length), analytically."""
        r = self.geometry.radius
        f, slope = self.excess_and_slope(float(h) / r)
        return math.pi + f, slope / r

    @abstractmethod
    def set_apex(self, h: float) -> None:
        """Fix the apex height (length); afterwards :meth:`frames` may be called."""

    @abstractmethod
    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        """Unit ruling directions ``u`` and in-surface normals ``e`` ``(k, 3)``
        at flat angles ``theta`` in [0, total angle] (radians)."""

    def directions_at(self, theta: ArrayLike) -> Array:
        """The ``u`` of :meth:`frames` alone."""
        return self.frames(theta)[0]

    def frame_at(self, theta: float) -> tuple[list[float], list[float]]:
        """``u`` and ``e`` of :meth:`frames` at one flat angle, as floats."""
        u, e = self.frames(np.array([theta]))
        return u[0].tolist(), e[0].tolist()

    @property
    @abstractmethod
    def total_angle(self) -> float:
        """The developed angle of one side at the fixed apex (radians)."""

    @property
    def apex(self) -> Array:
        """The apex ``(3,)``."""
        if self.height is None:
            raise RuntimeError("apex height not set")
        return np.array([0.0, 0.0, self.height])
