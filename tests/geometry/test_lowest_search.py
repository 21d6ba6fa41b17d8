"""The fast lowest-point search against slow, independent ones:
the cone's angle from its node table, the batched zoom, the ends its samples
certify, the pruned search over a body, and the numpy QuickHull."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad import FrameCurve, Material, Sheet, fold, solve
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.arc import arc_range
from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.ground import Samples
from onefold_cad.geometry.hull import convex_hull_2d
from onefold_cad.geometry.lows import exact_lows
from onefold_cad.geometry.pieces import end_minimum, zoom_min
from onefold_cad.geometry.placement import rest_form
from onefold_cad.geometry.zoom import zoom_many
from onefold_cad.templates import load_template

FRAMES = [
    (30.0, 30.0),
    (10.0, 89.9),
    (85.0, 85.0),
    (5.0, 5.0),
    (60.0, 89.999),
    (30.0, 90.0 - 1e-9),
]


@pytest.mark.parametrize(("alpha", "beta"), FRAMES)
def test_theta_near_is_theta_of_phi_and_phi_near_its_first_guess(alpha, beta) -> None:
    frame = FrameCurve(alpha, beta, 0.0, 100.0)
    cone = solve(frame, "exact").surface
    phi = np.linspace(*arc_range(frame), 20001)
    # the same angle to a few units in the last place, however fine the rule
    assert np.max(np.abs(cone.theta_near(phi) - cone.theta_of_phi(phi))) <= 8 * np.spacing(4.0)
    theta = np.linspace(0.0, cone.total_angle, 20001)
    guess = cone.phi_near(theta)
    assert np.max(np.abs(guess - cone.phi_of_theta(theta))) <= 1e-7
    assert np.all(np.diff(guess) >= 0.0)


def test_zoom_many_finds_what_zoom_min_finds() -> None:
    fns = [
        lambda x: (x - 0.3137) ** 2 + 2.0,
        lambda x: np.abs(x - 0.7071),
        np.cos,
        lambda x: np.where(x < 0.5, np.inf, x),
    ]
    lo, hi = np.array([0.0, 0.0, 0.0, 0.0]), np.array([1.0, 1.0, 2.0, 1.0])

    def f(jobs, t):
        v = np.empty(len(t))
        for j in range(len(fns)):
            v[jobs == j] = fns[j](t[jobs == j])
        return v, np.column_stack([t, v, v])

    t, v, p, done = zoom_many(f, lo, hi)
    for j, fn in enumerate(fns):
        tj, vj = zoom_min(fn, lo[j], hi[j])
        assert abs(v[j] - vj) <= 1e-12 and abs(t[j] - tj) <= 1e-7
        assert p[j, 0] == t[j] and done[j]


def test_an_end_is_certified_only_where_the_piece_rises_from_it() -> None:
    g = np.array([0.0, 0.0, 1.0])
    grid = np.array([0.0, 0.1, 0.12, 0.3])

    def corners(h):
        return np.column_stack([np.zeros(4), np.zeros(4), h])[:, None, :]

    # rising steeply from t = 0: the end, exactly
    t, p = end_minimum(grid, corners(grid + 0.5 * grid**2), 0.0, 0.1, g)
    assert t == 0.0 and p[2] == 0.0
    # rising from its neighbour but not from the end: a parabola dipping
    # between the first two samples (unevenly spaced), as on a long edge
    h = (grid - 0.04) ** 2 * 50.0
    assert h[1] > h[0] and end_minimum(grid, corners(h), 0.0, 0.1, g) is None
    # not at an end, or a corner that comes or goes: zoom
    assert end_minimum(grid, corners(grid), 0.1, 0.3, g) is None
    gone = np.concatenate([corners(grid), np.full((4, 1, 3), np.nan)], axis=1)
    gone[1, 1] = [0.0, 0.0, 1.0]
    assert end_minimum(grid, gone, 0.0, 0.1, g) is None


def _brute_lowest(body: FoldedBody, g: np.ndarray) -> float:
    """The body's lowest height along ``g``: every piece on a grid 8 times its
    own, zoom_min about each local minimum of that, and the fixed points."""
    best = float(np.min(body.fixed @ g)) if len(body.fixed) else math.inf
    for piece in body.pieces:
        t = np.interp(np.linspace(0, len(piece.grid) - 1, 8 * len(piece.grid)),
                      np.arange(len(piece.grid)), piece.grid)  # fmt: skip
        h = piece.heights(t, g)
        pad = np.concatenate([[np.inf], h, [np.inf]])
        for i in np.flatnonzero((pad[1:-1] <= pad[:-2]) & (pad[1:-1] <= pad[2:])):
            lo, hi = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
            best = min(best, zoom_min(lambda x, p=piece: p.heights(x, g), lo, hi)[1], h[i])
    return best


@pytest.mark.parametrize(
    "body",
    ["solid", "shell", "shell-without-hole"],
)
def test_exact_lows_finds_the_lowest_point_a_brute_force_finds(body) -> None:
    design = load_template("patkau-one-fold")
    frame = design.frame.with_changes(alpha=50.0, beta=70.0, h_c=20.0)
    folded = fold(solve(frame, "exact"), Sheet.rectangle(3000.0, 5000.0, 0.4))
    material = None if body == "shell-without-hole" else Material(thickness=5.0, relief_hole=30.0)
    form = FoldedBody(folded, material, body.split("-")[0])
    samples = Samples(*form.samples)
    rng = np.random.default_rng(11)
    dirs = rng.normal(size=(6, 3))
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    lows = exact_lows(form, samples, dirs)
    for g, found in zip(dirs, lows, strict=True):
        assert abs(float(found[0][2] @ g) - _brute_lowest(form, g)) <= 1e-12 * form.size


def test_quickhull_has_the_chain_s_corners_on_thousands_of_points() -> None:
    rng = np.random.default_rng(5)
    t = rng.uniform(0.0, 2.0 * math.pi, 3000)
    sets = [
        rng.normal(size=(5000, 2)),
        np.column_stack([np.cos(t), 0.2 * np.sin(t)]) * rng.uniform(0.99, 1.0, (3000, 1)),
        np.repeat(rng.normal(size=(400, 2)), 3, axis=0) + rng.normal(size=(1200, 2)) * 1e-13,
    ]
    for p in sets:
        hull = convex_hull_2d(p)
        assert len(hull) >= 3
        # counter-clockwise from the lowest x (then y), every point inside
        assert hull[0] == np.lexsort((p[:, 1], p[:, 0]))[0] or np.array_equal(
            p[hull[0]], p[np.lexsort((p[:, 1], p[:, 0]))[0]]
        )
        q = p[hull]
        e = np.roll(q, -1, axis=0) - q
        assert np.all(
            e[:, 0] * np.roll(e, -1, axis=0)[:, 1] - e[:, 1] * np.roll(e, -1, axis=0)[:, 0] > 0
        )
        cross = e[None, :, 0] * (p[:, None, 1] - q[None, :, 1]) - e[None, :, 1] * (
            p[:, None, 0] - q[None, :, 0]
        )
        assert np.all(cross >= -1e-12)


def test_a_tolerant_hull_keeps_the_corners_of_an_edge_of_near_duplicates() -> None:
    # three points at each end of a thin rectangle, a rounding error apart in
    # x: the chain, deciding its first turns within the tolerance, dropped the
    # corner (x0, -1) for the middle point (x0, 0); the hull keeps all four
    x0, x1 = -582.5445397198808, 0.0
    pts = np.array(
        [[x0 + 2e-13, 0.0], [x0, -1.98], [x0 + 1e-13, 1.98], [x1, -2.0], [x1, 0.0], [x1, 2.0]]
    )
    pts = np.vstack([pts, pts + 1e-14])
    hull = convex_hull_2d(pts, 1e-6)
    got = sorted(map(tuple, np.round(pts[hull], 6)))
    assert got == sorted([(round(x0, 6), -1.98), (round(x0, 6), 1.98), (0.0, -2.0), (0.0, 2.0)])


def test_a_form_standing_on_its_mitre_blocks_keeps_its_four_support_corners() -> None:
    # the default sheet at alpha 85, beta 89 stands as solved on the mitre
    # blocks at its apex: a support rectangle 0.36 x 3.1 mm; the placement of
    # main lost one of its corners to the chain's tolerance (above)
    design = load_template("patkau-one-fold")
    design = design.with_changes(frame=design.frame.with_changes(alpha=85.0, beta=89.0))
    folded = fold(solve(design.frame, "exact"), design.sheet)
    material = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    rest = rest_form(folded, material, "solid")
    poly = rest.support_polygon
    assert len(poly) == 4 and rest.stable
    span = poly.max(axis=0) - poly.min(axis=0)
    # a rectangle: its corners at its bounding box's corners
    for c in poly:
        assert np.all(
            np.minimum(np.abs(c - poly.min(axis=0)), np.abs(c - poly.max(axis=0)))
            <= 1e-9 * span.max()
        )
