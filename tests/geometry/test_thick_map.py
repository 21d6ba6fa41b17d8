"""The thick sheet's offsets about the exact cone (geometry/thick_sheet.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    SheetSurface,
    fold_design,
)
from onefold_cad.geometry.material import sheet_offsets
from onefold_cad.geometry.slab import Slab
from onefold_cad.geometry.slab_volume import section_integral, slab_volume
from onefold_cad.geometry.thick_map import (
    MITRE_CLEARANCE,
    SideMap,
    min_hole_diameter,
    min_relief_hole,
    mitre_depth,
    mitre_planes,
)


def _fold(alpha=50.0, beta=45.0, h_c=0.0, sheet=None, model="exact"):
    sheet = sheet or Sheet.quadrilateral(300, 200, 250, 150)
    return fold_design(Design("t", FrameCurve(alpha, beta, h_c), sheet, model=model))


@settings(max_examples=25, deadline=None)
@given(
    alpha=st.floats(10, 80),
    beta=st.floats(10, 80),
    frac=st.floats(-0.6, 0.6),
    lower=st.booleans(),
)
def test_side_map_at_s0_is_the_folded_surface(alpha, beta, frac, lower):
    folded = _fold(alpha, beta, frac * 100 * math.cos(math.radians(alpha)))
    side = SideMap(folded, lower=lower)
    theta = np.linspace(0.05, math.pi - 0.05, 9)
    r = np.linspace(20.0, 120.0, 9)
    psi = -theta if lower else theta
    xy = np.stack([r * np.cos(psi), r * np.sin(psi)], axis=1)
    mirror = np.array([1.0, -1.0, 1.0]) if lower else np.ones(3)
    np.testing.assert_allclose(
        side.points(theta, r, 0.0) * mirror, folded.map_points(xy), atol=1e-9
    )
    # its normal is the top normal of that side (the -y side's, mirrored back)
    _, _, n = side.frames(theta)
    np.testing.assert_allclose(n * mirror, folded.normals(xy), atol=1e-9)


@settings(max_examples=20, deadline=None)
@given(alpha=st.floats(10, 80), beta=st.floats(10, 80), s=st.floats(-5.0, 5.0))
def test_jacobian_is_r_minus_s_k(alpha, beta, s):
    """dF/dtheta = (r - s k) e: the basis of the slab's volume formula."""
    side = SideMap(_fold(alpha, beta))
    theta, r, h = np.array([0.4, 1.3, 2.7]), np.full(3, 80.0), 1e-6
    dF = (side.points(theta + h, r, s) - side.points(theta - h, r, s)) / (2 * h)
    _, e, _ = side.frames(theta)
    expected = (r - s * side.curvature(theta))[:, None] * e
    np.testing.assert_allclose(dF, expected, atol=1e-5)


def test_sheet_offsets_follow_sheet_surface():
    t = 2.0
    got = {s: sheet_offsets(Material(thickness=t, sheet_surface=s)) for s in SheetSurface}
    assert got == {
        SheetSurface.INSIDE: (-2.0, 0.0),
        SheetSurface.OUTSIDE: (0.0, 2.0),
        SheetSurface.MID: (-1.0, 1.0),
    }


def test_mid_slab_volume_is_area_times_thickness_up_to_the_mitre():
    """A developable mid-surface slab holds area x t; the mitre's wedges (a
    convex one added and a concave one cut off per crease half and side, each
    length x (t/2) x (t/2) tan(psi/2) / 2) nearly cancel."""
    folded = _fold()
    m = Material(thickness=3.0, sheet_surface=SheetSurface.MID)
    hole = 20.0
    area = folded.sheet.area - math.pi * hole**2 / 4
    v_mid = slab_volume(folded, m, hole)
    wedges = sum(
        2 * h.length * 1.5 * 1.5 * math.tan(math.radians(h.fold_angle_deg) / 2) / 2
        for h in folded.crease
    )
    assert abs(v_mid - area * 3.0) < wedges
    # INSIDE and OUTSIDE differ from it in opposite directions
    v_in = slab_volume(folded, m.with_changes(sheet_surface=SheetSurface.INSIDE), hole)
    v_out = slab_volume(folded, m.with_changes(sheet_surface=SheetSurface.OUTSIDE), hole)
    assert (v_in - area * 3.0) * (v_out - area * 3.0) < 0


def _clip(poly: list[tuple[float, float]], a: float, b: float, g: float) -> list:
    """The polygon ``poly`` (r, s) clipped to a r + b s + g >= 0 (Sutherland-Hodgman)."""
    out = []
    for i, p in enumerate(poly):
        q = poly[(i + 1) % len(poly)]
        fp, fq = a * p[0] + b * p[1] + g, a * q[0] + b * q[1] + g
        if fp >= 0:
            out.append(p)
        if (fp >= 0) != (fq >= 0):
            x = fp / (fp - fq)
            out.append((p[0] + x * (q[0] - p[0]), p[1] + x * (q[1] - p[1])))
    return out


def _polygon_integral(poly: list[tuple[float, float]], k: float) -> float:
    """The integral of r - k s over a simple polygon in (r, s) (Green's formula)."""
    total = 0.0
    for i, (x0, y0) in enumerate(poly):
        x1, y1 = poly[(i + 1) % len(poly)]
        cross = x0 * y1 - x1 * y0
        total += cross * ((x0 + x1) - k * (y0 + y1)) / 6.0
    return total


@pytest.mark.parametrize("surface", list(SheetSurface))
def test_section_integral_matches_the_clipped_polygon(surface):
    """The cross-section integral (Gauss-Legendre between the planes' crossings)
    against the rectangle r in [r_in, r_out], s in s_range clipped by each
    cutting plane as a polygon and integrated exactly: on the sheet, near a
    crease where the plane y = 0 cuts, and on the mitre blocks past both
    crease halves (a sharp fold: the mitre planes cut them)."""
    folded = _fold(70, 60, 10.0)
    m = Material(thickness=4.0, sheet_surface=surface)
    slab = Slab(folded, m, 1.2 * min_relief_hole(folded, m))
    s0, s1 = slab.s_range
    lo, hi = slab.domain
    theta = np.concatenate(
        [np.linspace(lo, 0.0, 9)[1:-1], [1e-4, 0.002, 1.0, slab.total - 0.002, slab.total - 1e-4]]
    )
    theta = np.concatenate([theta, np.linspace(slab.total, hi, 9)[1:-1]])
    u, _, n = slab.frames(theta)
    k = slab.sides[0].curvature(theta)
    for side in (0, 1):
        exact = section_integral(slab, side, theta)
        for i, t in enumerate(theta):
            r_in = float(slab.inner_radius(np.array([t]))[0])
            r_out = float(slab.outer_radius(side, np.array([t]))[0])
            poly = [(r_in, s0), (r_out, s0), (r_out, s1), (r_in, s1)]
            names = ["y"] + (["m0"] if t < 0.0 else ["m1"] if t > slab.total else [])
            for name in names:
                w, c = slab.planes[name]
                poly = _clip(poly, float(u[i] @ w), float(n[i] @ w), -c) if poly else poly
            expected = _polygon_integral(poly, float(k[i])) if len(poly) > 2 else 0.0
            assert exact[i] == pytest.approx(expected, rel=1e-12, abs=1e-12 * r_out**2)


def test_mitre_blocks_stay_clear_of_each_other():
    """On a sharp fold the blocks past the two crease halves would overlap next
    to the relief hole; each is cut MITRE_CLEARANCE x t short of the plane
    that bisects the crease halves, on its own side."""
    folded = _fold(70, 60, 10.0)
    m = Material(thickness=4.0)
    hole = 1.2 * min_relief_hole(folded, m)
    slab = Slab(folded, m, hole)
    rng = np.random.default_rng(0)
    u0, u1 = slab.sides[0].crease_frame(0)[0], slab.sides[0].crease_frame(1)[0]
    bisector = (u0 - u1) / np.linalg.norm(u0 - u1)
    clear = MITRE_CLEARANCE * 4.0
    kept = []
    for end, (lo, hi) in enumerate(((slab.domain[0], 0.0), (slab.total, slab.domain[1]))):
        t = rng.uniform(lo, hi, 20000)
        r = rng.uniform(slab.inner_radius(t), slab.outer_radius(0, t))
        s = rng.uniform(*slab.s_range, 20000)
        u, _, n = slab.frames(t)
        p = r[:, None] * u + s[:, None] * n
        inside = p[:, 1] >= 0.0
        w, c = slab.planes[f"m{end}"]
        inside &= p @ w >= c
        kept.append(p[inside] @ bisector)
    assert len(kept[0]) and len(kept[1])
    assert kept[0].min() >= clear - 1e-9 and kept[1].max() <= -clear + 1e-9


def test_min_relief_hole_grows_with_thickness_and_covers_the_mitre():
    folded = _fold()
    holes = [min_relief_hole(folded, Material(thickness=t)) for t in (1.0, 2.0, 4.0)]
    assert 0 < holes[0] < holes[1] < holes[2]
    # the regularity bound 2 max(s k) alone, computed here from the curvature
    side = SideMap(folded)
    k = side.curvature(np.linspace(0.01, side.total - 0.01, 400))
    s_range = sheet_offsets(Material(thickness=2.0))
    regular = 2 * max(float(np.max(s * k)) for s in s_range)
    assert holes[1] >= regular * (1 - 1e-3) and holes[1] >= 2 * mitre_depth(side, s_range)
    # and the crease rulings' sections (r >= hole, s from 0 to the convex
    # face) clear the other crease half's mitre plane
    for end, (w, c) in enumerate(mitre_planes(side, 2.0)):
        u, _, n = side.crease_frame(end)
        s_c = max(s_range, key=lambda x: x * n[1])
        for s in (0.0, s_c):
            assert (0.5 * holes[1] * u + s * n) @ w >= c
    # a hole below the minimum puts the sheet's face over the apex region: the
    # offset point at r just under s k lies on the other side of the ruling
    theta = np.linspace(0.01, side.total - 0.01, 400)
    s = min(s_range) if regular == 2 * float(np.max(min(s_range) * k)) else max(s_range)
    worst = int(np.argmax(s * k))
    r = 0.9 * float(s * k[worst])
    h = 1e-4
    p0 = side.points(theta[worst : worst + 1] - h, np.array([r]), s)
    p1 = side.points(theta[worst : worst + 1] + h, np.array([r]), s)
    _, e, _ = side.frames(theta[worst : worst + 1])
    assert float((p1 - p0)[0] @ e[0]) < 0  # the offset runs backwards: folded over


def test_paper_model_is_refused():
    with pytest.raises(InvalidParameterError, match="model"):
        SideMap(_fold(model="paper"))


def test_frames_and_curvature_in_one_call_are_each_angles_own():
    """:meth:`SideMap.frames_and_curvature` evaluates the frames at theta and
    theta +- h in one call: the same u, e, n and k as separate calls, angle
    by angle (on the sheet, at the creases and past them)."""
    side = SideMap(_fold(70, 60, 10.0))
    theta = np.concatenate(
        [[-0.1, 0.0, 1e-7, side.total, side.total + 0.1], np.linspace(0.01, 3, 9)]
    )
    u, e, n, k = side.frames_and_curvature(theta)
    h = 1e-6
    for i, t in enumerate(theta):
        ui, ei, ni = (v[0] for v in side.frames(np.array([t])))
        np.testing.assert_allclose([u[i], e[i], n[i]], [ui, ei, ni], rtol=0, atol=2e-15)
        lo, hi = np.clip([t - h, t + h], 0.0, side.total)
        if t < 0.0 or t > side.total:
            assert k[i] == 0.0
            continue
        dn = side.frames(np.array([hi]))[2][0] - side.frames(np.array([lo]))[2][0]
        # the difference quotient of n: rounding errors of n over h
        assert k[i] == pytest.approx(-float(dn @ ei) / (hi - lo), abs=1e-8)


def test_min_hole_diameter_is_the_same_on_both_sides():
    """min_relief_hole reads one side: the -y side's map, built for the
    mirrored sheet, gives the same smallest hole on a sheet that is not
    symmetric about the crease."""
    folded = _fold(40, 60, 20.0, sheet=Sheet.quadrilateral(300, 120, 250, 90))
    for surface in SheetSurface:
        s_range = sheet_offsets(Material(thickness=3.0, sheet_surface=surface))
        upper = min_hole_diameter(SideMap(folded), s_range)
        assert upper == min_hole_diameter(SideMap(folded, lower=True), s_range)
        assert upper == min_relief_hole(folded, Material(thickness=3.0, sheet_surface=surface))


def test_face_breaks_are_sign_changes_of_their_functions():
    """Each zero Slab.roots finds (one grid evaluation of all functions,
    frames once per angle, then bisection) is where its function, evaluated
    alone at angles just beside it, changes sign."""
    folded = _fold(70, 60, 10.0, sheet=Sheet.quadrilateral(300, 120, 250, 90))
    slab = Slab(folded, Material(thickness=4.0), 2.0 * min_relief_hole(folded, Material(4.0)))
    specs, _ = slab._specs()
    found = 0
    for spec in specs:
        for r in slab.roots[spec]:
            d = 1e-9 * max(1.0, abs(r))
            lab = np.zeros(2, dtype=int)
            lo, hi = slab._evaluate([spec], lab, np.array([r - d, r + d]))
            assert lo * hi <= 0.0, (spec, r, lo, hi)
            found += 1
    assert found > 0
