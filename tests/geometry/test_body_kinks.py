"""The kinks of the thick sheet's sections against the geometry they come
from: where the cut of the fold's plane of symmetry, y = r u_y + s n_y = 0,
passes a corner of the slab (r = rho or r_out, s = s0 or s1), with theta
from the cone's own inversion (not the node table's) and the ray lengths
from the sheet."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from onefold_cad import Material, fold, solve
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.body_kinks import arc_section, flat_section, section_kinks
from onefold_cad.templates import load_template


@pytest.mark.parametrize("name", ["patkau-one-fold", "broken-vault"])
def test_kinks_are_where_the_cut_passes_a_corner_of_the_slab(name: str) -> None:
    design = load_template(name)
    folded = fold(solve(design.frame, design.model), design.sheet)
    material = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    body = FoldedBody(folded, material, "solid")
    cone, arc = folded.solution.surface, ArcFrames(folded.solution.frame, folded.apex)
    (s0, s1), rho = body.s_range, body.hole

    def corners(phi: np.ndarray, lower: bool) -> np.ndarray:
        theta = cone.theta_of_phi(phi)
        u, _, n = arc.frames(phi)
        r_out = folded.sheet.ray_lengths(-theta if lower else theta)
        return np.stack([r * u[:, 1] + s * n[:, 1] for r in (rho, r_out) for s in (s0, s1)])

    ends = [body.vertex_phis[0][[0, -1]], body.vertex_phis[1][[0, -1]]]
    kinks = section_kinks(body, arc_section(body), [np.linspace(*e, 65) for e in ends])
    for lower, (found, (p0, p1)) in enumerate(zip(kinks, ends, strict=True)):
        assert len(found) >= 2  # the cut meets the slab near both crease ends
        values = corners(found, bool(lower))
        # each a zero of one of them (the functions' scale: the sheet's size)
        assert np.all(np.min(np.abs(values), axis=0) <= 1e-9 * body.size)
        # and every sign change on a fine grid (graded to the ends) is one
        _every_sign_change_found(found, lambda t, lo=bool(lower): corners(t, lo), p0, p1, 0.0)


def test_the_paper_model_s_kinks_are_in_the_flat_angle() -> None:
    """table1-row1's paper fan as a sheet 1 % of its size thick, no hole:
    the same corners, the wedges' frames at theta."""
    design = load_template("table1-row1")
    folded = fold(solve(design.frame, design.model), design.sheet)
    thick = Material(thickness=0.01 * folded.sheet.size, relief_hole=0.0)
    body = FoldedBody(folded, thick, "shell")
    fan = folded.solution.surface
    (s0, s1), rho = body.s_range, body.hole
    assert s1 > s0

    def corners(theta: np.ndarray, lower: bool) -> np.ndarray:
        u, e = fan.frames(theta)
        n = np.cross(u, e)
        r_out = folded.sheet.ray_lengths(-theta if lower else theta)
        return np.stack([r * u[:, 1] + s * n[:, 1] for r in (rho, r_out) for s in (s0, s1)])

    ends = [np.array([0.0, fan.total_angle])] * 2
    kinks = section_kinks(body, flat_section(body), [np.linspace(*e, 65) for e in ends])
    rays = np.asarray(fan.thetas)
    for lower, found in enumerate(kinks):
        assert len(found) >= 2
        # each a zero of one of them, or a sign change across a division ray
        # (where the wedges' normal jumps), within the refined step of it
        zero = np.min(np.abs(corners(found, bool(lower))), axis=0) <= 1e-9 * body.size
        at_ray = np.min(np.abs(found[:, None] - rays[None, :]), axis=1) <= np.pi / 64 / 16
        assert np.all(zero | at_ray) and zero.sum() >= 2
        # a jump is found within the refined step of its bracket
        _every_sign_change_found(
            found, lambda t, lo=bool(lower): corners(t, lo), 0.0, fan.total_angle, np.pi / 1024
        )


def _every_sign_change_found(
    found: np.ndarray,
    corners: Callable[[np.ndarray], np.ndarray],
    p0: float,
    p1: float,
    slack: float,
) -> None:
    """Every sign change of ``corners`` on a fine grid of [p0, p1] (4001
    points, graded towards both ends) lies within its grid step, or
    ``slack``, of one of the ``found`` kinks."""
    g = 0.5 ** np.arange(1, 40)
    grid = np.unique(np.concatenate([np.linspace(p0, p1, 4001), p0 + (p1 - p0) * g,
                                     p1 - (p1 - p0) * g]))  # fmt: skip
    for row in corners(grid):
        for i in np.nonzero(np.signbit(row[1:]) != np.signbit(row[:-1]))[0]:
            step = max(grid[i + 1] - grid[i], slack)
            assert np.min(np.abs(found - 0.5 * (grid[i] + grid[i + 1]))) <= step
