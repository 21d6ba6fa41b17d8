"""The body a form is written as: its minimiser, its pieces, its mass."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad import FrameCurve, Sheet, fold, solve
from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.body_mass import mass_properties
from onefold_cad.geometry.pieces import clipped_rectangle, zoom_min
from onefold_cad.geometry.thick_map import SideMap


def test_zoom_min_finds_smooth_kinked_and_end_minima() -> None:
    t, v = zoom_min(lambda x: (x - 0.3137) ** 2 + 2.0, 0.0, 1.0)
    assert abs(t - 0.3137) <= 1e-7 and abs(v - 2.0) <= 1e-15
    t, v = zoom_min(lambda x: np.abs(x - 0.7071), 0.0, 1.0)  # a kink
    assert abs(t - 0.7071) <= 1e-12 and v <= 1e-12
    t, v = zoom_min(lambda x: np.cos(x), 0.0, 2.0)  # at the bracket's end
    assert t == 2.0 and v == math.cos(2.0)
    t, v = zoom_min(lambda x: np.where(x < 0.5, np.inf, x), 0.0, 1.0)  # empty part
    assert abs(t - 0.5) <= 1e-12


@pytest.fixture(scope="module")
def folded():
    return fold(solve(FrameCurve(35.0, 45.0, 8.0, 100.0), "exact"), Sheet.rectangle(600, 400, 0.4))


def test_shell_mass_is_the_area_and_its_centroid(folded) -> None:
    area, com = mass_properties(FoldedBody(folded))
    assert abs(area - folded.sheet.area) <= 1e-10 * folded.sheet.area
    # the centroid of a fine mesh of the surface, extrapolated in its step (h^2)
    cents = []
    for k in (1, 2):
        v, f = folded.mesh(angular=200 * k, radial=20 * k)
        tri = v[f]
        w = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
        cents.append((w[:, None] * tri.mean(axis=1)).sum(axis=0) / w.sum() - folded.apex)
    rich = (4.0 * cents[1] - cents[0]) / 3.0
    assert np.linalg.norm(com - rich) <= 1e-6 * folded.sheet.size


def test_arc_frames_are_the_cone_s(folded) -> None:
    # the body's frames, straight from the arc, against the cone's and the
    # solid's: directions and normals (SideMap), the geodesic curvature
    # (thick_sheet's finite differences) and dtheta/dphi (central differences
    # of the cone's own theta(phi))

    cone, side = folded.solution.surface, SideMap(folded)
    theta = np.linspace(0.05, side.total - 0.05, 41)
    phi = cone.phi_of_theta(theta)
    u, e, n, k, speed = ArcFrames(folded.solution.frame, folded.apex).frames(phi, curvature=True)
    su, se, sn = side.frames(theta)
    for mine, theirs in ((u, su), (e, se), (n, sn)):
        np.testing.assert_allclose(mine, theirs, atol=1e-12)
    np.testing.assert_allclose(k, side.curvature(theta), rtol=1e-6, atol=1e-9)
    h = 1e-5
    slope = (cone.theta_of_phi(phi + h) - cone.theta_of_phi(phi - h)) / (2 * h)
    np.testing.assert_allclose(speed, slope, rtol=1e-9)


def test_lowest_asked_again_answers_the_same_without_zooming(folded, monkeypatch) -> None:
    # a repeated (piece, bracket, direction) gives the first zoom's answer, a
    # copy (callers keep and move their points); a new direction zooms anew
    import onefold_cad.geometry.body as body_mod

    body = FoldedBody(folded)
    zooms = []
    real = body_mod.zoom_min

    def counting(f, lo, hi):
        zooms.append((lo, hi))
        return real(f, lo, hi)

    monkeypatch.setattr(body_mod, "zoom_min", counting)
    piece = body.pieces[0]
    g = np.array([0.0, 0.3, -1.0]) / math.hypot(0.3, 1.0)
    t1, p1 = body.lowest(0, piece.t0, piece.t1, g)
    p1[:] = np.nan  # the caller's copy
    t2, p2 = body.lowest(0, piece.t0, piece.t1, g * 1.0 + 0.0)
    assert len(zooms) == 1 and t2 == t1 and np.all(np.isfinite(p2))
    np.testing.assert_array_equal(p2, piece.lowest(t1, g))
    body.lowest(0, piece.t0, piece.t1, -g)
    assert len(zooms) == 2


def test_clipped_rectangle_gives_the_corners_inside_and_the_line_s_crossings() -> None:
    # against the definition, rectangle by rectangle: the corners on the kept
    # side of cr r + cs s = 0 and the points where that line crosses a side

    rng = np.random.default_rng(7)
    k = 200
    r0 = rng.uniform(0.0, 2.0, k)
    r1 = r0 + rng.uniform(0.1, 5.0, k)
    s0, s1 = -1.5, 0.5
    cr = rng.choice([0.0, 0.4, -0.7, 1.0], k)
    cs = rng.choice([0.0, 0.6, -1.0], k)
    cr[(cr == 0.0) & (cs == 0.0)] = 1.0
    z = clipped_rectangle(r0, r1, s0, s1, cr, cs, 0.0)
    for i in range(k):
        want = [(r, s) for r, s in ((r0[i], s0), (r1[i], s0), (r1[i], s1), (r0[i], s1))
                if cr[i] * r + cs[i] * s >= 0.0]  # fmt: skip
        if cr[i] != 0.0:
            want += [
                (-cs[i] * s / cr[i], s) for s in (s0, s1) if r0[i] <= -cs[i] * s / cr[i] <= r1[i]
            ]
        if cs[i] != 0.0:
            want += [
                (r, -cr[i] * r / cs[i]) for r in (r0[i], r1[i]) if s0 <= -cr[i] * r / cs[i] <= s1
            ]
        got = sorted(tuple(map(float, p)) for p in z[i] if not np.isnan(p[0]))
        assert len(got) == len(want)
        np.testing.assert_allclose(got, sorted(want), rtol=0, atol=1e-15)
        assert all(np.isnan(p).all() or not np.isnan(p).any() for p in z[i])
