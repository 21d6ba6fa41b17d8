"""The wedge-locking check's pure-numpy parts (benchmarks/ccx_locking.py): the
panel's mesh, the stress of its bend and the exact linear release, against
closed forms. No ccx needed."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import ccx_locking as lk  # noqa: E402
import ccx_release as cr  # noqa: E402


@pytest.mark.parametrize("h", [0.386, 0.156])
def test_panel_wedges_fill_the_curved_panel_with_faces_about_h_long(h):
    p = lk.panel(h)
    solid = cr.solid_mesh(
        p["x"], p["triangles"], p["normals"], p["mids"], p["mid_normals"], p["face_edge"],
        lk.THICKNESS, 2,
    )  # fmt: skip
    vol = cr.wedge_volumes(solid)
    assert vol.min() > 0.0  # counterclockwise about the top normal
    # a shell of thickness t about a cylinder: volume L W t exactly
    assert vol.sum() == pytest.approx(lk.LENGTH * lk.WIDTH * lk.THICKNESS, rel=1e-5)
    assert np.median(lk.longest_edges(p["x"], p["triangles"])) == pytest.approx(h, rel=0.1)
    r = np.hypot(p["x"][:, 0], p["x"][:, 2] - lk.RADIUS)
    np.testing.assert_allclose(r, lk.RADIUS, rtol=1e-12)


def test_bend_stress_follows_the_tangent_at_each_point():
    """At a point of the panel the stress is E' eps along the cylinder's
    tangent there, nu E' eps along the rulings, and no traction on the
    surface (s . n = 0); with one frame a face it has one where the tangent
    turned."""
    p = lk.panel(0.386)
    heights = cr.point_heights(lk.THICKNESS, 1)
    s = lk.bend_stress(p["flat"], p["triangles"], heights, lk.RADIUS, "point")
    xi, eta = cr.GAUSS_WEDGE[:, 0], cr.GAUSS_WEDGE[:, 1]
    f = 5
    s_pt = p["flat"][p["triangles"][f], 0] @ np.column_stack([1 - xi - eta, xi, eta]).T
    a = s_pt / lk.RADIUS
    t = np.column_stack([np.cos(a), 0 * a, np.sin(a)])
    n = np.column_stack([-np.sin(a), 0 * a, np.cos(a)])
    full = np.zeros((9, 3, 3))
    for (i, j), c in {(0, 0): 0, (1, 1): 1, (2, 2): 2, (0, 1): 3, (0, 2): 4, (1, 2): 5}.items():
        full[:, i, j] = full[:, j, i] = s[f, :, c]
    eps = -heights[0] / lk.RADIUS
    ep = lk.YOUNGS / (1 - lk.POISSON**2)
    np.testing.assert_allclose(np.einsum("ki,kij,kj->k", t, full, t), ep * eps, rtol=1e-12)
    np.testing.assert_allclose(full[:, 1, 1], lk.POISSON * ep * eps, rtol=1e-12)
    np.testing.assert_allclose(
        np.einsum("kij,kj->ki", full, n), 0.0, atol=1e-9 * ep * abs(eps).max()
    )
    face = lk.bend_stress(p["flat"], p["triangles"], heights, lk.RADIUS, "face")
    assert np.abs(face - s).max() > 1e-3 * np.abs(s).max()


def test_linear_unbend_has_no_membrane_strain_and_turns_the_tangent_back():
    """u' = -(s / R) n: t . u' = 0 (inextensional), and d(u')/ds . n =
    -1 / R, the curvature taken back; for a slight bend it is the
    unrolling's first order."""
    r = 3.0
    s = np.linspace(-1.0, 1.0, 2001)
    flat = np.column_stack([s, np.zeros_like(s)])
    u = lk.linear_unbend(flat, r, steps=2000)
    du = np.gradient(u, s, axis=0)
    t = np.column_stack([np.cos(s / r), 0 * s, np.sin(s / r)])
    n = np.column_stack([-np.sin(s / r), 0 * s, np.cos(s / r)])
    inner = slice(10, -10)  # np.gradient is first order at the ends
    assert np.abs(np.einsum("ki,ki->k", t, du)[inner]).max() < 1e-6
    ddu = np.gradient(du, s, axis=0)
    np.testing.assert_allclose(np.einsum("ki,ki->k", n, ddu)[inner], -1 / r, rtol=2e-3)
    x, _ = lk.on_cylinder(flat, 1e3)
    u_slight = lk.linear_unbend(flat, 1e3)
    unrolled = np.column_stack([s, 0 * s, 0 * s]) - x
    np.testing.assert_allclose(u_slight, unrolled, atol=1e-6)


def test_rigid_deviation_sees_through_a_rigid_motion_only():
    rng = np.random.default_rng(1)
    a = rng.normal(size=(50, 3))
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.linalg.det(q))
    moved = a @ q.T + [1.0, -2.0, 0.5]
    assert lk.rigid_deviation(moved, a)[0] < 1e-12
    bumped = a.copy()
    bumped[7, 2] += 1.0  # one node off by 1: after the fit the rest move a little
    dmax, drms = lk.rigid_deviation(bumped, a)
    assert 0.8 < dmax <= 1.0 and drms == pytest.approx(dmax / math.sqrt(50), rel=0.2)


def test_split4_fills_each_face_with_four_of_a_quarter_its_area_each():
    p = lk.panel(0.386)
    flat, tri = p["flat"], p["triangles"]
    pts, kids, parent = lk.split4(flat, tri)

    def areas(xy, t):
        d = xy[t]
        return 0.5 * (
            (d[:, 1, 0] - d[:, 0, 0]) * (d[:, 2, 1] - d[:, 0, 1])
            - (d[:, 1, 1] - d[:, 0, 1]) * (d[:, 2, 0] - d[:, 0, 0])
        )

    np.testing.assert_allclose(areas(pts, kids), np.repeat(areas(flat, tri), 4) / 4, rtol=1e-12)
    np.testing.assert_array_equal(parent, np.repeat(np.arange(len(tri)), 4))
    centroid = pts[kids].mean(axis=1).reshape(-1, 4, 2).mean(axis=1)
    np.testing.assert_allclose(centroid, flat[tri].mean(axis=1), atol=1e-12)
    # shared midpoints: n + E new nodes, no duplicates
    assert len(pts) == len(flat) + len(p["edges"])
    twice = lk.panel(0.386, splits=2)
    assert len(twice["triangles"]) == 16 * len(tri)
    np.testing.assert_array_equal(twice["parent"], np.repeat(np.arange(len(tri)), 16))
