"""The centre of mass of a folded form's body, integrated from its description.

Area-weighted on the reference surface for zero thickness, volume-weighted
(Jacobian ``r - s k``, k the geodesic curvature of u, see
:mod:`onefold_cad.geometry.thick_map`) otherwise: the slab of each side by a
composite Gauss-Legendre rule over the sectors between vertex rays, and for
the exact model's solid the mitre blocks past the creases. Points are
relative to the apex; lengths in the design unit.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body import MIRROR, Body
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.numeric import Array, cross3, gauss_legendre, panel_rule, sorted_unique
from onefold_cad.geometry.thick_map import CreaseFrames, SideMap, mitre_depth, mitre_planes

__all__ = ["mass_properties"]


def mass_properties(body: Body) -> tuple[float, Array]:
    """The sheet's measure (area for zero thickness, else volume; length^2
    or length^3) and its centre of mass ``(3,)`` (relative to the apex).

    The thickness and reference surface are the material's whichever
    body is written (the part that stands is the thick sheet); the relief
    hole is left out; for the exact model the solid's mitre blocks count."""
    total = 0.0
    moment = np.zeros(3)
    folded = body.folded
    cone = folded.solution.surface
    for lower in (False, True):
        mirror = MIRROR if lower else np.ones(3)
        up, lo = folded.sheet.side_angles
        breaks = np.clip(np.asarray(lo if lower else up, dtype=float), 0.0, cone.total_angle)
        # graded towards both crease ends: the cut at the crease (thick
        # sheet), and a sheet edge passing near H (r = d / sin(theta + psi):
        # a peak of width psi at theta = 0 or pi, e.g. a needle's tip)
        grade = 0.5 ** np.arange(3, 31)
        near = breaks[1] * grade
        far = breaks[-1] - (breaks[-1] - breaks[-2]) * grade
        breaks = sorted_unique(np.concatenate([breaks, near, far]))
        if body.exact:
            # the rule runs in the arc's phi (no inversion at every node):
            # dtheta = |du/dphi| dphi, theta being u's arc length
            assert isinstance(cone, ExactCone)
            phi, weights = _sector_rule(cone.phi_of_theta(breaks))
            theta = np.clip(cone.theta_of_phi(phi), breaks[0], breaks[-1])
            u, _, n, k, speed = ArcFrames(folded.solution.frame, folded.apex).frames(
                phi, curvature=True
            )
            weights = weights * speed
        else:  # planar triangles: no curvature within them
            theta, weights = _sector_rule(breaks)
            u, e = cone.frames(theta)
            n, k = cross3(u, e), np.zeros(len(theta))
        vals = weights @ _slab_moments(body, theta, lower, u, n, k)
        total += vals[0]
        moment += vals[1:] * mirror
        if body.thickness > 0.0 and body.exact:
            side = CreaseFrames(SideMap(folded, lower=lower))
            for end in (0, 1):
                vol, mom = _block_moments(body, side, end)
                total += vol
                moment += mom * mirror
    return total, moment / total


def _slab_moments(body: Body, theta: Array, lower: bool, u: Array, n: Array, k: Array) -> Array:
    """Per flat angle ``(k,)`` (ruling direction u, top normal n and
    curvature k there): the section's measure and first moment ``(k, 4)``
    (per radian), in the +y side's coordinates."""
    rho = body.hole
    r_out = body.folded.sheet.ray_lengths(-theta if lower else theta)
    if body.thickness <= 0.0:
        i0 = 0.5 * (r_out**2 - rho**2)
        i1 = (r_out**3 - rho**3) / 3.0
        return np.column_stack([i0, u * i1[:, None]])
    s0, s1 = body.s_range
    uy, ny = u[:, 1], n[:, 1]
    # y = r u_y + s n_y >= 0 cuts r at -s n_y / u_y (u_y > 0 inside a side):
    # split s where that bound passes rho and r_out
    with np.errstate(divide="ignore", invalid="ignore"):
        s_b = np.where(ny != 0.0, -rho * uy / ny, s0)
        s_e = np.where(ny != 0.0, -r_out * uy / ny, s0)
    cuts = np.column_stack([np.full_like(uy, s0), s_b, s_e, np.full_like(uy, s1)])
    cuts = np.sort(np.clip(cuts, s0, s1), axis=1)
    out = np.zeros((len(theta), 4))
    nodes, weights = gauss_legendre(3)  # exact: degree 4 in s
    for j in range(3):
        lo, half = cuts[:, j], 0.5 * (cuts[:, j + 1] - cuts[:, j])
        for x, w in zip(nodes, weights, strict=True):
            s = lo + half * (1.0 + x)
            with np.errstate(divide="ignore", invalid="ignore"):
                r_y = np.where(uy > 0.0, -s * ny / uy, np.where(s * ny >= 0.0, -np.inf, np.inf))
            r_lo = np.minimum(np.maximum(rho, r_y), r_out)
            sk = s * k
            i0 = (r_out**2 - r_lo**2) / 2.0 - sk * (r_out - r_lo)
            i1 = (r_out**3 - r_lo**3) / 3.0 - sk * (r_out**2 - r_lo**2) / 2.0
            ww = w * half
            out[:, 0] += ww * i0
            first = (s[:, None] * n) * i0[:, None] + u * i1[:, None]
            out[:, 1:] += ww[:, None] * first
    return out


def _block_moments(body: Body, side: CreaseFrames, end: int) -> tuple[float, Array]:
    """Volume and first moment ``(3,)`` of the kept part of the mitre block
    past crease half ``end`` (+y side's coordinates): x integrated exactly,
    Gauss-Legendre in d and s."""
    s0, s1 = body.s_range
    rho = body.hole
    u, e, n = side.crease_frame(end)
    away = -e if end == 0 else e
    length = float(side.edge_radius(np.array([0.0 if end == 0 else side.total]))[0])
    depth = mitre_depth(side, body.s_range)
    m, c = mitre_planes(side, s1 - s0)[end]
    (xs, ws), (xd, wd) = gauss_legendre(8), gauss_legendre(48)
    vol = 0.0
    mom = np.zeros(3)
    for si, wsi in zip(s0 + (s1 - s0) * 0.5 * (1.0 + xs), ws * 0.5 * (s1 - s0), strict=True):
        # y = d away_y + s n_y >= 0 (u_y = 0 on the crease): a bound on d
        if away[1] < 0.0:
            d_hi = min(depth, max(si * n[1] / -away[1], 0.0))
        else:
            d_hi = depth if si * n[1] >= 0.0 else 0.0
        if d_hi <= 0.0:
            continue
        d = 0.5 * d_hi * (1.0 + xd)
        wdd = wd * 0.5 * d_hi
        xa = np.sqrt(np.maximum(rho * rho - d * d, 0.0))
        xb = np.full_like(d, length)
        # (p - A) . m = x (u.m) + d (away.m) + s (n.m) >= c
        um, c0 = float(u @ m), d * float(away @ m) + si * float(n @ m) - c
        if um > 0.0:
            xa = np.maximum(xa, -c0 / um)
        elif um < 0.0:
            xb = np.minimum(xb, -c0 / um)
        else:
            xb = np.where(c0 >= 0.0, xb, xa)
        span = np.maximum(xb - xa, 0.0)
        sq = np.where(span > 0.0, 0.5 * (xb**2 - xa**2), 0.0)
        base = d[:, None] * away + si * n
        vol += wsi * float(wdd @ span)
        mom += wsi * ((wdd * span) @ base + float(wdd @ sq) * u)
    return vol, mom


#: Panels of the 16-point Gauss-Legendre rule per sector between vertex rays.
_PANELS = 8


def _sector_rule(breaks: Array) -> tuple[Array, Array]:
    """Nodes and weights of a composite 16-point Gauss-Legendre rule over the
    sectors between consecutive ``breaks`` (the edge radius is smooth within
    each): up to 8 panels per sector, in proportion to its width.

    The caller also grades the breaks towards the crease (halving the
    distance 28 times): the cut at the fold's plane of symmetry leaves only
    r > C / theta of a thick sheet's concave side there, a feature on every
    scale from the hole's radius to the sheet's edge; and a sheet edge that
    passes near H along the crease peaks there on the scale of its angle."""
    lo, hi = breaks[:-1], breaks[1:]
    keep = hi > lo
    lo, hi = lo[keep], hi[keep]
    panels = np.clip(np.ceil(_PANELS * (hi - lo) / np.max(hi - lo)), 1, _PANELS).astype(int)
    owner = np.repeat(np.arange(len(lo)), panels)
    step = ((hi - lo) / panels)[owner]
    first = np.concatenate([[0], np.cumsum(panels)[:-1]])
    a = lo[owner] + (np.arange(len(owner)) - first[owner]) * step
    half = 0.5 * step
    nodes, weights = panel_rule(a + half, half, 16)
    return nodes.ravel(), weights.ravel()
