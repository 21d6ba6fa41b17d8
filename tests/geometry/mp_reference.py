"""Independent mpmath references for the apex near an end of the f-line.

Nothing here uses onefold_cad's geometry: the frame points come from the
inputs as given (paper section 3.2, the floats taken as exact binary values)
and the cone's developed angle is the integral of |u'(phi)| = |P' x (P - A)| /
|P - A|^2 by tanh-sinh on panels graded geometrically towards the arc's ends,
the arc point nearest the apex's foot and the upper limit: near an end of the
f-line |u'| peaks at about R / L over a width of about L / R (L the end's
distance from H), which uniform panels step over.
"""

from __future__ import annotations

from collections.abc import Callable

import mpmath as mp

from onefold_cad import FrameCurve


def _inputs(frame: FrameCurve) -> tuple[mp.mpf, ...]:
    a = mp.mpf(frame.alpha) * mp.pi / 180
    b = mp.mpf(frame.beta) * mp.pi / 180
    return mp.mpf(frame.radius), a, b, mp.mpf(frame.h_c)


def point(frame: FrameCurve, phi: mp.mpf) -> tuple[mp.mpf, mp.mpf, mp.mpf]:
    """The frame-curve point at arc parameter phi (working precision)."""
    r, a, b, hc = _inputs(frame)
    d = r * mp.sin(a) + r * mp.sin(phi)
    return (-hc + r * mp.cos(phi), d * mp.cos(b), d * mp.sin(b))


def speed(frame: FrameCurve, h: mp.mpf) -> Callable[[mp.mpf], mp.mpf]:
    """|u'(phi)| for the apex at (0, 0, h)."""
    r, a, b, hc = _inputs(frame)
    sa, cb, sb = mp.sin(a), mp.cos(b), mp.sin(b)

    def f(phi: mp.mpf) -> mp.mpf:
        d = r * sa + r * mp.sin(phi)
        v = (-hc + r * mp.cos(phi), d * cb, d * sb - h)
        dp = (-r * mp.sin(phi), r * mp.cos(phi) * cb, r * mp.cos(phi) * sb)
        c = (
            dp[1] * v[2] - dp[2] * v[1],
            dp[2] * v[0] - dp[0] * v[2],
            dp[0] * v[1] - dp[1] * v[0],
        )
        return mp.sqrt(sum(x * x for x in c)) / sum(x * x for x in v)

    return f


def graded_nodes(frame: FrameCurve, h: mp.mpf, upto: mp.mpf | None = None) -> list[mp.mpf]:
    """Panel edges on [p0, upto]: split at the ends, ``upto`` and the arc point
    nearest the apex's foot, each piece halved towards both its ends until
    the smallest panel is a quarter of the apex's distance from the circle (/R):
    every panel is then at least as far from the integrand's singularities as
    it is wide, where tanh-sinh converges fast."""
    r, a, b, hc = _inputs(frame)
    p0, p1 = -a, mp.pi + a
    top = p1 if upto is None else upto
    fx, fd = hc, h * mp.sin(b) - r * mp.sin(a)  # the foot minus the arc's centre
    foot = mp.atan2(fd, fx)
    if foot < p0:
        foot += 2 * mp.pi
    cuts = sorted(c for c in {p0, top, foot} if p0 <= c <= top)
    gap = mp.hypot(mp.hypot(fx, fd) - r, h * mp.cos(b)) / r + mp.mpf(10) ** -40
    depth = min(int(mp.ceil(mp.log(2 * mp.pi / gap, 2))) + 2, 160)
    grade = [mp.mpf(2) ** -k for k in range(depth, 0, -1)]
    nodes = [p0]
    for lo, hi in zip(cuts[:-1], cuts[1:], strict=True):
        w = (hi - lo) / 2
        nodes += [lo + w * g for g in grade] + [lo + w] + [hi - w * g for g in reversed(grade)]
        nodes.append(hi)
    return sorted(set(nodes))


def cone_excess(frame: FrameCurve, h: float, dps: int = 30) -> mp.mpf:
    """S(h) - pi of the exact cone (radians), tanh-sinh on graded panels."""
    with mp.workdps(dps):
        hh = mp.mpf(h)
        return mp.quad(speed(frame, hh), graded_nodes(frame, hh)) - mp.pi


def developed_angle(frame: FrameCurve, h: float, u: tuple[float, float, float]) -> float:
    """The developed angle (radians, from the +x end) of the arc point that the
    ray from the apex (0, 0, h) along ``u`` meets in the frame plane."""
    with mp.workdps(30):
        r, a, b, hc = _inputs(frame)
        hh = mp.mpf(h)
        uu = [mp.mpf(float(c)) for c in u]
        t = -(hh * mp.cos(b)) / (-uu[1] * mp.sin(b) + uu[2] * mp.cos(b))
        d = uu[1] * t * mp.cos(b) + (hh + uu[2] * t) * mp.sin(b)
        phi = mp.atan2(d - r * mp.sin(a), uu[0] * t + hc)
        if phi < -a - mp.mpf(10) ** -12:
            phi += 2 * mp.pi
        return float(mp.quad(speed(frame, hh), graded_nodes(frame, hh, phi)))
