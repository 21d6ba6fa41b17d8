"""The exact model's direction-surface: the cone from the apex over the arc.

The developed angle is the integral over the arc of the speed of the unit
vector from the apex to the arc point, evaluated by Gauss-Legendre quadrature
on panels graded towards the integrand's complex singularities (see below);
the rule is in :mod:`.rule`, the surface interface and the in-plane
formulation in :mod:`.surface`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.geometry.arc import arc_range, end_relative
from onefold_cad.geometry.cone.nodes import hermite_s, theta_from_both, theta_from_nodes
from onefold_cad.geometry.cone.rule import (
    GL_NODES,
    GL_WEIGHTS,
    NODE_INTEGRALS,
    REACH,
    HalfRule,
    half_rule,
    halved,
    panels,
    rule_speed,
    singularities,
    speed_at,
)
from onefold_cad.geometry.frame_curve import FrameCurve
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.surface import EPS, DirectionSurface

__all__ = ["ExactCone"]

_EPS = EPS


class ExactCone(DirectionSurface):
    """The continuous cone from the apex over the circular arc (exact model).

    The developed angle theta(phi) = integral of |u'(phi)| dphi is evaluated by
    composite Gauss-Legendre quadrature on panels graded towards the
    integrand's complex singularities for the apex heights in question (see
    the comment above), and inverted by Newton's method. The rule is rebuilt
    whenever a new apex height needs finer panels; :meth:`verify` checks it
    against the rule with every panel halved.
    """

    def __init__(self, frame: FrameCurve, reach: float = REACH) -> None:
        super().__init__(frame)
        self.reach = reach
        self._rule: tuple[HalfRule, HalfRule] | None = None
        self._valid_for: list[float] = []
        # at the apex (set_apex)
        self._apex_rule: tuple[HalfRule, HalfRule] | None = None
        self._theta_lo: tuple[Array, Array] | None = None  # per half: theta at panel starts
        self._speed_at: tuple[Array, Array] | None = None  # per half: |u'| at the nodes
        self._half_total: tuple[float, float] = (0.0, 0.0)
        self._tables: tuple[tuple[Array, Array, Array], tuple[Array, Array, Array]] | None = None
        self._verified: tuple[float, float] | None = None

    # -- the quadrature rule ---------------------------------------------------
    def _sing_arrays(self, heights: list[float], planar: bool = False) -> tuple[Array, Array]:
        g = self.geometry
        sp: list[tuple[float, float]] = []
        sm: list[tuple[float, float]] = []
        two_pi = 2.0 * math.pi
        for h in heights:
            for rp, rm, dist in singularities(g, h, planar):
                for k in (-two_pi, 0.0, two_pi):
                    sp.append((rp + k, dist))
                    sm.append((rm + k, dist))
        return np.array(sp).reshape(-1, 2), np.array(sm).reshape(-1, 2)

    def _build(
        self, heights: list[float], reach: float, planar: bool = False
    ) -> tuple[HalfRule, HalfRule]:
        g = self.geometry
        sp, sm = self._sing_arrays(heights, planar)
        hs = 0.5 * g.span
        return (
            half_rule(g, True, panels(hs, sp, reach)),
            half_rule(g, False, panels(hs, sm, reach)),
        )

    def _valid(self, rule: tuple[HalfRule, HalfRule], heights: list[float]) -> bool:
        sp, sm = self._sing_arrays(heights)
        for hf, sing in zip(rule, (sp, sm), strict=True):
            if not len(sing):
                continue
            c = hf.edges[:-1] + hf.half
            dist = np.hypot(c[:, None] - sing[:, 0], sing[:, 1]).min(axis=1)
            if bool((hf.half > self.reach * dist).any()):
                return False
        return True

    def _rule_for(self, heights: list[float]) -> tuple[HalfRule, HalfRule]:
        """A rule fine enough for every apex height in ``heights`` (units of R)."""
        if self._rule is not None:
            new = [h for h in heights if h not in self._valid_for]
            if not new:
                return self._rule
            if self._valid(self._rule, new):
                self._valid_for.extend(new)
                return self._rule
        self._rule = self._build(heights, self.reach)
        self._valid_for = list(heights)
        return self._rule

    # -- the angle condition -------------------------------------------------------
    def _integral(self, rule: tuple[HalfRule, HalfRule], h: float | Array) -> Array | float:
        g = self.geometry
        total: Array | float = 0.0
        for hf in rule:
            total = total + rule_speed(hf, g, h) @ hf.weights
        return total

    def excess(self, h: float) -> float:
        rule = self._rule_for([h])
        return float(self._integral(rule, h)) - math.pi

    def excesses(self, h: Array) -> Array:
        hh = np.asarray(h, dtype=float).ravel()
        rule = self._rule_for(hh.tolist())
        out: Array = np.asarray(self._integral(rule, hh[:, None]), dtype=float)
        return out - math.pi

    def excess_bound(self) -> float:
        return 16.0 * _EPS * math.pi

    def excess_accurate(self, h: float) -> tuple[float, float]:
        g = self.geometry
        hs = h * g.sin_beta
        t = h * g.cos_beta
        m1 = hs * (hs - 2.0 * g.sin_alpha) - g.l_plus * g.l_minus
        if m1 >= 0.0:  # F on or outside the circle: no in-plane split
            return self.excess(h), self.excess_bound()
        rule = self._build([h], self.reach, planar=True)
        t2 = t * t
        total = 0.0
        size = 0.0
        for hf in rule:
            q = hf.d - hs
            w = hf.x * hf.cphi + q * hf.sphi  # > 0: F inside
            pp = hf.x * hf.x + q * q
            sig = np.hypot(w, t)
            # w / pp - sig / (pp + t^2) = t^2 (w - pp / (w + sig)) / (pp (pp + t^2))
            dens = w - pp / (w + sig)
            dens *= t2
            dens /= pp * (pp + t2)
            total += float(dens @ hf.weights)
            size += float(np.abs(dens) @ hf.weights)
        sweep = math.atan(hs / g.l_plus) + math.atan(hs / g.l_minus)
        return sweep - total, 16.0 * _EPS * (sweep + size)

    def excess_and_slope(self, h: float) -> tuple[float, float]:
        g = self.geometry
        sb, cb = g.sin_beta, g.cos_beta
        rule = self._rule_for([h])
        t = h * cb
        f = 0.0
        slope = 0.0
        for hf in rule:
            q = hf.d - h * sb
            w = hf.x * hf.cphi + q * hf.sphi
            den = hf.x * hf.x + q * q + t * t
            sig = np.hypot(w, t)
            val = sig / den
            # d/dh: w' = -sb sin(phi), t' = cb, den' = -2 q sb + 2 t cb
            dsig = (t * cb - sb * w * hf.sphi) / sig
            dden = 2.0 * (t * cb - sb * q)
            deriv = (dsig - val * dden) / den
            f += float(val @ hf.weights)
            slope += float(deriv @ hf.weights)
        return f - math.pi, slope

    # -- the apex ----------------------------------------------------------------------
    def set_apex(self, h: float) -> None:
        g = self.geometry
        self.height = h
        hu = h / g.radius
        coarse = self._rule_for([hu])
        # the verified rule: every panel halved
        c0, c1 = coarse
        fine = (half_rule(g, c0.plus, halved(c0.edges)), half_rule(g, c1.plus, halved(c1.edges)))
        speeds = (rule_speed(fine[0], g, hu), rule_speed(fine[1], g, hu))
        lo = []
        totals = []
        for hf, sp in zip(fine, speeds, strict=True):
            per = (sp * hf.weights).reshape(len(hf.half), -1).sum(axis=1)
            th = np.empty(len(per) + 1)
            th[0] = 0.0
            np.cumsum(per, out=th[1:])
            lo.append(th)
            totals.append(float(per.sum()))
        self._apex_rule = fine
        self._speed_at = speeds
        self._theta_lo = (lo[0], lo[1])
        self._half_total = (totals[0], totals[1])
        self._tables = None
        s_fine = totals[0] + totals[1]
        s_coarse = float(self._integral(coarse, hu))
        # node values to a few rounding errors each; the arc placed to ~4
        # rounding errors of its coordinates (from the nearer end) and the apex
        # to one of h: |u'| moves by about that over |P - A| times |u'| (R = 1)
        sens = 0.0
        for hf, sp in zip(fine, speeds, strict=True):
            q = hf.d - hu * g.sin_beta
            place = 4.0 * (np.abs(hf.x) + np.abs(hf.d)) + 2.0 * hu
            place /= np.sqrt(hf.x * hf.x + q * q + (hu * g.cos_beta) ** 2)
            sens += float((sp * place) @ hf.weights)
        rounding = 16.0 * _EPS * math.pi + 4.0 * _EPS * sens
        self._verified = (s_fine - math.pi, abs(s_fine - s_coarse) + rounding)

    def verify(self, target: float = 0.0) -> tuple[float, float]:
        if self._verified is None:
            raise RuntimeError("apex height not set")
        return self._verified

    @property
    def total_angle(self) -> float:
        return self._half_total[0] + self._half_total[1]

    # -- theta along each half and its inverse --------------------------------------
    def _theta_half(self, k: int, s: Array) -> tuple[Array, Array]:
        """theta measured from half k's end (0: +x, 1: -x) at distances ``s``
        from it, and |u'| there."""
        assert self._apex_rule is not None and self._theta_lo is not None
        assert self.height is not None
        hf = self._apex_rule[k]
        g = self.geometry
        j = hf.edges.searchsorted(s, side="right")
        j -= 1
        np.maximum(j, 0, out=j)  # np.clip's work without its Python wrapper
        np.minimum(j, len(hf.half) - 1, out=j)
        a = hf.edges.take(j)
        half = 0.5 * (s - a)
        pts = np.empty((len(s), 21))
        pts[:, :20] = (a + half)[:, None] + half[:, None] * GL_NODES
        pts[:, 20] = s
        flat = pts.ravel()
        x, d = end_relative(g, flat, hf.plus)
        ang = flat - g.alpha
        cphi = np.cos(ang)
        if not hf.plus:
            np.negative(cphi, out=cphi)
        speed = speed_at(g, x, d, cphi, np.sin(ang), self.height / g.radius)
        speed = speed.reshape(len(s), 21)
        theta = self._theta_lo[k].take(j) + half * (speed[:, :20] @ GL_WEIGHTS)
        return theta, speed[:, 20]

    def node_table(self, k: int) -> tuple[Array, Array, Array]:
        """theta from half k's end, s and |u'| = d theta / d s, ascending in s,
        at the end, every node of the verified rule and the midpoint (first
        guesses of the inverse, :mod:`onefold_cad.geometry.cone.nodes`)."""
        if self._tables is None:
            assert self._apex_rule is not None and self._speed_at is not None
            assert self._theta_lo is not None and self.height is not None
            g = self.geometry
            out = []
            for hf, sp, lo in zip(self._apex_rule, self._speed_at, self._theta_lo, strict=True):
                per = sp.reshape(len(hf.half), -1)
                nodes = per @ NODE_INTEGRALS.T
                nodes *= hf.half[:, None]
                nodes += lo[:-1, None]
                th = np.concatenate(((0.0,), nodes.ravel(), lo[-1:]))
                s = np.concatenate(((0.0,), hf.s.ravel(), hf.edges[-1:]))
                x, d = end_relative(g, s[[0, -1]], hf.plus)  # |u'| at the ends
                ang = s[[0, -1]] - g.alpha
                cphi = np.cos(ang) if hf.plus else -np.cos(ang)
                at_ends = speed_at(g, x, d, cphi, np.sin(ang), self.height / g.radius)
                speed = np.concatenate((at_ends[:1], sp, at_ends[1:]))
                out.append((th, s, speed))
            self._tables = (out[0], out[1])
        return self._tables[k]

    def _s_of_theta(self, k: int, theta: Array) -> Array:
        """Distances s from half k's end at which theta (from that end) is reached.

        Each angle is iterated until its own Newton step is small, so its s
        does not depend on which other angles share the call (up to the
        rounding of the vectorised sums): one call over many angles gives
        what one call per angle gives."""
        s, bend = hermite_s(self.node_table(k), theta)  # the first guess
        top = float(self.node_table(k)[1][-1])
        todo = np.arange(len(s))  # the angles still iterating
        sa, ta = s, theta
        for _ in range(30):
            f, speed = self._theta_half(k, sa)
            step = (f - ta) / speed
            sa -= step
            np.clip(sa, 0.0, top, out=sa)
            s[todo] = sa
            # Newton leaves an error of about step^2 |u''| / (2 |u'|): stop
            # when that is below a rounding error of s, for |u''| / |u'| as
            # the table gives it (bend) and as large as 1 / s (near an end)
            step *= step
            going = (step > 1e-16 * sa * sa) | (bend * step > _EPS * sa)
            if not going.any():
                break
            todo, sa, ta, bend = todo[going], sa[going], ta[going], bend[going]
        return s

    def _split(self, theta: ArrayLike) -> tuple[Array, NDArray[np.bool_], Array]:
        """Flat angles -> (which half is +x, s on its half)."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        first = self._half_total[0]
        plus = t <= first
        s = np.empty(len(t))
        if plus.any():
            s[plus] = self._s_of_theta(0, np.maximum(t[plus], 0.0))
        if (~plus).any():
            back = self.total_angle - t[~plus]
            s[~plus] = self._s_of_theta(1, np.maximum(back, 0.0))
        return t, plus, s

    def theta_of_phi(self, phi: ArrayLike) -> Array:
        """Developed angle theta (radians) at arc parameters ``phi``."""
        ph = np.atleast_1d(np.asarray(phi, dtype=float))
        g = self.geometry
        p0, p1 = arc_range(self.frame)
        sp = ph - p0
        plus = sp <= 0.5 * g.span
        if plus.all():  # one half (as a zoom's bracket mostly is): no masks
            return self._theta_half(0, np.maximum(sp, 0.0))[0]
        out = np.empty(len(ph))
        if plus.any():
            out[plus] = self._theta_half(0, np.maximum(sp[plus], 0.0))[0]
        if (~plus).any():
            sm = np.maximum(p1 - ph[~plus], 0.0)
            out[~plus] = self.total_angle - self._theta_half(1, sm)[0]
        return out

    def phi_of_theta(self, theta: ArrayLike) -> Array:
        """Arc parameters phi (radians) at developed angles ``theta`` (Newton)."""
        _, plus, s = self._split(theta)
        p0, p1 = arc_range(self.frame)
        return np.where(plus, p0 + s, p1 - s)

    def theta_near(self, phi: Array) -> Array:
        """:meth:`theta_of_phi` of arc parameters ``phi`` ``(k,)``, integrated from
        the nearest node of the rule (:func:`~onefold_cad.geometry.cone.nodes.theta_from_nodes`):
        the same to a few rounding errors, at a fifth of the work."""
        g = self.geometry
        p0, p1 = arc_range(self.frame)
        h = float(self.height) / g.radius  # type: ignore[arg-type]
        plus = phi - p0 <= 0.5 * g.span
        if plus.all():  # one half (a zoom's bracket mostly is): no masks
            return theta_from_nodes(self.node_table(0), g, True, h, np.maximum(phi - p0, 0.0))
        if not plus.any():
            th = theta_from_nodes(self.node_table(1), g, False, h, np.maximum(p1 - phi, 0.0))
            return self.total_angle - th
        s = np.maximum(np.where(plus, phi - p0, p1 - phi), 0.0)
        th = theta_from_both((self.node_table(0), self.node_table(1)), g, h, s, plus)
        return np.where(plus, th, self.total_angle - th)

    def phi_near(self, theta: Array) -> Array:
        """Arc parameters at developed angles ``theta`` ``(k,)`` to about 1e-10 rad:
        the first guess of :meth:`phi_of_theta` (no Newton step), for samples."""
        p0, p1 = arc_range(self.frame)
        plus = theta <= self._half_total[0]
        out = np.empty(len(theta))
        if plus.any():
            out[plus] = p0 + hermite_s(self.node_table(0), np.maximum(theta[plus], 0.0))[0]
        if (~plus).any():
            back = np.maximum(self.total_angle - theta[~plus], 0.0)
            out[~plus] = p1 - hermite_s(self.node_table(1), back)[0]
        return out

    def _vectors(self, plus: NDArray[np.bool_] | bool, s: Array) -> tuple[Array, Array]:
        """Unit directions ``u`` from the apex and the arc's unit tangents
        (towards increasing phi) ``(k, 3)`` at the points s from their ends."""
        assert self.height is not None
        g = self.geometry
        x, d = end_relative(g, s, plus)
        v = np.empty((len(s), 3))
        v[:, 0] = x
        np.multiply(d, g.cos_beta, out=v[:, 1])
        np.multiply(d, g.sin_beta, out=v[:, 2])
        v[:, 2] -= self.height / g.radius
        v /= np.sqrt(np.einsum("ij,ij->i", v, v))[:, None]
        ang = s - g.alpha
        cphi = np.where(plus, np.cos(ang), -np.cos(ang))
        tan = np.empty_like(v)  # P'(phi) / R, a unit vector
        np.negative(np.sin(ang), out=tan[:, 0])
        np.multiply(cphi, g.cos_beta, out=tan[:, 1])
        np.multiply(cphi, g.sin_beta, out=tan[:, 2])
        return v, tan

    def directions_at(self, theta: ArrayLike) -> Array:
        _, plus, s = self._split(theta)
        return self._vectors(plus, s)[0]

    def frames(self, theta: ArrayLike) -> tuple[Array, Array]:
        _, plus, s = self._split(theta)
        return _orthonormal(*self._vectors(plus, s))

    def frames_at_arc(self, phi: Array) -> tuple[Array, Array]:
        """:meth:`frames` at arc parameters ``phi`` ``(k,)`` (radians) instead of
        flat angles: no flat angle to invert (``phi_of_theta`` maps one to the other)."""
        p0, p1 = arc_range(self.frame)
        plus = phi - p0 <= 0.5 * self.geometry.span
        return _orthonormal(
            *self._vectors(plus, np.maximum(np.where(plus, phi - p0, p1 - phi), 0.0))
        )

    def frame_at(self, theta: float) -> tuple[list[float], list[float]]:
        """``u`` and ``e`` of :meth:`frames` at one flat angle, as floats
        (the ends of the arc without iterating)."""
        if theta <= 0.0 or theta >= self.total_angle:
            plus = theta <= 0.0
            u, e = self._vectors(np.array([plus]), np.zeros(1))
            e -= float(e[0] @ u[0]) * u
            e /= float(np.sqrt(e[0] @ e[0]))
            return u[0].tolist(), e[0].tolist()
        u, e = self.frames(np.array([theta]))
        return u[0].tolist(), e[0].tolist()


def _orthonormal(u: Array, e: Array) -> tuple[Array, Array]:
    """``u`` and ``e`` made normal to it and unit (``e`` in place)."""
    e -= np.einsum("ij,ij->i", e, u)[:, None] * u
    e /= np.sqrt(np.einsum("ij,ij->i", e, e))[:, None]
    return u, e
