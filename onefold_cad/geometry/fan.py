"""The paper's direction-surface: a fan of planar triangles (section 3.2).

The apex angles are evaluated as described in :mod:`.surface`; the search's
evaluation (:meth:`PaperFan.excess`) works in the plane of the frame curve,
the verifying one (:meth:`PaperFan.set_apex`) from the unit direction-vectors
in space, so the two share the points but no formula.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.arc import ArcSpacing, division_points
from onefold_cad.geometry.frame_curve import FrameCurve
from onefold_cad.geometry.numeric import Array, cross3
from onefold_cad.geometry.surface import EPS, DirectionSurface

__all__ = ["PaperFan"]

#: Up to this many divisions the fan's apex angles are taken from the unit
#: direction-vectors (Kahan's 2 atan2(|u - v|, |u + v|), each to ~6 rounding
#: errors, absolute); above it from the chords, to a relative rounding error.
_KAHAN_MAX = 2048


class PaperFan(DirectionSurface):
    """The fan of ``divisions`` planar triangles of the paper (section 3.2):
    over the paper's equally spaced division points, or over those of a
    ``spacing`` (:class:`ArcSpacing`, of the frame's ``divisions``) on the
    same arc.

    Attributes:
        spacing: the spacing given (None: the paper's equal steps).
        directions: once the apex is set, the ``(divisions + 1, 3)`` unit
            direction-vectors from the apex to the division points, from the
            f-line's +x end to its -x end.
        gammas: once the apex is set, the ``(divisions,)`` apex angles (radians).
        thetas: once the apex is set, the ``(divisions + 1,)`` cumulative flat
            angles theta_k = gamma_1 + ... + gamma_k (radians), theta_0 = 0.
    """

    def __init__(self, frame: FrameCurve, spacing: ArcSpacing | None = None) -> None:
        super().__init__(frame)
        g = self.geometry
        n = frame.divisions
        if spacing is not None and spacing.divisions != n:
            raise InvalidParameterError(
                "spacing", f"the spacing has {spacing.divisions} divisions, the frame {n}"
            )
        self.spacing = spacing
        pts = division_points(g, n, spacing)  # rows x, d
        x, d = pts
        # Speed (the paper model's whole solve + fold takes ~60 us at 90
        # divisions, ~0.2-0.4 us per numpy call): every call below works on
        # both rows (x, d) at once where it can, on contiguous rows, and
        # writes into its output.
        p0, p1 = pts[:, :-1], pts[:, 1:]
        e = p1 - p0  # rows ex, ed
        ex, ed = e
        self._x, self._d, self._ex, self._ed, self._n = x, d, ex, ed, n
        # The search's S(h): with c_i = p_i x e_i = P_i x e_i + h sin(beta) ex_i
        # (p = P - F, F = (0, h sin(beta)) the apex's foot in the arc's plane),
        #   |a_i x a_i+1|^2 = c_i^2 + t^2 |e_i|^2 = c0^2 + 2 sb c0 ex h + (ex^2 + cb^2 ed^2) h^2,
        #   a_i . a_i+1 = P_i . P_i+1 - sb (d_i + d_i+1) h + h^2,
        # their coefficients of (1, h, h^2), ``quad[0]`` and ``quad[1]``, so
        # that S(h) at several heights costs one (batched) matrix product (the
        # verification does not use them).
        sb, cb = g.sin_beta, g.cos_beta
        quad = np.empty((2, 3, n))
        rows = quad.reshape(6, n)
        t = p0 * e[::-1]  # rows x0 ed, d0 ex
        c0 = np.subtract(t[0], t[1], out=rows[1])
        c0[-1] = x.item(n) * ed.item(n - 1)  # from the -x end (d_n = 0): P_n may lie close to H
        np.multiply(c0, c0, out=rows[0])
        c0 *= ex  # rows[1]: 2 sb c0 ex
        c0 *= 2.0 * sb
        e2 = e * e
        xc = np.multiply(e2[1], cb * cb, out=rows[2])
        xc += e2[0]
        t = np.multiply(p0, p1, out=t)  # rows x0 x1, d0 d1
        np.add(t[0], t[1], out=rows[3])
        yb = np.add(d[:-1], d[1:], out=rows[4])
        yb *= -sb
        rows[5].fill(1.0)
        self._quad = quad
        self._cs = np.array(((cb,), (sb,)))  # to place the points in space at once
        self._plane: tuple[Array, Array, Array, tuple[float, float]] | None = None
        self.directions: Array | None = None
        self.gammas: Array | None = None
        self.thetas: Array | None = None
        self._apex_state: tuple[float, float, float, Array] | None = None

    @property
    def points(self) -> Array:
        """``(divisions + 1, 3)`` the division points (length), +x end first."""
        g = self.geometry
        r = g.radius
        return np.stack(
            [r * self._x, (r * g.cos_beta) * self._d, (r * g.sin_beta) * self._d], axis=-1
        )

    # -- the angle condition -----------------------------------------------------
    def excess(self, h: float) -> float:
        q = np.array((1.0, h, h * h)) @ self._quad  # (2, n): |a x b|^2 and a . b
        s = np.maximum(q[0], 0.0)  # >= 0 but for rounding
        np.sqrt(s, out=s)
        return float(np.add.reduce(np.arctan2(s, q[1], out=s))) - math.pi

    def excesses(self, h: Array) -> Array:
        hh = np.empty((len(h), 3))
        hh[:, 0] = 1.0
        hh[:, 1] = h
        np.multiply(h, h, out=hh[:, 2])
        q = hh @ self._quad  # (2, k, n): |a x b|^2 and a . b, each contiguous
        s = np.maximum(q[0], 0.0)  # >= 0 but for rounding
        np.sqrt(s, out=s)
        np.arctan2(s, q[1], out=s)
        out: Array = np.add.reduce(s, axis=1)
        out -= math.pi
        return out

    def excess_bound(self) -> float:
        # |a x b|^2 and a . b to a few rounding errors of the sizes of their
        # expanded terms, which exceed them only where A lies close to the
        # plane of the frame and near it (the verification then rejects the
        # root and :func:`solve` steps on the verified sum)
        return 16.0 * EPS * math.pi

    def _terms(self, h: float) -> tuple[Array, Array, Array, Array]:
        """c_i = p_i x e_i, p_i . p_i+1, t |e_i| and q = d - h sin(beta), each
        from the differences of points (no expansion in h)."""
        if self._plane is None:
            x, ex, ed = self._x, self._ex, self._ed
            self._plane = (
                x[:-1] * ed,
                x[:-1] * x[1:],
                np.hypot(ex, ed),
                (float(x[-1] * ed[-1]), float(ex[-1])),
            )
        xed, xx, elen, (xl, el) = self._plane
        g = self.geometry
        hs = h * g.sin_beta
        q = self._d - hs
        q0 = q[:-1]
        c = xed - q0 * self._ex
        c[-1] = xl + hs * el  # the last triangle from its -x end
        dot = q0 * q[1:]
        dot += xx
        return c, dot, (h * g.cos_beta) * elen, q

    def excess_accurate(self, h: float) -> tuple[float, float]:
        g = self.geometry
        c, dot, te, _ = self._terms(h)
        t = h * g.cos_beta
        t2 = t * t
        sig = np.hypot(c, te)
        if float(c.min()) > 0.0:
            # F inside the fan: the in-plane sweep is pi + eps exactly; deficit
            # phi_i - gamma_i = atan2(c t^2 + dot (c - sig), dot (dot + t^2) + c sig)
            # with c - sig = -t^2 |e|^2 / (c + sig)
            cms = te * te
            cms /= c + sig
            num = c * t2
            num -= dot * cms
            den = dot + t2
            den *= dot
            den += c * sig
            deficit = np.arctan2(num, den)
            hs = h * g.sin_beta
            sweep = math.atan(hs / g.l_plus) + math.atan(hs / g.l_minus)
            scale = sweep + float(np.abs(deficit).sum())
            return sweep - float(deficit.sum()), 16.0 * EPS * scale
        dot += t2
        return float(np.arctan2(sig, dot).sum()) - math.pi, self.excess_bound()

    def excess_and_slope(self, h: float) -> tuple[float, float]:
        g = self.geometry
        sb, cb = g.sin_beta, g.cos_beta
        c, dot, te, q = self._terms(h)
        t = h * cb
        dot += t * t
        ss = c * c
        ss += te * te
        sig = np.sqrt(ss)
        f = float(np.arctan2(sig, dot).sum()) - math.pi
        # d/dh atan2(sig, dot) = (dot sig' - sig dot') / (sig^2 + dot^2)
        dsig = c * (sb * self._ex)
        assert self._plane is not None
        elen = self._plane[2]
        dsig += (t * cb) * (elen * elen)
        dsig /= sig
        ddot = q[:-1] + q[1:]
        ddot *= -sb
        ddot += 2.0 * t * cb
        num = dot * dsig
        num -= sig * ddot
        ss += dot * dot
        num /= ss
        return f, float(num.sum())

    # -- the apex ------------------------------------------------------------------
    def set_apex(self, h: float) -> None:
        g = self.geometry
        self.height = h
        hu = h / g.radius
        n = self._n
        # the vectors a_i = P_i - A, one row per coordinate (3, n + 1)
        v = np.empty((3, n + 1))
        v[0] = self._x
        np.multiply(self._d, self._cs, out=v[1:])  # d cos(beta), d sin(beta)
        v[2] -= np.array(hu)
        nrm = np.add.reduce(v * v, axis=0)  # one call for the three rows
        np.sqrt(nrm, out=nrm)
        if n > _KAHAN_MAX:
            # from the 3D chords: |a_i x e_i| and a_i . a_i+1, relative accuracy
            e = np.empty((n, 3))
            e[:, 0] = self._ex
            np.multiply(self._ed, g.cos_beta, out=e[:, 1])
            np.multiply(self._ed, g.sin_beta, out=e[:, 2])
            vt = v.T
            cr = cross3(vt[:-1], e)
            dots = np.einsum("ij,ij->i", vt[:-1], vt[1:])
            gammas = np.arctan2(np.sqrt(np.einsum("ij,ij->i", cr, cr)), dots)
            arithmetic = 24.0 * EPS * math.pi
            v /= nrm
        else:
            v /= nrm
            # Kahan: gamma = 2 atan2(|u_i+1 - u_i|, |u_i+1 + u_i|), each to ~6
            # rounding errors (absolute). Both chords of all three rows come
            # from one flat difference and one flat sum (w[:, r, i] is row r's
            # u_i+1 -+ u_i; the entries i = n straddle two rows and are unused,
            # the last one is set to keep the squares finite), squared and
            # summed over the rows in two calls.
            flat = v.reshape(-1)
            w = np.empty((2, 3 * n + 3))
            np.subtract(flat[1:], flat[:-1], out=w[0, :-1])
            np.add(flat[1:], flat[:-1], out=w[1, :-1])
            w[:, -1] = 0.0
            w *= w
            lens = np.add.reduce(w.reshape(2, 3, n + 1), axis=1)
            np.sqrt(lens, out=lens)
            gammas = np.arctan2(lens[0, :n], lens[1, :n])
            gammas += gammas
            arithmetic = EPS * (6.0 * n + 8.0 * math.pi)
        self.directions = v.T  # (n + 1, 3), a view
        self.gammas = gammas
        thetas = np.empty(n + 1)
        thetas[0] = 0.0
        np.add.accumulate(gammas, out=thetas[1:])
        self.thetas = thetas
        self._apex_state = (float(np.add.reduce(gammas)) - math.pi, arithmetic, hu, nrm)

    def verify(self, target: float = 0.0) -> tuple[float, float]:
        """S(h) - pi from the apex angles of :meth:`set_apex` and a bound on its
        error: the arithmetic's, and that of the points' and the apex's own
        placement (each to ~4 rounding errors of its coordinates, measured from
        the nearer end of the arc, so an end point to one of L). A crude bound
        on the latter is used when it proves ``|S - pi| <= target / 10``."""
        if self._apex_state is None:
            raise RuntimeError("apex height not set")
        res, arithmetic, hu, nrm = self._apex_state
        # every apex angle moves by at most 2 dP / |P - A| for a placement dP
        g = self.geometry
        size = 4.0 * (2.0 + abs(g.hc) + g.sin_alpha) + 2.0 * hu
        crude = EPS * 2.0 * size * len(nrm) / float(np.minimum.reduce(nrm))
        if abs(res) + arithmetic + crude <= 0.1 * target:
            return res, arithmetic + crude
        return res, arithmetic + EPS * self._placement(nrm, hu)

    def _placement(self, nrm: Array, hu: float) -> float:
        """sum over the points of |grad_P S| times their placement error (/eps).

        Moving P_i by dP turns u_i by dP / |a_i|, which changes gamma_i-1 +
        gamma_i by at most that times |t_in - t_out|, the turn of the fan's
        spherical image at u_i: at most the turn of its chords plus half the
        two angles. The end directions each bound one angle."""
        assert self.directions is not None and self.gammas is not None
        v, gammas = self.directions, self.gammas
        du = v[1:] - v[:-1]
        chord = np.sqrt(np.einsum("ij,ij->i", du, du))
        np.maximum(chord, 1e-300, out=chord)
        du /= chord[:, None]
        turn = du[1:] - du[:-1]
        turn = np.sqrt(np.einsum("ij,ij->i", turn, turn))
        turn += 0.5 * (gammas[1:] + gammas[:-1])
        np.minimum(turn, 2.0, out=turn)
        place = np.abs(self._x)
        place += np.abs(self._d)
        place *= 4.0
        place += 2.0 * hu
        place /= nrm
        return float(place[0] + place[-1]) + float(turn @ place[1:-1])

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
                u[j] = self.direction1(int(k[j]), float(w[j]))
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
        p, q = self.directions[k : k + 2].tolist()
        return _slerp(self.gammas.item(k), w, p, q)

    def direction1(self, k: int, w: float) -> list[float]:
        """The ``u`` of :meth:`_frame1` alone."""
        assert self.directions is not None and self.gammas is not None
        p, q = self.directions[k : k + 2].tolist()
        return _slerp(self.gammas.item(k), w, p, q, False)[0]

    def crease_frames(self) -> tuple[tuple[list[float], list[float]], ...]:
        """``u`` and ``e`` of :meth:`frames` on the two crease halves (theta =
        0 and the total angle), as floats."""
        assert self.directions is not None and self.gammas is not None
        n = self._n
        p, q, r, s = self.directions.take((0, 1, n - 1, n), axis=0).tolist()
        g = self.gammas
        last = g.item(n - 1)
        return _slerp(g.item(0), 0.0, p, q), _slerp(last, last, r, s)


def _slerp(
    g: float, w: float, p: list[float], q: list[float], tangent: bool = True
) -> tuple[list[float], list[float]]:
    """In a triangle of apex angle ``g`` between the unit directions ``p`` and
    ``q``, the ray at angle ``w`` from ``p``: ``u`` and (``tangent``) ``e``
    (see :meth:`PaperFan.frames`), written out in plain Python (a
    comprehension costs a call)."""
    sg = math.sin(g)
    a0, a1 = math.sin(g - w) / sg, math.sin(w) / sg
    p0, p1, p2 = p
    q0, q1, q2 = q
    u = [a0 * p0 + a1 * q0, a0 * p1 + a1 * q1, a0 * p2 + a1 * q2]
    if not tangent:
        return u, []
    b0, b1 = math.cos(g - w) / sg, math.cos(w) / sg
    return u, [b1 * q0 - b0 * p0, b1 * q1 - b0 * p1, b1 * q2 - b0 * p2]


#: Up to this many rays are interpolated in plain Python by PaperFan.directions_at.
_FEW = 8
