"""Distances from the designed surface and the rigid best fit, checked on
points whose distance is known by construction (on the surface, and moved
along its normal), and on rigid motions of known size."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.path import Path

from onefold_cad.design import fold_design
from onefold_cad.mechanics.deviation import best_fit, surface_distance
from onefold_cad.templates import load_template
from tests.counting import count_calls


@pytest.fixture(scope="module")
def patkau():
    design = load_template("patkau-one-fold")
    return design, fold_design(design)


def _inside(design, n: int, seed: int, margin: float) -> np.ndarray:
    """Flat points inside the sheet, at least ``margin`` from H."""
    v = design.sheet.vertices
    rng = np.random.default_rng(seed)
    xy = rng.uniform(v.min(0), v.max(0), size=(n, 2))
    xy = xy[Path(v).contains_points(xy)]
    return xy[np.hypot(*xy.T) > margin]


def test_points_on_the_designed_surface_are_at_distance_zero(patkau):
    design, folded = patkau
    xy = _inside(design, 3000, 1, 20.0)
    d = surface_distance(folded, folded.map_points(xy), 9.57)
    assert np.max(d) <= 1e-9 * design.sheet.size


def test_points_moved_along_the_normal_are_that_far(patkau):
    """Away from the crease (where the other side can be nearer) a point moved
    by s along the surface normal is |s| from the surface."""
    design, folded = patkau
    xy = _inside(design, 3000, 2, 20.0)
    xy = xy[np.abs(xy[:, 1]) > 300.0]
    s = np.random.default_rng(3).uniform(-80.0, 80.0, len(xy))
    p = folded.map_points(xy) + s[:, None] * folded.normals(xy)
    assert np.allclose(surface_distance(folded, p, 9.57), np.abs(s), rtol=0, atol=1e-9 * 7315)


def test_a_point_beyond_the_edge_is_measured_to_the_edge(patkau):
    design, folded = patkau
    corner = design.sheet.vertices[0]
    out = folded.map_points([corner * 1.0])[0]
    ruling = out - folded.apex
    beyond = out + 100.0 * ruling / np.linalg.norm(ruling)  # 100 further along the ruling
    assert surface_distance(folded, [beyond], 9.57)[0] == pytest.approx(100.0, rel=1e-9)


def test_best_fit_undoes_a_rigid_motion():
    rng = np.random.default_rng(4)
    p = rng.normal(size=(200, 3)) * [3.0, 2.0, 1.0]
    q_rot = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    q_rot *= np.sign(np.linalg.det(q_rot))
    moved = p @ q_rot.T + [5.0, -2.0, 1.0]
    fit = best_fit(moved, p)
    assert fit.rms < 1e-12
    assert np.allclose(fit.apply(moved), p, atol=1e-12)
    assert np.linalg.det(fit.rotation) == pytest.approx(1.0)


def test_best_fit_of_noisy_points_leaves_their_noise():
    """Noise orthogonal to every rigid motion's effect stays: the rms equals it."""
    rng = np.random.default_rng(5)
    p = rng.normal(size=(4000, 3))
    noise = rng.normal(scale=1e-3, size=p.shape)
    fit = best_fit(p + noise, p)
    assert fit.rms == pytest.approx(np.sqrt(np.mean(np.sum(noise**2, axis=1))), rel=0.01)


def test_the_sampled_rulings_are_each_folds_own_and_made_once(patkau, monkeypatch):
    """The rulings sampled for the closest-ruling search are kept with their
    fold: a second measure of the same fold inverts no flat angle (no call of
    ``frames``), and another design's fold (broken-vault, alternated with
    patkau) gets its own: the points on each surface are on it, not on the
    other."""
    design, folded = patkau
    other_design = load_template("broken-vault")
    other = fold_design(other_design)
    xy, xy_other = _inside(design, 400, 6, 20.0), _inside(other_design, 400, 7, 2.0)
    on, on_other = folded.map_points(xy), other.map_points(xy_other)
    for fold, points, d in ((folded, on, design), (other, on_other, other_design)) * 2:
        assert np.max(surface_distance(fold, points, 0.0)) <= 1e-9 * d.sheet.size
    assert np.min(surface_distance(other, on, 0.0)) > 1.0  # patkau's points are off it
    calls = count_calls(monkeypatch, type(folded.solution.surface), "frames")
    surface_distance(folded, on, 9.57)
    assert calls == [], "the flat angles of the sampled rulings or of the search again"
