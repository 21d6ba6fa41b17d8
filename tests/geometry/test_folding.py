"""Developability and crease invariants of the fold, over random admissible designs."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings

from onefold_cad import FrameCurve, Sheet, fold, solve

from .conftest import frames, sheets

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    c = np.linalg.norm(np.cross(a, b), axis=-1)
    return np.arctan2(c, (a * b).sum(-1))


@SETTINGS
@given(frame=frames(), sheet=sheets)
def test_paper_model_is_developable(frame: FrameCurve, sheet: Sheet) -> None:
    folded = fold(solve(frame, "paper"), sheet)
    scale = sheet.size
    flat, r3 = folded.rulings_flat, folded.rulings_3d
    # every ruling keeps its flat length
    l_flat = np.linalg.norm(flat[:, 1] - flat[:, 0], axis=1)
    l_3d = np.linalg.norm(r3[:, 1] - r3[:, 0], axis=1)
    assert np.all(np.abs(l_3d - l_flat) <= 1e-9 * scale)
    # every boundary segment keeps its flat length (the boundary is straight between ruling ends)
    b2, b3 = folded.boundary_flat, folded.boundary_3d
    s2 = np.linalg.norm(np.roll(b2, -1, axis=0) - b2, axis=1)
    s3 = np.linalg.norm(np.roll(b3, -1, axis=0) - b3, axis=1)
    assert np.all(np.abs(s3 - s2) <= 1e-9 * scale)
    # every angle at the apex between neighbouring rulings keeps its flat value
    m = len(folded.ruling_angles[0])
    for side in (slice(0, m), slice(m, None)):
        d3 = r3[side, 1] - r3[side, 0]
        d2 = np.column_stack([flat[side, 1], np.zeros(len(d3))])
        assert np.allclose(_angle(d3[:-1], d3[1:]), _angle(d2[:-1], d2[1:]), atol=1e-9)
    # area: the fan of planar triangles (A, b_i, b_i+1) has the flat area
    assert abs(folded.metrics.area_3d - sheet.area) <= 1e-9 * sheet.area
    assert abs(folded.metrics.angle_sum_deg - 360.0) <= 1e-9


@SETTINGS
@given(frame=frames(divisions=1), sheet=sheets)
def test_exact_model_is_developable(frame: FrameCurve, sheet: Sheet) -> None:
    sol = solve(frame, "exact")
    folded = fold(sol, sheet, boundary_samples=4000)
    m = folded.metrics
    # chords of the folded boundary: their length and fan area tend to the flat values
    # as O(step^2): small at 4000 samples, and much smaller (ideally 16x) at 4x the samples
    fine = fold(sol, sheet, boundary_samples=16000).metrics
    for coarse_err, fine_err in (
        (m.boundary_length_rel_error, fine.boundary_length_rel_error),
        (m.area_rel_error, fine.area_rel_error),
    ):
        assert coarse_err < 1e-4
        assert fine_err < max(coarse_err / 4, 1e-12)
    assert m.boundary_length_3d <= m.boundary_length_flat * (1 + 1e-12)
    # every flat distance from H survives: boundary points stay at their flat distance from A
    r2 = np.hypot(*folded.boundary_flat.T)
    r3 = np.linalg.norm(folded.boundary_3d - folded.apex, axis=1)
    assert np.allclose(r3, r2, rtol=1e-12, atol=1e-12 * sheet.size)
    # the inverse map recovers the flat sheet
    back, off = folded.unfold(folded.boundary_3d[::7])
    assert np.allclose(back, folded.boundary_flat[::7], atol=1e-9 * sheet.size)
    assert np.all(off <= 1e-9 * sheet.size)


@SETTINGS
@given(frame=frames(), sheet=sheets)
def test_crease_fold_angle_is_the_same_from_both_sides(frame: FrameCurve, sheet: Sheet) -> None:
    for model in ("paper", "exact"):
        folded = fold(solve(frame, model), sheet)
        for half in folded.crease:
            sign = 1.0 if half.name == "plus_x" else -1.0
            xs = sign * half.length * np.array([0.2, 0.5, 0.9])
            eps = 1e-10 * np.abs(xs)  # flat angle 1e-10 rad off the crease
            up = folded.normals(np.column_stack([xs, eps]))
            down = folded.normals(np.column_stack([xs, -eps]))
            a_ud = np.degrees(_angle(up, down))
            a_du = np.degrees(_angle(down, up))
            assert np.allclose(a_ud, half.fold_angle_deg, atol=1e-4)
            assert np.allclose(a_du, half.fold_angle_deg, atol=1e-4)
            assert 0.0 < half.fold_angle_deg < 180.0
            # the crease end lies on the folded surface at the crease's flat length
            end = folded.map_points(half.end_flat[None, :])[0]
            assert np.allclose(end, half.end_3d, atol=1e-9 * sheet.size)
            assert abs(np.linalg.norm(end - folded.apex) - half.length) <= 1e-9 * sheet.size


def test_fold_angle_matches_finite_difference_dihedral() -> None:
    frame = FrameCurve(32, 34, 68, 100, 90)
    folded = fold(solve(frame, "exact"), Sheet.quadrilateral(103, 201, 300, 96))
    for half in folded.crease:
        x = 0.5 * half.end_flat[0]
        d = 1e-4 * abs(x)
        # two tangent vectors on each side, from points of the folded surface only
        a = folded.map_points([[x, 0.0], [x + d, 0.0], [x, d], [x, -d]])
        n_up = np.cross(a[1] - a[0], a[2] - a[0])
        n_dn = np.cross(a[3] - a[0], a[1] - a[0])
        angle = math.degrees(_angle(n_up, n_dn))
        assert abs(angle - half.fold_angle_deg) < 0.01


def test_bend_direction_flips_with_the_sheet_side() -> None:
    # A simple V: if the two sides rise towards +z the bend is UP (valley seen from the top).
    folded = fold(solve(FrameCurve(50, 45, 0, 100, 90), "exact"), Sheet.quadrilateral(1, 1, 1, 1))
    for half in folded.crease:
        x = half.end_flat / 2
        pts = folded.map_points([x, x + [0.0, 1e-3], x - [0.0, 1e-3]])
        n = folded.normals([x + [0.0, 1e-9]])[0]
        n_other = n * [1.0, -1.0, 1.0]
        rises = np.dot(pts[1] - pts[0], n_other) > 0
        assert (half.bend == "UP") == bool(rises)


@SETTINGS
@given(frame=frames(divisions=1), sheet=sheets)
def test_resting_placement_stands_on_the_ground(frame: FrameCurve, sheet: Sheet) -> None:
    folded = fold(solve(frame, "exact"), sheet, boundary_samples=400)
    rest = folded.resting
    pts = rest.apply(np.vstack([folded.boundary_3d, folded.apex]))
    size = sheet.size
    assert pts[:, 2].min() >= -1e-7 * size
    assert np.all(np.abs(pts[rest.touching, 2]) <= 1e-6 * size)
    assert len(rest.touching) >= 3
    assert np.allclose(rest.rotation @ rest.rotation.T, np.eye(3), atol=1e-12)
    assert abs(np.linalg.det(rest.rotation) - 1.0) < 1e-12


def test_mesh_is_on_the_surface() -> None:
    folded = fold(solve(FrameCurve(50, 45, 0, 100, 90), "exact"), Sheet.rectangle(10, 24, 0.4))
    verts, faces = folded.mesh(angular=30, radial=5)
    assert faces.max() < len(verts)
    _, off = folded.unfold(verts[1:])
    assert off.max() < 1e-9 * folded.sheet.size


@SETTINGS
@given(frame=frames(), sheet=sheets)
def test_fold_results_agree_with_the_fold_map(frame: FrameCurve, sheet: Sheet) -> None:
    # fold() builds rulings, crease ends and (paper model) the boundary in bulk;
    # the general map of flat points gives the same points
    for model in ("paper", "exact"):
        folded = fold(solve(frame, model), sheet)
        ends2, ends3 = folded.rulings_flat[:, 1], folded.rulings_3d[:, 1]
        scale = sheet.size
        np.testing.assert_allclose(folded.map_points(ends2), ends3, rtol=0, atol=1e-9 * scale)
        assert np.array_equal(folded.rulings_3d[:, 0], np.tile(folded.apex, (len(ends3), 1)))
        up, lo = folded.ruling_angles
        assert np.all(np.diff(up) > 1e-12) and np.all(np.diff(lo) > 1e-12)
        assert up[0] == lo[0] == 0.0 and up[-1] == lo[-1] == math.pi
        # every vertex has a ruling through it
        for v in sheet.vertices:
            assert np.min(np.linalg.norm(ends2 - v, axis=1)) <= 1e-9 * scale
        if model == "paper":
            # the boundary is the ruling ends, counter-clockwise, each once
            b2, b3 = folded.boundary_flat, folded.boundary_3d
            assert len(b2) == len(ends2) - 2
            np.testing.assert_allclose(folded.map_points(b2), b3, rtol=0, atol=1e-9 * scale)
            area = 0.5 * np.sum(b2[:, 0] * np.roll(b2[:, 1], -1) - b2[:, 1] * np.roll(b2[:, 0], -1))
            assert abs(area - sheet.area) <= 1e-9 * sheet.area
