"""Toppling on samples: point sets whose resting faces are known by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.geometry.ground import holds
from onefold_cad.geometry.topple import com_depth, com_outside, roll


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    k = axis / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * (kx @ kx)


@pytest.mark.parametrize("angle", [0.3, 0.7, 1.1, 2.0])
def test_a_tilted_box_comes_to_rest_on_a_face(angle: float) -> None:
    # a 1 x 2 x 3 box turned about a skew axis: it rests on one of its six
    # faces (normal along one of its turned axes), on that face's 4 corners
    rot = _rotation(np.array([1.0, 2.0, 0.5]), angle)
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 2) for z in (0, 3)], dtype=float)
    pts = corners @ rot.T
    com = np.array([0.5, 1.0, 1.5]) @ rot.T
    g, on = roll(pts, com, np.array([0.0, 0.0, 1.0]), 1e-12)
    axes = rot.T  # rows: the box's axes in the turned frame
    assert np.max(np.abs(axes @ g)) == pytest.approx(1.0, abs=1e-12)
    assert len(on) == 4
    assert holds(pts[on], com, g, 1e-12)
    # the contacts are the lowest corners, level with each other
    h = pts @ g
    assert np.allclose(h[on], h.min(), atol=1e-12)


def test_a_form_balanced_above_an_edge_falls_to_one_side() -> None:
    # a triangular prism standing on its ridge: two lowest points in a line
    # below the centre of mass; it must fall on one of its two slanted faces
    pts = np.array(
        [[-1, 0, 0], [1, 0, 0], [-1, -1, 1], [1, -1, 1], [-1, 1, 1], [1, 1, 1]], dtype=float
    )
    com = pts.mean(axis=0)
    g, on = roll(pts, com, np.array([0.0, 0.0, 1.0]), 1e-12)
    assert len(on) == 4 and holds(pts[on], com, g, 1e-12)
    assert abs(abs(g[1]) - math.sqrt(0.5)) <= 1e-12 and g[2] == pytest.approx(math.sqrt(0.5))


def test_a_tetrahedron_rests_on_a_face_under_its_centre() -> None:
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    com = pts.mean(axis=0)
    tilt = _rotation(np.array([1.0, -1.0, 0.3]), 2.5)  # start it far off a face
    g, on = roll(pts @ tilt.T, com @ tilt.T, np.array([0.0, 0.0, 1.0]), 1e-12)
    assert len(on) == 3
    normals = np.array([[0, 0, 1], [0, 1, 0], [1, 0, 0], [-1, -1, -1] / np.sqrt(3)]) @ tilt.T
    assert np.max(normals @ g) == pytest.approx(1.0, abs=1e-12)


def test_lowest_points_find_the_lowest_point_of_a_many_vertex_sheet() -> None:
    # A 120-vertex star sheet with one long spike: its edge is sampled far
    # more coarsely than the others (samples go by length), so a band of the
    # body's largest spacing would take in every edge; each piece is refined
    # within its own spacing instead. Expected, independently: the folded
    # boundary's lowest point along g from 801 samples per edge and scipy's
    # bounded Brent at each edge's sampled minimum.
    from scipy.optimize import minimize_scalar

    from onefold_cad import FrameCurve, Sheet, fold, solve
    from onefold_cad.geometry.body import FoldedBody
    from onefold_cad.geometry.ground import Samples, lowest_points, sample_spacing

    rng = np.random.default_rng(7)
    n = 120
    angles = np.sort(rng.uniform(0.0, 2.0 * math.pi, n))
    radii = rng.uniform(50.0, 120.0, n)
    radii[n // 3] = 2000.0  # the spike
    poly = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])
    folded = fold(solve(FrameCurve(40.0, 60.0, 5.0, 100.0, 90), "exact"), Sheet.polygon(poly))
    body = FoldedBody(folded)
    samples = Samples(*body.samples)
    size = body.size
    band = 2.0 * sample_spacing(body) + 1e-10 * size
    v = folded.sheet.vertices
    for g in rng.normal(size=(4, 3)):
        g /= np.linalg.norm(g)
        lows = lowest_points(body, samples, g, band)
        found = float(lows[0][2] @ g)
        want = 0.0  # the apex (the body's origin), a point of the shell without a hole
        for k in range(len(v)):
            a, b = v[k], v[(k + 1) % len(v)]

            def height(s, a=a, b=b, g=g):
                q = a + np.atleast_1d(s)[:, None] * (b - a)
                return (folded.map_points(q) - folded.apex) @ g

            s = np.linspace(0.0, 1.0, 801)
            z = height(s)
            i = int(np.argmin(z))
            res = minimize_scalar(
                lambda t, h=height: float(h(t)[0]),
                bounds=(s[max(i - 1, 0)], s[min(i + 1, 800)]),
                method="bounded",
                options={"xatol": 1e-14},
            )
            want = min(want, float(z[i]), float(res.fun))
        assert abs(found - want) <= 1e-9 * size


def test_a_needle_with_an_offset_centre_rolls_onto_its_heavy_side() -> None:
    # a cylinder 1 long and 2e-7 across (a folded needle's proportions), 1000
    # points round each end: the tolerance 1e-10 is a few point spacings
    # (6e-10) across its ends. Its centre of mass sits 0.9 of the radius off
    # the axis: it can only rest with that side down, the centre of mass
    # 0.1 r above the ground (less the sagitta of the sampled ends)
    r, n = 1e-7, 1000
    t = 2.0 * math.pi * np.arange(n) / n
    ring = np.column_stack([np.zeros(n), r * np.cos(t), r * np.sin(t)])
    pts = np.vstack([ring, ring + [1.0, 0.0, 0.0]])
    com = np.array([0.5, 0.9 * r * math.cos(2.0), 0.9 * r * math.sin(2.0)])
    tilt = _rotation(np.array([0.2, 1.0, 0.4]), 1.3)
    pts, com = pts @ tilt.T, com @ tilt.T
    g, on = roll(pts, com, np.array([0.0, 0.0, 1.0]), 1e-10)
    height = float(com @ g - np.min(pts @ g))
    sagitta = r * (1.0 - math.cos(math.pi / n))
    assert 0.1 * r - sagitta - 1e-10 <= height <= 0.1 * r + 1e-10
    assert holds(pts[on], com, g, 1e-10)


def test_a_centre_of_mass_outside_the_points_stops_the_topple() -> None:
    # a flat square with its centre of mass 1 below it: no rest can hold it;
    # the topple ends (it does not roll on) and com_depth says it lies outside
    pts = np.array([[x, y, 0.0] for x in np.linspace(0, 1, 9) for y in np.linspace(0, 1, 9)])
    com = np.array([0.3, 0.6, -1.0])
    assert com_outside(pts, com) >= 1.0 - 1e-12
    g, _ = roll(pts, com, np.array([0.3, 0.1, 1.0]) / math.hypot(0.3, 0.1, 1.0), 1e-12)
    assert com_depth(pts, com, g) > 1e-12
