"""Direction-surfaces: the paper's triangle fan and the exact cone over the arc.

Both describe one side (y >= 0) of the fold as a map from the flat polar angle
theta in [0, pi] (radians, counter-clockwise from +x) to a unit ruling
direction ``u(theta)`` and the unit in-surface direction ``e(theta)``
perpendicular to it, towards increasing theta. A flat point at polar
coordinates (r, theta) folds to ``A + r * u(theta)``; its neighbourhood's
top-side normal is ``u x e``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.frame import arc_points, arc_range, arc_tangents, division_angles
from onefold_cad.geometry.params import FrameCurve
from onefold_cad.geometry.validate import cross3

__all__ = ["DirectionSurface", "PaperFan", "ExactCone"]

Array = NDArray[np.float64]


def _unit(v: Array) -> Array:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _angles(a: Array, b: Array) -> Array:
    """Angles between row vectors (radians), accurate for tiny and large angles."""
    c = cross3(a, b)
    return np.arctan2(np.sqrt(np.einsum("ij,ij->i", c, c)), np.einsum("ij,ij->i", a, b))


class DirectionSurface(ABC):
    """One side's direction-surface over a frame curve, apex at (0, 0, h)."""

    def __init__(self, frame: FrameCurve) -> None:
        self.frame = frame
        self.height: float | None = None

    @abstractmethod
    def angle_sum(self, h: float) -> float:
        """Sum of the apex angles of one side (radians) for the apex at height h."""

    @abstractmethod
    def angle_sums(self, h: Array) -> Array:
        """S(h) for many apex heights at once: ``(m,)`` heights -> ``(m,)`` radians."""

    @abstractmethod
    def angle_sum_and_slope(self, h: float) -> tuple[float, float]:
        """S(h) (radians) and dS/dh (radians per length), analytically."""

    @abstractmethod
    def set_apex(self, h: float) -> None:
        """Fix the apex height; afterwards :meth:`frames` may be called."""

    @abstractmethod
    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        """Unit ruling directions ``u`` and in-surface normals ``e`` ``(k, 3)``
        at flat angles ``theta`` in [0, total angle] (radians)."""

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


class PaperFan(DirectionSurface):
    """The fan of ``divisions`` planar triangles of the paper (section 3.2)."""

    def __init__(self, frame: FrameCurve) -> None:
        super().__init__(frame)
        self.points = arc_points(frame, division_angles(frame))
        self._xy = self.points[:, :2]
        self._z = self.points[:, 2]
        self.directions: Array | None = None
        self.gammas: Array | None = None
        self.thetas: Array | None = None

    def _vectors(self, h: float) -> Array:
        v = np.empty_like(self.points)
        v[:, :2] = self._xy
        v[:, 2] = self._z - h
        return v

    def angle_sum(self, h: float) -> float:
        v = self._vectors(h)
        return float(np.sum(_angles(v[:-1], v[1:])))

    def _pair_terms(self) -> tuple[Array, ...]:
        """Per-triangle constants: with a, b consecutive points and the apex at
        height h, (a - h z) x (b - h z) = C - h W and the dot product is
        D - h Z + h^2; so S(h) costs a few array operations."""
        if not hasattr(self, "_terms"):
            a, b = self.points[:-1], self.points[1:]
            c = cross3(a, b)
            w = a - b
            self._terms = (
                c[:, 0].copy(),
                c[:, 1].copy(),
                c[:, 2] ** 2,
                w[:, 1].copy(),
                -w[:, 0],
                np.einsum("ij,ij->i", a, b),
                a[:, 2] + b[:, 2],
            )
        return self._terms

    def angle_sums(self, h: Array) -> Array:
        c1, c2, c3sq, w1, w2, dot0, zs = self._pair_terms()
        hh = np.asarray(h, dtype=float)[:, None]
        s1 = c1 - hh * w1
        s2 = c2 - hh * w2
        sin = np.sqrt(s1 * s1 + s2 * s2 + c3sq)
        cos = dot0 - hh * zs + hh * hh
        return np.arctan2(sin, cos).sum(axis=1)

    def angle_sum_and_slope(self, h: float) -> tuple[float, float]:
        c1, c2, c3sq, w1, w2, dot0, zs = self._pair_terms()
        s1 = c1 - h * w1
        s2 = c2 - h * w2
        sin = np.sqrt(s1 * s1 + s2 * s2 + c3sq)
        cos = dot0 - h * zs + h * h
        dsin = -(s1 * w1 + s2 * w2) / sin
        dcos = 2.0 * h - zs
        slope = (cos * dsin - sin * dcos) / (sin * sin + cos * cos)
        return float(np.arctan2(sin, cos).sum()), float(slope.sum())

    def set_apex(self, h: float) -> None:
        self.height = h
        v = self._vectors(h)
        self.directions = _unit(v)
        self.gammas = _angles(v[:-1], v[1:])
        self.thetas = np.concatenate([[0.0], np.cumsum(self.gammas)])

    @property
    def total_angle(self) -> float:
        assert self.thetas is not None
        return float(self.thetas[-1])

    def sector(self, theta: ArrayLike) -> NDArray[np.int64]:
        """Index k of the triangle whose flat sector [theta_k, theta_k+1] holds theta."""
        assert self.thetas is not None
        t = np.asarray(theta, dtype=float)
        k = np.searchsorted(self.thetas, t, side="right") - 1
        return np.clip(k, 0, len(self.thetas) - 2)

    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        assert self.directions is not None and self.thetas is not None
        assert self.gammas is not None
        t = np.asarray(theta, dtype=float)
        k = self.sector(t)
        d0, d1 = self.directions[k], self.directions[k + 1]
        g = self.gammas[k]
        # unit vector in triangle k's plane, perpendicular to d0, towards d1
        e0 = _unit(d1 - np.cos(g)[:, None] * d0)
        w = (t - self.thetas[k])[:, None]
        u = np.cos(w) * d0 + np.sin(w) * e0
        e = -np.sin(w) * d0 + np.cos(w) * e0
        return u, e


# Composite Gauss-Legendre rule on the arc parameter: the integrand is analytic
# on the closed arc, so this converges geometrically; the test suite checks it
# against a rule with four times as many nodes.
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(20)
_PANELS = 96


class ExactCone(DirectionSurface):
    """The continuous cone from the apex over the circular arc (exact model).

    The developed angle theta(phi) = integral of |u'(phi)| dphi, with u the
    unit vector from the apex to the arc point P(phi), is evaluated by
    composite Gauss-Legendre quadrature and inverted by Newton's method.
    """

    def __init__(self, frame: FrameCurve, panels: int = _PANELS) -> None:
        super().__init__(frame)
        p0, p1 = arc_range(frame)
        self.edges = np.linspace(p0, p1, panels + 1)
        half = 0.5 * np.diff(self.edges)
        mid = 0.5 * (self.edges[:-1] + self.edges[1:])
        self._nodes = (mid[:, None] + half[:, None] * _GL_NODES[None, :]).ravel()
        self._weights = (half[:, None] * _GL_WEIGHTS[None, :]).ravel()
        self._p = arc_points(frame, self._nodes)
        self._dp = arc_tangents(frame, self._nodes)
        self._panel_theta: Array | None = None

    def _speed(self, h: float, p: Array, dp: Array) -> Array:
        """|du/dphi| at arc points p with tangents dp (radians per radian)."""
        v = p.copy()
        v[:, 2] -= h
        c = cross3(dp, v)
        return np.sqrt(np.einsum("ij,ij->i", c, c)) / np.einsum("ij,ij->i", v, v)

    def angle_sum(self, h: float) -> float:
        return float(np.dot(self._weights, self._speed(h, self._p, self._dp)))

    def _node_terms(self) -> tuple[Array, ...]:
        """Per-node constants: with v = P - h z, P' x v = K - h L (L = P' x z)."""
        if not hasattr(self, "_terms"):
            k = cross3(self._dp, self._p)
            self._terms = (
                k[:, 0].copy(),
                k[:, 1].copy(),
                k[:, 2] ** 2,
                self._dp[:, 1].copy(),
                -self._dp[:, 0],
                np.einsum("ij,ij->i", self._p, self._p),
                self._p[:, 2].copy(),
            )
        return self._terms

    def angle_sums(self, h: Array) -> Array:
        k1, k2, k3sq, l1, l2, pp, pz = self._node_terms()
        hh = np.asarray(h, dtype=float)[:, None]
        c1 = k1 - hh * l1
        c2 = k2 - hh * l2
        vv = pp - 2.0 * hh * pz + hh * hh
        return (np.sqrt(c1 * c1 + c2 * c2 + k3sq) / vv) @ self._weights

    def angle_sum_and_slope(self, h: float) -> tuple[float, float]:
        k1, k2, k3sq, l1, l2, pp, pz = self._node_terms()
        c1 = k1 - h * l1
        c2 = k2 - h * l2
        cn = np.sqrt(c1 * c1 + c2 * c2 + k3sq)
        vv = pp - 2.0 * h * pz + h * h
        g = cn / vv
        dg = -(c1 * l1 + c2 * l2) / (cn * vv) - g * (2.0 * h - 2.0 * pz) / vv
        return float(g @ self._weights), float(dg @ self._weights)

    def set_apex(self, h: float) -> None:
        self.height = h
        per_panel = (self._weights * self._speed(h, self._p, self._dp)).reshape(
            len(self.edges) - 1, -1
        )
        self._panel_theta = np.concatenate([[0.0], np.cumsum(per_panel.sum(axis=1))])

    @property
    def total_angle(self) -> float:
        assert self._panel_theta is not None
        return float(self._panel_theta[-1])

    def theta_of_phi(self, phi: ArrayLike) -> Array:
        """Developed angle theta (radians) at arc parameters ``phi``."""
        assert self._panel_theta is not None and self.height is not None
        ph = np.atleast_1d(np.asarray(phi, dtype=float))
        k = np.clip(np.searchsorted(self.edges, ph, side="right") - 1, 0, len(self.edges) - 2)
        a = self.edges[k]
        half = 0.5 * (ph - a)
        nodes = (a + half)[:, None] + half[:, None] * _GL_NODES[None, :]
        flat = nodes.ravel()
        s = self._speed(self.height, arc_points(self.frame, flat), arc_tangents(self.frame, flat))
        partial = (s.reshape(nodes.shape) * _GL_WEIGHTS[None, :]).sum(axis=1) * half
        return self._panel_theta[k] + partial

    def phi_of_theta(self, theta: ArrayLike) -> Array:
        """Arc parameters phi (radians) at developed angles ``theta`` (Newton)."""
        assert self._panel_theta is not None and self.height is not None
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        k = np.clip(np.searchsorted(self._panel_theta, t, side="right") - 1, 0, len(self.edges) - 2)
        span = self._panel_theta[k + 1] - self._panel_theta[k]
        frac = (t - self._panel_theta[k]) / span
        phi = self.edges[k] + frac * (self.edges[k + 1] - self.edges[k])
        lo, hi = self.edges[0], self.edges[-1]
        for _ in range(20):
            f = self.theta_of_phi(phi) - t
            ds = self._speed(
                self.height, arc_points(self.frame, phi), arc_tangents(self.frame, phi)
            )
            step = f / ds
            phi = np.clip(phi - step, lo, hi)
            if float(np.max(np.abs(step), initial=0.0)) <= 1e-14:
                break
        return phi

    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        assert self.height is not None
        phi = self.phi_of_theta(theta)
        v = arc_points(self.frame, phi)
        v[:, 2] -= self.height
        dp = arc_tangents(self.frame, phi)
        u = _unit(v)
        e = _unit(dp - np.einsum("ij,ij->i", dp, u)[:, None] * u)
        return u, e
