"""Direction-surfaces: the paper's triangle fan and the exact cone over the arc.

Both describe one side (y >= 0) of the fold as a map from the flat polar angle
theta in [0, pi] (radians, counter-clockwise from +x) to a unit ruling
direction ``u(theta)`` and the unit in-surface direction ``e(theta)``
perpendicular to it, towards increasing theta. A flat point at polar
coordinates (r, theta) folds to ``A + r * u(theta)``; its neighbourhood's
top-side normal is ``u x e``.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.frame import arc_range, division_angles
from onefold_cad.geometry.params import FrameCurve

__all__ = ["DirectionSurface", "PaperFan", "ExactCone"]

Array = NDArray[np.float64]


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

    def refine(self, h: float) -> bool:
        """Make the surface's numerics fit the apex at height h; True if that
        changed S(h), so the apex must be solved again. (Only the exact
        model's quadrature adapts.)"""
        return False

    @abstractmethod
    def set_apex(self, h: float) -> None:
        """Fix the apex height; afterwards :meth:`frames` may be called."""

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


class PaperFan(DirectionSurface):
    """The fan of ``divisions`` planar triangles of the paper (section 3.2).

    Attributes:
        points: ``(divisions + 1, 3)`` the division points of the frame curve,
            from the f-line's +x end to its -x end.
        directions: once the apex is set, the ``(divisions + 1, 3)`` unit
            direction-vectors from the apex to the points.
        gammas: once the apex is set, the ``(divisions,)`` apex angles (radians).
        thetas: once the apex is set, the ``(divisions + 1,)`` cumulative flat
            angles theta_k = gamma_1 + ... + gamma_k (radians), theta_0 = 0.
    """

    def __init__(self, frame: FrameCurve) -> None:
        super().__init__(frame)
        phi = division_angles(frame)
        r = frame.radius
        a, b = math.radians(frame.alpha), math.radians(frame.beta)
        cb, sb = math.cos(b), math.sin(b)
        # the division points (x, d cos b, d sin b), as in frame.arc_points
        x = -frame.h_c + r * np.cos(phi)
        d = r * math.sin(a) + r * np.sin(phi)
        pts = np.empty((len(phi), 3))
        pts[:, 0] = x
        np.multiply(d, cb, out=pts[:, 1])
        np.multiply(d, sb, out=pts[:, 2])
        self.points = pts
        self.directions: Array | None = None
        self.gammas: Array | None = None
        self.thetas: Array | None = None
        # Triangle i has the corners A = (0, 0, h), P_i and P_i+1. With
        # m = x_i d_i+1 - d_i x_i+1 and the differences dx, dd of P_i+1 - P_i,
        #   (P_i - A) x (P_i+1 - A) = (h cb dd, -(sb m + h dx), cb m),
        #   (P_i - A) . (P_i+1 - A) = dot_i - h zs_i + h^2  (zs_i = z_i + z_i+1),
        # so sin^2 and cos of gamma_i (times |P_i - A| |P_i+1 - A|) are quadratics
        # in h: for the solver, the coefficients of (1, h, h^2) of sin^2, cos,
        # d(sin^2)/dh / 2 and d(cos)/dh side by side, so that S(h) and S'(h)
        # cost one matrix product.
        x0, x1, d0, d1 = x[:-1], x[1:], d[:-1], d[1:]
        n = len(x0)
        q = np.zeros((3, 4 * n))
        sin2, cos, dsin2, dcos = (slice(k * n, (k + 1) * n) for k in range(4))
        m = x0 * d1
        m -= d0 * x1
        dx = x1 - x0
        cdd = d1 - d0
        cdd *= cb
        np.multiply(m, m, out=q[0, sin2])
        np.multiply(m, dx, out=q[0, dsin2])
        q[0, dsin2] *= sb
        np.multiply(q[0, dsin2], 2.0, out=q[1, sin2])
        np.multiply(dx, dx, out=q[2, sin2])
        q[2, sin2] += cdd * cdd
        q[1, dsin2] = q[2, sin2]
        np.multiply(x0, x1, out=q[0, cos])
        q[0, cos] += d0 * d1
        np.add(d0, d1, out=q[1, cos])
        q[1, cos] *= -sb
        q[2, cos] = 1.0
        q[0, dcos] = q[1, cos]
        q[1, dcos] = 2.0
        self._quad = q
        self._n = n
        self._terms = (m, dx, cdd, sb, cb)

    def _sin_cos(self, h: Array | float) -> tuple[Array, Array]:
        """|(P_i - A) x (P_i+1 - A)| and (P_i - A) . (P_i+1 - A), from the terms
        unexpanded (``h`` a float or a column ``(k, 1)``)."""
        m, dx, cdd, sb, cb = self._terms
        n = self._n
        s2 = sb * m + h * dx
        t = h * cdd
        cm = cb * m
        dot, zs = self._quad[0, n : 2 * n], self._quad[1, n : 2 * n]
        return np.sqrt(t * t + s2 * s2 + cm * cm), dot + h * (h + zs)

    def angle_sum(self, h: float) -> float:
        return float(np.arctan2(*self._sin_cos(float(h))).sum())

    def angle_sums(self, h: Array) -> Array:
        hh = np.asarray(h, dtype=float)[:, None]
        return np.arctan2(*self._sin_cos(hh)).sum(axis=1)

    def angle_sum_and_slope(self, h: float) -> tuple[float, float]:
        n = self._n
        q = np.array((1.0, h, h * h)) @ self._quad
        sin2, cos, dsin2, dcos = q[:n], q[n : 2 * n], q[2 * n : 3 * n], q[3 * n :]
        sin = np.sqrt(sin2)
        # d/dh atan2(sin, cos) = (cos sin' - sin cos') / (sin^2 + cos^2), sin' = dsin2 / sin
        slope = cos * dsin2
        slope -= sin2 * dcos
        den = cos * cos
        den += sin2
        den *= sin
        slope /= den
        return float(np.arctan2(sin, cos).sum()), float(slope.sum())

    def set_apex(self, h: float) -> None:
        self.height = h
        v = self.points.copy()
        v[:, 2] -= h
        v /= np.sqrt(np.einsum("ij,ij->i", v, v))[:, None]
        self.directions = v
        # gamma_i from the chord between unit vectors: 2 asin(|d_i+1 - d_i| / 2)
        chord = v[1:] - v[:-1]
        half = np.sqrt(np.einsum("ij,ij->i", chord, chord))
        half *= 0.5
        gammas = np.arcsin(half, out=half)
        gammas *= 2.0
        self.gammas = gammas
        thetas = np.empty(len(v))
        thetas[0] = 0.0
        np.cumsum(gammas, out=thetas[1:])
        self.thetas = thetas

    @property
    def total_angle(self) -> float:
        assert self.thetas is not None
        return float(self.thetas[-1])

    def sector(self, theta: ArrayLike) -> NDArray[np.int64]:
        """Index k of the triangle whose flat sector [theta_k, theta_k+1] holds theta."""
        assert self.thetas is not None
        k = self.thetas.searchsorted(np.asarray(theta, dtype=float), side="right")
        k -= 1
        np.minimum(k, len(self.thetas) - 2, out=k)
        return np.maximum(k, 0, out=k)

    # In triangle k, with g its apex angle, the ray at the flat angle w from
    # direction d_k is the spherical interpolation (slerp) of d_k and d_k+1,
    #   u = (sin(g - w) d_k + sin(w) d_k+1) / sin(g),
    # and its in-surface direction is e = du/dw
    #   = (cos(w) d_k+1 - cos(g - w) d_k) / sin(g);
    # on a division (w = 0) u is d_k exactly.

    def _locate(self, theta: ArrayLike) -> tuple[NDArray[np.int64], Array]:
        """The triangles k holding flat angles ``theta`` and the angles w
        (radians) of ``theta`` from direction k."""
        assert self.thetas is not None
        t = np.asarray(theta, dtype=float)
        k = self.sector(t)
        return k, t - self.thetas.take(k)

    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        assert self.directions is not None and self.gammas is not None
        k, w = self._locate(theta)
        g = self.gammas.take(k)
        rest = g - w
        sg = np.sin(g)
        a0, a1 = np.sin(rest), np.sin(w)
        b0, b1 = np.cos(rest), np.cos(w)
        a0 /= sg
        a1 /= sg
        b0 /= sg
        b1 /= sg
        d0 = self.directions.take(k, axis=0)
        d1 = self.directions.take(k + 1, axis=0)
        u = a0[:, None] * d0
        u += a1[:, None] * d1
        e = b1[:, None] * d1
        e -= b0[:, None] * d0
        return u, e

    def directions_at(self, theta: ArrayLike) -> Array:
        """The unit ruling directions ``(k, 3)`` at flat angles ``theta``: the
        ``u`` of :meth:`frames`. Rays on a division are gathered; the few
        others (a sheet's vertex rays) are interpolated one by one."""
        assert self.directions is not None
        k, w = self._locate(theta)
        u = self.directions.take(k, axis=0)
        (off,) = w.nonzero()
        if len(off) > _FEW:
            u[off] = self.frames(np.asarray(theta, dtype=float)[off])[0]
        else:
            for j in off.tolist():
                u[j] = self._frame1(int(k[j]), float(w[j]))[0]
        return u

    def frame_at(self, theta: float) -> tuple[list[float], list[float]]:
        """``u`` and ``e`` of :meth:`frames` at one flat angle, as floats."""
        assert self.thetas is not None
        k = int(self.thetas.searchsorted(theta, side="right")) - 1
        k = min(max(k, 0), len(self.thetas) - 2)
        return self._frame1(k, theta - float(self.thetas[k]))

    def _frame1(self, k: int, w: float) -> tuple[list[float], list[float]]:
        """The slerp of triangle k at angle w, in plain Python (faster than
        numpy for one ray)."""
        assert self.directions is not None and self.gammas is not None
        g = float(self.gammas[k])
        sg = math.sin(g)
        a0, a1 = math.sin(g - w) / sg, math.sin(w) / sg
        b0, b1 = math.cos(g - w) / sg, math.cos(w) / sg
        d0, d1 = self.directions[k].tolist(), self.directions[k + 1].tolist()
        u = [a0 * p + a1 * q for p, q in zip(d0, d1, strict=True)]
        e = [b1 * q - b0 * p for p, q in zip(d0, d1, strict=True)]
        return u, e


#: Up to this many rays are interpolated in plain Python by PaperFan.directions_at.
_FEW = 8


# Composite Gauss-Legendre rule on the arc parameter, 20 nodes per panel. The
# integrand is analytic on the closed arc. Its complex singularities include
# the zeros of |P(phi) - A|^2 = K0 + K1 cos(phi) + K2 sin(phi), at imaginary
# distance acosh(K0 / hypot(K1, K2)) from the real axis: panels no wider than
# 2 * _PANEL_REACH times that distance leave them outside the Bernstein
# ellipse of parameter 5, where the 20-point rule's error is about 5^-40.
# The zeros of |P' x (P - A)| approach the real axis as beta -> 90 deg; those
# show in the Legendre coefficients of the integrand on each panel, so the
# rule is checked at the apex and refined (panels doubled, up to _MAX_PANELS)
# until the last two coefficients are below _TAIL_TOL of the integrand.
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(20)
_PANEL_REACH = 0.4
_MAX_PANELS = 16384
_TAIL_TOL = 1e-12
#: Rows of the last two Legendre coefficients of the polynomial through the nodes.
_TAIL = np.linalg.inv(np.polynomial.legendre.legvander(_GL_NODES, 19))[-2:]


def _integration_matrix(nodes: Array) -> Array:
    """M with (M @ f)_i = integral from -1 to nodes_i of the polynomial that
    interpolates f at ``nodes`` (exact for polynomials of degree < len(nodes))."""
    leg = np.polynomial.legendre
    n = len(nodes)
    # column j: the integral from -1 of the Legendre polynomial P_j, at the nodes
    integrals = leg.legval(nodes, leg.legint(np.eye(n), lbnd=-1)).T
    return integrals @ np.linalg.inv(leg.legvander(nodes, n - 1))


#: theta at the nodes of a panel from the integrand there (for initial guesses).
_NODE_INTEGRALS = _integration_matrix(_GL_NODES)


class ExactCone(DirectionSurface):
    """The continuous cone from the apex over the circular arc (exact model).

    The developed angle theta(phi) = integral of |u'(phi)| dphi, with u the
    unit vector from the apex to the arc point P(phi), is evaluated by
    composite Gauss-Legendre quadrature (``panels`` panels of 20 nodes; by
    default as many as the apex height needs, see :meth:`refine`) and
    inverted by Newton's method.

    With c = cos(phi), s = sin(phi), w = R - h_c c + R sin(alpha) s and
    d = R sin(alpha) + R s:
    |u'| = R |(h cb c, sb w - h s, cb w)| / |P - A|^2,
    |P - A|^2 = (R c - h_c)^2 + d^2 - 2 h sb d + h^2 (cb, sb: cos and sin of beta).
    """

    def __init__(self, frame: FrameCurve, panels: int | None = None) -> None:
        super().__init__(frame)
        r = frame.radius
        a, b = math.radians(frame.alpha), math.radians(frame.beta)
        self._r, self._hc, self._rsa = r, frame.h_c, r * math.sin(a)
        self._cb, self._sb = math.cos(b), math.sin(b)
        self.fixed_panels = panels
        self._panel_theta: Array | None = None
        self._node_speed: Array | None = None  # |u'| at the nodes, (panels, 20)
        self._table: tuple[Array, Array] | None = None  # see _node_table
        self._checked: tuple[float, Array] | None = None  # see refine
        if panels is None:
            l0 = frame.paper_lower_bound
            panels = max(self._panels_for(l0), self._panels_for(2.0 * l0))
        self._build(panels)

    # -- the quadrature rule -------------------------------------------------
    def _panels_for(self, h: float) -> int:
        """Panels the rule needs for the apex at height h (see _PANEL_REACH)."""
        r, hc, rsa, sb = self._r, self._hc, self._rsa, self._sb
        k0 = r * r + hc * hc + rsa * rsa - 2.0 * h * sb * rsa + h * h
        reach = math.acosh(max(k0 / math.hypot(2.0 * r * hc, 2.0 * r * (rsa - h * sb)), 1.0))
        span = math.pi + 2.0 * math.radians(self.frame.alpha)
        if not reach > 0.0:
            return _MAX_PANELS
        return min(_MAX_PANELS, max(1, math.ceil(0.5 * span / (_PANEL_REACH * reach))))

    def _build(self, panels: int) -> None:
        self._checked = None
        p0, p1 = arc_range(self.frame)
        width = (p1 - p0) / panels
        self.edges = np.arange(panels + 1) * width + p0
        self.edges[-1] = p1
        half = 0.5 * width
        mid = self.edges[:-1] + half
        self._half = half
        self._nodes = (mid[:, None] + half * _GL_NODES).ravel()
        self._node_phi = np.concatenate(((p0,), self._nodes, (p1,)))
        weights = np.empty((panels, len(_GL_WEIGHTS)))
        weights[:] = half * _GL_WEIGHTS
        self._weights = weights.ravel()
        c, s = np.cos(self._nodes), np.sin(self._nodes)
        self._cs = (c, s)
        r, hc, rsa, sb, cb = self._r, self._hc, self._rsa, self._sb, self._cb
        # |u'| = r sqrt(w^2 - 2 h sb w s + h^2 (cb^2 c^2 + s^2)) / (x^2 + d^2 - 2 h sb d + h^2):
        # quadratics in h, side by side as coefficients of (1, h, h^2) for the
        # numerator^2, the denominator and half their derivatives
        w = r - hc * c + rsa * s
        d = rsa + r * s
        n = len(c)
        q = np.zeros((3, 4 * n))
        half_b = -sb * w * s
        c2 = (cb * c) ** 2 + s * s
        half_e = -sb * d
        # |P|^2 = (r c - h_c)^2 + d^2
        pp = (r * r + hc * hc + rsa * rsa) - (2.0 * r * hc) * c + (2.0 * r * rsa) * s
        q[0, :n], q[1, :n], q[2, :n] = w * w, 2.0 * half_b, c2
        q[0, n : 2 * n], q[1, n : 2 * n], q[2, n : 2 * n] = pp, 2.0 * half_e, 1.0
        q[0, 2 * n : 3 * n], q[1, 2 * n : 3 * n] = half_b, c2
        q[0, 3 * n :], q[1, 3 * n :] = half_e, 1.0
        self._quad = q
        self._n = n
        self._rw = r * self._weights

    def refine(self, h: float) -> bool:
        """Make the rule fine enough for the apex at height h; True if it changed
        (the apex must then be solved again)."""
        if self.fixed_panels is not None:
            return False
        panels = len(self.edges) - 1
        need = self._panels_for(h)
        if need <= panels:
            speed = self._speed_cs(h, *self._cs).reshape(panels, -1)
            tail = float(np.abs(speed @ _TAIL.T).max())
            if tail <= _TAIL_TOL * float(speed.max()) or panels >= _MAX_PANELS:
                self._checked = (h, speed)  # set_apex(h) reuses it
                return False
            need = 2 * panels
        self._build(min(need, _MAX_PANELS))
        return True

    def _speed_cs(self, h: float | Array, c: Array, s: Array) -> Array:
        """|u'(phi)| (radians per radian) at arc parameters with cosines ``c`` and
        sines ``s``, for apex heights ``h`` (a float, or an array broadcasting)."""
        r, hc, rsa, sb, cb = self._r, self._hc, self._rsa, self._sb, self._cb
        w = r - hc * c + rsa * s
        t1 = (h * cb) * c
        t2 = sb * w - h * s
        t3 = cb * w
        # |P - A|^2 = k0 + k1 c + k2 s
        k0 = r * r + hc * hc + rsa * rsa - 2.0 * h * sb * rsa + h * h
        vv = k0 - (2.0 * r * hc) * c + (2.0 * r) * (rsa - h * sb) * s
        return r * np.sqrt(t1 * t1 + t2 * t2 + t3 * t3) / vv

    def _speed(self, h: float, phi: Array) -> Array:
        return self._speed_cs(h, np.cos(phi), np.sin(phi))

    # -- the angle condition ---------------------------------------------------
    def angle_sum(self, h: float) -> float:
        return float(self._speed_cs(float(h), *self._cs) @ self._weights)

    def angle_sums(self, h: Array) -> Array:
        hh = np.asarray(h, dtype=float)[:, None]
        c, s = self._cs
        return self._speed_cs(hh, c[None, :], s[None, :]) @ self._weights

    def angle_sum_and_slope(self, h: float) -> tuple[float, float]:
        n = self._n
        q = np.array((1.0, h, h * h)) @ self._quad
        num2, vv, dnum, dvv = q[:n], q[n : 2 * n], q[2 * n : 3 * n], q[3 * n :]
        g = np.sqrt(num2)
        g /= vv
        # d/dh [sqrt(num2) / vv] = g (num2' / (2 num2) - vv' / vv)
        slope = g * (dnum / num2 - 2.0 * dvv / vv)
        return float(g @ self._rw), float(slope @ self._rw)

    def set_apex(self, h: float) -> None:
        self.height = h
        panels = len(self.edges) - 1
        if self._checked is not None and self._checked[0] == h:
            speed = self._checked[1]
        else:
            speed = self._speed_cs(h, *self._cs).reshape(panels, -1)
        theta = np.empty(panels + 1)
        theta[0] = 0.0
        np.cumsum(speed @ (self._half * _GL_WEIGHTS), out=theta[1:])
        self._panel_theta = theta
        self._node_speed = speed
        self._table = None

    def _node_table(self) -> tuple[Array, Array]:
        """theta and phi, ascending, at the start of the arc, every node and the
        end of the arc (for first guesses of :meth:`phi_of_theta`)."""
        if self._table is None:
            assert self._panel_theta is not None and self._node_speed is not None
            theta = self._panel_theta
            nodes = self._node_speed @ (self._half * _NODE_INTEGRALS.T)
            nodes += theta[:-1, None]
            self._table = (np.concatenate(((0.0,), nodes.ravel(), theta[-1:])), self._node_phi)
        return self._table

    @property
    def total_angle(self) -> float:
        assert self._panel_theta is not None
        return float(self._panel_theta[-1])

    # -- theta(phi) and its inverse --------------------------------------------
    def _theta_and_speed(self, phi: Array) -> tuple[Array, Array]:
        """theta(phi) (by a 20-point rule from the start of phi's panel) and
        |u'(phi)|, for ``(k,)`` arc parameters in range."""
        assert self._panel_theta is not None and self.height is not None
        k = self.edges.searchsorted(phi, side="right")
        k -= 1
        np.minimum(k, len(self.edges) - 2, out=k)
        np.maximum(k, 0, out=k)
        a = self.edges.take(k)
        half = 0.5 * (phi - a)
        pts = np.empty((len(phi), 21))
        pts[:, :20] = (a + half)[:, None] + half[:, None] * _GL_NODES
        pts[:, 20] = phi
        speed = self._speed(self.height, pts)
        theta = self._panel_theta.take(k) + half * (speed[:, :20] @ _GL_WEIGHTS)
        return theta, speed[:, 20]

    def theta_of_phi(self, phi: ArrayLike) -> Array:
        """Developed angle theta (radians) at arc parameters ``phi``."""
        ph = np.atleast_1d(np.asarray(phi, dtype=float))
        return self._theta_and_speed(ph)[0]

    def phi_of_theta(self, theta: ArrayLike) -> Array:
        """Arc parameters phi (radians) at developed angles ``theta`` (Newton)."""
        assert self._panel_theta is not None and self.height is not None
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        # first guess: linear between the tabulated nodes
        th_tab, ph_tab = self._node_table()
        j = th_tab.searchsorted(t, side="right")
        j -= 1
        np.minimum(j, len(th_tab) - 2, out=j)
        np.maximum(j, 0, out=j)
        t0, t1 = th_tab.take(j), th_tab.take(j + 1)
        p0, p1 = ph_tab.take(j), ph_tab.take(j + 1)
        phi = p0 + (t - t0) / (t1 - t0) * (p1 - p0)
        lo, hi = float(self.edges[0]), float(self.edges[-1])
        for _ in range(20):
            f, speed = self._theta_and_speed(phi)
            step = (f - t) / speed
            phi -= step
            np.minimum(np.maximum(phi, lo, out=phi), hi, out=phi)
            # Newton leaves an error of about step^2 |u''| / (2 |u'|)
            if float(np.max(np.abs(step), initial=0.0)) <= 1e-9:
                break
        return phi

    def _directions(self, phi: Array) -> Array:
        """Unit vectors ``(k, 3)`` from the apex to the arc points at ``phi``."""
        assert self.height is not None
        r = self._r
        c, s = np.cos(phi), np.sin(phi)
        d = self._rsa + r * s
        v = np.empty((len(phi), 3))
        np.multiply(c, r, out=v[:, 0])
        v[:, 0] -= self._hc
        np.multiply(d, self._cb, out=v[:, 1])
        np.multiply(d, self._sb, out=v[:, 2])
        v[:, 2] -= self.height
        v /= np.sqrt(np.einsum("ij,ij->i", v, v))[:, None]
        return v

    def directions_at(self, theta: ArrayLike) -> Array:
        return self._directions(self.phi_of_theta(theta))

    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        phi = self.phi_of_theta(theta)
        u = self._directions(phi)
        c, s = np.cos(phi), np.sin(phi)
        e = np.empty_like(u)  # P'(phi) / r, a unit vector
        np.negative(s, out=e[:, 0])
        np.multiply(c, self._cb, out=e[:, 1])
        np.multiply(c, self._sb, out=e[:, 2])
        e -= np.einsum("ij,ij->i", e, u)[:, None] * u
        e /= np.sqrt(np.einsum("ij,ij->i", e, e))[:, None]
        return u, e

    def frame_at(self, theta: float) -> tuple[list[float], list[float]]:
        """``u`` and ``e`` of :meth:`frames` at one flat angle, as floats
        (the ends of the arc without iterating)."""
        assert self.height is not None
        if theta <= 0.0:
            phi = float(self.edges[0])
        elif theta >= self.total_angle:
            phi = float(self.edges[-1])
        else:
            phi = float(self.phi_of_theta(theta)[0])
        r, cb, sb = self._r, self._cb, self._sb
        c, s = math.cos(phi), math.sin(phi)
        d = self._rsa + r * s
        v = (r * c - self._hc, d * cb, d * sb - self.height)
        norm = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
        u = [x / norm for x in v]
        dp = (-s, c * cb, c * sb)
        along = dp[0] * u[0] + dp[1] * u[1] + dp[2] * u[2]
        e = [p - along * q for p, q in zip(dp, u, strict=True)]
        norm = math.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
        return u, [x / norm for x in e]
