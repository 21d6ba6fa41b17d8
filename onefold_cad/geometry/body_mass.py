"""The centre of mass of a folded form's body, integrated from its description.

Area-weighted on the reference surface for zero thickness, volume-weighted
(Jacobian ``r - s k``, k the geodesic curvature of u, see
:mod:`onefold_cad.geometry.thick_map`) otherwise: the slab of each side by a
composite Gauss-Legendre rule over the sectors between vertex rays, and for
the exact model's solid the mitre blocks past the creases. Points are
relative to the apex; lengths in the design unit.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body import MIRROR, FoldedBody
from onefold_cad.geometry.body_kinks import arc_section, flat_section, section_kinks
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.numeric import Array, cross3, gauss_legendre, panel_rule, sorted_unique
from onefold_cad.geometry.sheet import Sheet

__all__ = ["mass_properties"]


def mass_properties(body: FoldedBody) -> tuple[float, Array]:
    """The sheet's measure (area for zero thickness, else volume; length^2
    or length^3) and its centre of mass ``(3,)`` (relative to the apex).

    The thickness and reference surface are the material's whichever
    body is written (the part that stands is the thick sheet); the relief
    hole is left out; for the exact model the solid's mitre blocks count."""
    folded = body.folded
    cone = folded.solution.surface
    up, lo = folded.sheet.side_angles
    sides = []
    for lower in (False, True):
        breaks = np.clip(np.asarray(lo if lower else up, dtype=float), 0.0, cone.total_angle)
        sides.append((lower, breaks, *_towards_poles(folded.sheet, breaks, lower)))
    slabs = _exact_slabs if body.exact else _paper_slabs
    total, moment = slabs(body, sides)
    return total, moment / total


def _paper_slabs(
    body: FoldedBody, sides: list[tuple[bool, Array, Array, Array]]
) -> tuple[float, Array]:
    """The paper model's measure and first moment (see :func:`mass_properties`),
    ``sides`` as :func:`_exact_slabs`': planar triangles, no curvature within
    them, the rule in the flat angle with breaks at the division rays (where
    the wedges' planes kink) and at the thick sheet's cut (:func:`flat_section`)."""
    cone = body.folded.solution.surface
    total, moment = 0.0, np.zeros(3)
    rays = np.asarray(getattr(cone, "thetas", []), dtype=float)
    # a thick sheet's cut leaves r > C / theta near the crease ends, steep
    # over the first degrees whatever the sheet's vertices: graded from an
    # eighth of the side (in halvings), on the finer rule
    reach = cone.total_angle / 8.0
    steps = reach * 0.5 ** np.arange(_PAPER_HALVINGS + 1)
    grades = []
    for _, breaks, poles, _ in sides:
        inside = rays[(rays > breaks[0]) & (rays < breaks[-1])]
        graded = [_graded(breaks, _PAPER_HALVINGS), poles, inside]
        if body.thickness > 0.0:
            graded += [breaks[0] + steps, breaks[-1] - steps]
        kept = sorted_unique(np.concatenate(graded))
        grades.append(kept[(kept >= breaks[0]) & (kept <= breaks[-1])])
    kinks = section_kinks(body, flat_section(body), grades)
    for (lower, ends, _, spans), graded, cuts in zip(sides, grades, kinks, strict=True):
        breaks = np.sort(np.concatenate([graded, cuts]))
        if body.thickness > 0.0:
            crease = [[ends[0], ends[0] + reach], [ends[-1] - reach, ends[-1]]]
            spans = np.vstack([spans, crease])
        theta, weights = _sector_rule(breaks, _PAPER_POINTS, _PAPER_PANELS, (_EXACT_POINTS, spans))
        u, e = cone.frames(theta)
        n, k = cross3(u, e), np.zeros(len(theta))
        vals = weights @ _slab_moments(body, theta, np.full(len(theta), lower), u, n, k)
        total += vals[0]
        moment += vals[1:] * (MIRROR if lower else np.ones(3))
    return total, moment


def _exact_slabs(
    body: FoldedBody, sides: list[tuple[bool, Array, Array, Array]]
) -> tuple[float, Array]:
    """The exact model's measure and first moment (see :func:`mass_properties`)
    from both sides' ``(lower, vertex angles, breaks towards poles, their
    spans)``, their rules evaluated together.

    The rule runs in the arc's phi (no inversion at every node): dtheta =
    |du/dphi| dphi, theta being u's arc length; its panels end at the vertex
    rays (the edge radius's kinks) and at the section's own kinks
    (:func:`~onefold_cad.geometry.body_kinks.section_kinks`), and are graded
    towards the crease ends (:func:`_graded`) and towards poles
    (:func:`_towards_poles`), the graded breaks' arc parameters from the cone's
    table (their errors vanish towards the crease ends, where they crowd),
    the vertex rays' exact."""
    folded = body.folded
    cone = folded.solution.surface
    assert isinstance(cone, ExactCone)
    grades, ats = [], []
    for lower, breaks, poles, _ in sides:
        graded = sorted_unique(np.concatenate([_graded(breaks, _EXACT_HALVINGS), poles]))
        at = cone.phi_near(graded)
        at[np.searchsorted(graded, breaks)] = body.vertex_phis[int(lower)]
        grades.append(graded)
        ats.append(np.maximum.accumulate(at))
    rules = []
    for graded, at, kinks in zip(
        grades, ats, section_kinks(body, arc_section(body), ats), strict=True
    ):
        breaks = np.sort(np.concatenate([at, kinks]))
        phi, weights = _sector_rule(breaks, _EXACT_POINTS, _EXACT_PANELS)
        rules.append((phi, weights, graded))
    phi = np.concatenate([r[0] for r in rules])
    on_lower = np.repeat([False, True], [len(r[0]) for r in rules])
    theta = cone.theta_near(phi)
    for side, (_, _, graded) in enumerate(rules):
        np.clip(theta, graded[0], graded[-1], out=theta, where=on_lower == bool(side))
    u, _, n, k, speed = ArcFrames(folded.solution.frame, folded.apex).frames(phi, curvature=True)
    slab = _slab_moments(body, theta, on_lower, u, n, k) * speed[:, None]
    total, moment = 0.0, np.zeros(3)
    blocks = _block_moments(body) if body.thickness > 0.0 else []
    for side, (_, weights, _) in enumerate(rules):
        vals = weights @ slab[on_lower == bool(side)]
        total += vals[0]
        moment += vals[1:] * (MIRROR if side else np.ones(3))
        for vol, mom in blocks[2 * side : 2 * side + 2]:
            total += vol
            moment += mom * (MIRROR if side else np.ones(3))
    return total, moment


def _towards_poles(sheet: Sheet, breaks: Array, lower: bool) -> tuple[Array, Array]:
    """Breaks ``(k,)`` (flat angles) grading each sector between vertex rays
    towards an end near which its ray length is steep: along a straight
    edge r = d / sin(psi_s - theta), whose pole psi_s lies beyond the end
    vertex by the edge's angle there with the ray (the angle of the triangle
    H, start, end at that vertex). An edge nearly along its end's ray (a
    needle's) puts the pole within a degree or two: breaks at that distance
    times 1/16, 1/8, ... 1, 2, 4, ... from the end, up to half the sector
    (none for a sector whose ends' angles are a quarter of it or more); and
    the spans ``(j, 2)`` so graded, where a rule of few points would
    converge too slowly."""
    psi = -breaks if lower else breaks
    r = sheet.ray_lengths(psi)
    p = r[:, None] * np.column_stack([np.cos(psi), np.sin(psi)])
    width = np.diff(breaks)
    out, spans = [], []
    for i in np.nonzero(width > 0.0)[0]:
        a, b = p[i], p[i + 1]
        for end, other, sign in ((b, a, -1.0), (a, b, 1.0)):
            edge, back = other - end, -end
            cos = float(edge @ back) / max(float(np.hypot(*edge) * np.hypot(*back)), 1e-300)
            angle = math.acos(min(max(cos, -1.0), 1.0))
            if not 0.0 < angle < 0.25 * width[i]:
                continue
            steps = angle * 2.0 ** np.arange(-4, int(math.log2(0.5 * width[i] / angle)) + 1)
            start = breaks[i + 1] if sign < 0 else breaks[i]
            out.append(start + sign * steps)
            spans.append(sorted((start, start + sign * 0.5 * width[i])))
    return (np.concatenate(out) if out else np.empty(0)), np.array(spans).reshape(-1, 2)


def _graded(breaks: Array, halvings: int) -> Array:
    """The sector breaks ``(m,)`` (flat angles, or the arc parameters of the
    vertex rays) graded towards both crease ends, halving the distance to
    each ``halvings`` times from an eighth of the end sector: the cut at the
    crease (thick sheet), and a sheet edge passing near H (r = d / sin(theta
    + psi): a peak of width psi at theta = 0 or pi, e.g. a needle's tip)."""
    grade = 0.5 ** np.arange(3, 3 + halvings)
    near = breaks[0] + (breaks[1] - breaks[0]) * grade
    far = breaks[-1] - (breaks[-1] - breaks[-2]) * grade
    return sorted_unique(np.concatenate([breaks, near, far]))


def _slab_moments(
    body: FoldedBody, theta: Array, lower: NDArray[np.bool_], u: Array, n: Array, k: Array
) -> Array:
    """Per flat angle ``(k,)`` of the -y side or not (``lower``), with the
    ruling direction u, top normal n and curvature k there: the section's
    measure and first moment ``(k, 4)`` (per radian), in the +y side's
    coordinates."""
    rho = body.hole
    r_out = body.folded.sheet.ray_lengths(np.where(lower, -theta, theta))
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
    # s0, s_b and s_e within [s0, s1], s1: sorted (np.sort's result, cheaper)
    s_b = np.minimum(np.maximum(s_b, s0), s1)
    s_e = np.minimum(np.maximum(s_e, s0), s1)
    cuts = np.column_stack(
        [np.full_like(uy, s0), np.minimum(s_b, s_e), np.maximum(s_b, s_e), np.full_like(uy, s1)]
    )
    lo, hi = cuts[:, :3], cuts[:, 1:]
    out = np.zeros((len(theta), 4))
    ro = r_out[:, None]
    # on each part r_lo (the cut's r, clipped to [rho, r_out]) is rho, the
    # cut's line (linear in s) or r_out throughout: which, at its middle
    mid = 0.5 * (lo + hi)
    r_mid = _cut_radius(mid, uy, ny)
    at_rho = (r_mid <= rho) & (hi > lo) & (ro > rho)  # (no sheet inside the hole)
    # r_lo = rho: the moments are polynomials in s of degree 2, in closed form
    d1 = np.where(at_rho, hi - lo, 0.0)
    d2 = d1 * (lo + hi) / 2.0  # (hi^2 - lo^2) / 2
    d3 = d1 * (lo * lo + lo * hi + hi * hi) / 3.0  # (hi^3 - lo^3) / 3
    a2, b1 = (ro**2 - rho**2) / 2.0, ro - rho
    a3 = (ro**3 - rho**3) / 3.0
    kk = k[:, None]
    m0 = (a2 * d1 - kk * b1 * d2).sum(axis=1)
    m1 = (a2 * d2 - kk * b1 * d3).sum(axis=1)
    m2 = (a3 * d1 - kk * a2 * d2).sum(axis=1)
    # r_lo on the cut's line: 3-point Gauss-Legendre (exact: degree 4 in s),
    # on those parts only (r_lo = r_out leaves nothing)
    ti, pi = np.nonzero((r_mid > rho) & (r_mid < ro) & (hi > lo))
    if len(ti):
        nodes, weights = gauss_legendre(3)
        half = 0.5 * (hi[ti, pi] - lo[ti, pi])
        ss = lo[ti, pi][:, None] + half[:, None] * (1.0 + nodes)  # (c, 3)
        ww = half[:, None] * weights
        rc = ro[ti]
        r_lo = np.minimum(np.maximum(rho, _cut_radius(ss, uy[ti], ny[ti])), rc)
        sk = ss * kk[ti]
        i0 = (rc**2 - r_lo**2) / 2.0 - sk * (rc - r_lo)
        i1 = (rc**3 - r_lo**3) / 3.0 - sk * (rc**2 - r_lo**2) / 2.0
        w0 = ww * i0
        n_t = len(theta)
        m0 += np.bincount(ti, w0.sum(axis=1), n_t)
        m1 += np.bincount(ti, (w0 * ss).sum(axis=1), n_t)
        m2 += np.bincount(ti, (ww * i1).sum(axis=1), n_t)
    out[:, 0] = m0
    out[:, 1:] = m1[:, None] * n + m2[:, None] * u
    return out


def _cut_radius(s: Array, uy: Array, ny: Array) -> Array:
    """The r at which y = r u_y + s n_y = 0 cuts each ruling at offsets ``s``
    ``(k, m)`` (u_y, n_y ``(k,)``): -s n_y / u_y; -inf (no cut) or +inf (all
    cut) where u_y = 0."""
    sny, suy = s * ny[:, None], uy[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(suy > 0.0, -sny / suy, np.where(sny >= 0.0, -np.inf, np.inf))


def _block_moments(body: FoldedBody) -> list[tuple[float, Array]]:
    """Volume and first moment ``(3,)`` of the kept part of each mitre block
    (:attr:`FoldedBody.mitre_frames`; +y side's coordinates): x integrated exactly,
    Gauss-Legendre in d and s, the four blocks in one pass."""
    s0, s1 = body.s_range
    rho = body.hole
    frames = body.mitre_frames
    u, away, n = (np.array([f[k] for f in frames]) for k in (2, 3, 4))  # (4, 3) each
    length, depth = (np.array([f[k] for f in frames])[:, None, None] for k in (5, 6))
    planes = [f[7] for f in frames]
    um, am, nm = (
        np.array([float(v @ m) for v, m in zip(w, planes, strict=True)]) for w in (u, away, n)
    )
    c = np.array([f[8] for f in frames])[:, None, None]
    (xs, ws), (xd, wd) = gauss_legendre(8), gauss_legendre(48)
    # the s nodes ``(8,)``, each with its d nodes ``(4, 8, 48)``
    si, wsi = s0 + (s1 - s0) * 0.5 * (1.0 + xs), ws * 0.5 * (s1 - s0)
    # y = d away_y + s n_y >= 0 (u_y = 0 on the crease): a bound on d
    sn = si * n[:, 1:2]
    with np.errstate(divide="ignore", invalid="ignore"):
        d_hi = np.where(
            away[:, 1:2] < 0.0,
            np.minimum(depth[:, 0], np.maximum(sn / -away[:, 1:2], 0.0)),
            np.where(sn >= 0.0, depth[:, 0], 0.0),
        )
    d = 0.5 * d_hi[..., None] * (1.0 + xd)
    wdd = wd * 0.5 * d_hi[..., None]
    xa = np.sqrt(np.maximum(rho * rho - d * d, 0.0))
    xb = np.broadcast_to(length, d.shape)
    # (p - A) . m = x (u.m) + d (away.m) + s (n.m) >= c
    c0 = d * am[:, None, None] + si[:, None] * nm[:, None, None] - c
    up = um[:, None, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        cut = -c0 / up
    xa = np.where(up > 0.0, np.maximum(xa, cut), xa)
    xb = np.where(up < 0.0, np.minimum(xb, cut), xb)
    xb = np.where((up == 0.0) & (c0 < 0.0), xa, xb)
    span = np.maximum(xb - xa, 0.0)
    sq = np.where(span > 0.0, 0.5 * (xb**2 - xa**2), 0.0)
    ws_span = wsi[:, None] * wdd * span  # ``(4, 8, 48)``
    flat = ws_span.reshape(len(frames), -1)
    vol = flat.sum(axis=1)
    along = (ws_span * d).reshape(len(frames), -1).sum(axis=1)
    ins = (wsi[:, None] * wdd * sq).reshape(len(frames), -1).sum(axis=1)
    out = []
    for k in range(len(frames)):
        mom = float(along[k]) * away[k] + float(ws_span[k].sum(axis=1) @ si) * n[k]
        mom += float(ins[k]) * u[k]
        out.append((float(vol[k]), mom))
    return out


#: Gauss-Legendre points per panel. Every sector's integrand is smooth: its
#: breaks are the vertex rays, the grading towards the crease ends and
#: towards a vertex whose edge runs nearly along its ray (:func:`_towards_poles`),
#: and the kinks within (:mod:`~onefold_cad.geometry.body_kinks`: where the
#: fold's plane cuts a corner of the thick slab), and for the paper model its
#: division rays, between which its planar wedges (a few degrees each) take 4
#: points in up to 2 panels, the spans graded towards a pole and, for a thick
#: sheet, the eighth of each side at a crease end (graded too: the cut's
#: r > C / theta) 16. Against a rule of 40 points, 32 panels and 40 halvings the
#: measure and the centre of mass agree within 1e-12 (of the measure, of the
#: size) on every template, and the paper sheet's centroid is its folded
#: pieces' to 1e-12 (tests/geometry/test_body_mass.py). The rule before (16
#: points, 8 panels, 28 halvings, none of those breaks) was off by up to 7e-10
#: of the volume on the templates, 2e-8 of the size on drawn thick sheets,
#: 9e-7 on the paper templates and 1e-7 to 4e-7 on needles.
_EXACT_POINTS = 16
_PAPER_POINTS = 4
#: Panels per sector, at most (in proportion to its width), and the
#: grading's halvings towards the crease ends, for each model.
_EXACT_PANELS, _EXACT_HALVINGS = 8, 8
_PAPER_PANELS, _PAPER_HALVINGS = 2, 8


def _sector_rule(
    breaks: Array, points: int, panels: int, fine: tuple[int, Array] | None = None
) -> tuple[Array, Array]:
    """Nodes and weights of a composite ``points``-point Gauss-Legendre rule
    over the sectors between consecutive ``breaks`` (the integrand is smooth
    within each): up to ``panels`` panels per sector, in proportion to its
    width; ``fine``: (more points, spans ``(j, 2)``) for the panels whose
    middle lies in one of those spans.

    The caller also grades the breaks towards the crease (:func:`_graded`):
    the cut at the fold's plane of symmetry leaves only
    r > C / theta of a thick sheet's concave side there, a feature on every
    scale from the hole's radius to the sheet's edge; and a sheet edge that
    passes near H along the crease peaks there on the scale of its angle."""
    lo, hi = breaks[:-1], breaks[1:]
    keep = hi > lo
    lo, hi = lo[keep], hi[keep]
    count = np.clip(np.ceil(panels * (hi - lo) / np.max(hi - lo)), 1, panels).astype(int)
    owner = np.repeat(np.arange(len(lo)), count)
    step = ((hi - lo) / count)[owner]
    first = np.concatenate([[0], np.cumsum(count)[:-1]])
    a = lo[owner] + (np.arange(len(owner)) - first[owner]) * step
    half = 0.5 * step
    mid = a + half
    if fine is None or not len(fine[1]):
        nodes, weights = panel_rule(mid, half, points)
        return nodes.ravel(), weights.ravel()
    more, spans = fine
    near = ((mid[:, None] >= spans[:, 0]) & (mid[:, None] <= spans[:, 1])).any(axis=1)
    n0, w0 = panel_rule(mid[~near], half[~near], points)
    n1, w1 = panel_rule(mid[near], half[near], more)
    return np.concatenate([n0.ravel(), n1.ravel()]), np.concatenate([w0.ravel(), w1.ravel()])
