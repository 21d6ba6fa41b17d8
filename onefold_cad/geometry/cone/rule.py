"""The exact cone's quadrature: Gauss-Legendre panels on the frame arc graded
towards the integrand's complex singularities.

The developed angle is the integral over the arc of the speed of the unit
vector u from the apex to the arc point, in the plane's coordinates (units of
R, p = P - F, t = h cos(beta), phi the arc parameter):

  |u'(phi)| = sqrt(w^2 + t^2) / (|p|^2 + t^2),   w = p x P'(phi) = x cos(phi) + q sin(phi).

With W = C - F (C the arc's centre, F the apex's foot), |p|^2 = |W|^2 + 1 +
2 |W| cos(phi - arg W) and w = 1 + |W| cos(phi - arg W): the integrand's
complex singularities are the zeros of |p|^2 + t^2 (one conjugate pair, at
arg(F - C) + i acosh((|W|^2 + 1 + t^2) / (2 |W|))) and of w^2 + t^2 (two
pairs, near the tangent points from F when F lies outside the circle). A
composite 20-point Gauss-Legendre rule whose panels are no wider than
2 * REACH times their distance from every singularity converges like
4.8^-40; the panels are halved towards each singularity until that holds,
so the rule is graded geometrically towards nearly real singularities (H near
an end of the f-line, beta near 90 deg) instead of being uniformly fine.

The arc is split at its midpoint into two halves, each parametrised by s, the
arc parameter's distance from its own end (phi = -alpha + s on the +x half,
phi = 180 + alpha - s on the -x half), so that nodes near an end are placed
to a rounding error of their distance from it.

Nodes are in units of R (heights) and radians (arc parameters).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.geometry.arc import end_relative
from onefold_cad.geometry.frame_curve import ArcGeometry
from onefold_cad.geometry.numeric import Array, gauss_legendre

__all__ = [
    "GL_NODES",
    "GL_WEIGHTS",
    "MAX_DEPTH",
    "NODE_INTEGRALS",
    "REACH",
    "HalfRule",
    "half_rule",
    "halved",
    "integration_matrix",
    "panels",
    "singularities",
    "rule_speed",
    "speed_at",
]

#: The 20-point rule of every panel.
GL_NODES, GL_WEIGHTS = gauss_legendre(20)
REACH = 0.4
MAX_DEPTH = 60


def integration_matrix(nodes: Array) -> Array:
    """M with (M @ f)_i = integral from -1 to nodes_i of the polynomial that
    interpolates f at ``nodes`` (exact for polynomials of degree < len(nodes))."""
    leg = np.polynomial.legendre
    n = len(nodes)
    integrals = leg.legval(nodes, leg.legint(np.eye(n), lbnd=-1)).T
    return integrals @ np.linalg.inv(leg.legvander(nodes, n - 1))


#: s at the nodes of a panel from the integrand there (for initial guesses).
NODE_INTEGRALS = integration_matrix(GL_NODES)


def singularities(
    g: ArcGeometry, h: float, planar: bool = False
) -> list[tuple[float, float, float]]:
    """The integrand's complex singularities for the apex at height h (units of
    R): ``(s+, s-, distance)``, their real parts as distances from the +x and
    from the -x end (each accurate near its own end) and their distance from
    the real axis. ``planar`` adds the zeros of |p|^2 (the in-plane sweep
    w / |p|^2 of :meth:`ExactCone.excess_accurate`)."""
    hs = h * g.sin_beta
    t = h * g.cos_beta
    m1 = hs * (hs - 2.0 * g.sin_alpha) - g.l_plus * g.l_minus  # |W|^2 - 1
    wn = math.sqrt(max(1.0 + m1, 0.0))
    if wn < 1e-6:  # F at the centre: |u'| is nearly constant
        return []
    ea = complex(g.cos_alpha, g.sin_alpha)
    # the direction of F from the centre, from each end: arg((F - C) / (P_end - C))
    psi_p = cmath.phase(1.0 + complex(-g.l_plus, hs) * ea)
    psi_m = -cmath.phase(1.0 - complex(g.l_minus, hs) * ea.conjugate())
    wm1 = m1 / (1.0 + wn)  # |W| - 1
    y = (wm1 * wm1 + t * t) / (2.0 * wn)
    out = [(psi_p, psi_m, math.log1p(y + math.sqrt(y * (y + 2.0))))]
    if planar:
        y = wm1 * wm1 / (2.0 * wn)
        out.append((psi_p, psi_m, math.log1p(y + math.sqrt(y * (y + 2.0)))))
    # w^2 + t^2 = 0: cos(phi - psi) = (1 +- i t) / |W| = 1 + zeta
    zeta = complex(-wm1, t) / wn
    z = 2.0 * cmath.asin(cmath.sqrt(-0.5 * zeta))
    re, im = abs(z.real), abs(z.imag)
    out.append((psi_p + re, psi_m - re, im))
    out.append((psi_p - re, psi_m + re, im))
    return out


def panels(half_span: float, sing: Array, reach: float) -> Array:
    """Panel edges on [0, half_span] (one half's s), halved until every panel's
    half-width is at most ``reach`` times its centre's distance from each
    singularity ``sing`` ``(m, 2)`` (real part in this half's s, distance)."""
    lo = np.array([0.0])
    hi = np.array([half_span])
    done_lo: list[Array] = []
    done_hi: list[Array] = []
    for _ in range(MAX_DEPTH):
        c = 0.5 * (lo + hi)
        hw = 0.5 * (hi - lo)
        if len(sing):
            dist = np.hypot(c[:, None] - sing[:, 0], sing[:, 1]).min(axis=1)
            split = hw > reach * dist
        else:
            split = hw > 0.5
        done_lo.append(lo[~split])
        done_hi.append(hi[~split])
        if not split.any():
            break
        c, lo, hi = c[split], lo[split], hi[split]
        lo, hi = np.concatenate((lo, c)), np.concatenate((c, hi))
    else:
        done_lo.append(lo)
        done_hi.append(hi)
    a, b = np.concatenate(done_lo), np.concatenate(done_hi)
    order = np.argsort(a)
    edges = np.empty(len(a) + 1)
    edges[:-1] = a[order]
    edges[-1] = b[order[-1]]
    return edges


@dataclass(frozen=True)
class HalfRule:
    """The quadrature rule on one half of the arc (``plus``: from the +x end).

    Attributes:
        plus: which half.
        edges: ``(p + 1,)`` panel edges in s (radians from this half's end).
        half: ``(p,)`` panel half-widths.
        s: ``(p, 20)`` the nodes' s.
        weights: ``(p * 20,)`` Gauss-Legendre weights.
        x, d: ``(p * 20,)`` the nodes' in-plane coordinates (units of R).
        cphi, sphi: ``(p * 20,)`` cos and sin of the nodes' arc parameter.
    """

    plus: bool
    edges: Array
    half: Array
    s: Array
    weights: Array
    x: Array
    d: Array
    cphi: Array
    sphi: Array


def half_rule(g: ArcGeometry, plus: bool, edges: Array) -> HalfRule:
    half = 0.5 * (edges[1:] - edges[:-1])
    mid = edges[:-1] + half
    s = mid[:, None] + half[:, None] * GL_NODES
    flat = s.ravel()
    x, d = end_relative(g, flat, plus)
    ang = flat - g.alpha
    cphi = np.cos(ang)
    if not plus:
        np.negative(cphi, out=cphi)
    weights = (half[:, None] * GL_WEIGHTS).ravel()
    return HalfRule(plus, edges, half, s, weights, x, d, cphi, np.sin(ang))


def rule_speed(hf: HalfRule, g: ArcGeometry, h: float | Array) -> Array:
    """|u'| at the nodes of ``hf`` for apex heights ``h`` (units of R; a float
    or a column ``(k, 1)``)."""
    return speed_at(g, hf.x, hf.d, hf.cphi, hf.sphi, h)


def speed_at(
    g: ArcGeometry, x: Array, d: Array, cphi: Array, sphi: Array, h: float | Array
) -> Array:
    """|u'| at arc points with in-plane coordinates ``x``, ``d`` (units of R) and
    arc parameter cosines/sines ``cphi``, ``sphi``, apex at height(s) ``h``."""
    q = d - h * g.sin_beta
    t = h * g.cos_beta
    w = x * cphi
    w = w + q * sphi
    den = x * x
    den = den + q * q
    den += t * t
    num = np.hypot(w, t)
    num /= den
    return num


def halved(edges: Array) -> Array:
    """Panel edges with every panel split in two."""
    out = np.empty(2 * len(edges) - 1)
    out[::2] = edges
    out[1::2] = 0.5 * (edges[:-1] + edges[1:])
    return out
