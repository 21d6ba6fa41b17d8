"""A sheet's placement on the site: the resting placement, then a turn about
the vertical and a move on the ground."""

from __future__ import annotations

import math

import numpy as np

from onefold_cad.design import fold_design, rest_once
from onefold_cad.site.placement import SitePlacement
from onefold_cad.templates import load_template


def test_a_turn_of_90_deg_takes_x_to_y_and_the_move_adds_on():
    s = SitePlacement(10.0, -5.0, 90.0)
    got = s.apply([[1.0, 0.0, 2.0], [0.0, 1.0, 0.0]])
    assert np.allclose(got, [[10.0, -4.0, 2.0], [9.0, -5.0, 0.0]], atol=1e-12)
    assert np.allclose(s.apply([[1.0, 0.0]]), [[10.0, -4.0]], atol=1e-12)


def test_the_turn_keeps_lengths_heights_and_turns_counter_clockwise():
    s = SitePlacement(0.0, 0.0, 30.0)
    p = np.array([[3.0, 4.0, 7.0]])
    q = s.apply(p)[0]
    assert math.isclose(np.hypot(*q[:2]), 5.0) and q[2] == 7.0
    turn = math.degrees(math.atan2(q[1], q[0]) - math.atan2(4.0, 3.0))
    assert math.isclose(turn, 30.0)


def test_compose_is_the_resting_placement_then_the_site_motion():
    d = load_template("paper-square")
    folded = fold_design(d)
    rest = rest_once(folded)
    s = SitePlacement(120.0, 45.0, -37.0)
    pts = folded.boundary_3d
    m = s.compose(rest)
    got = pts @ m[:3, :3].T + m[:3, 3]
    assert np.allclose(got, s.apply(rest.apply(pts)), atol=1e-9 * d.sheet.size)
    assert np.allclose(m[3], [0.0, 0.0, 0.0, 1.0])
