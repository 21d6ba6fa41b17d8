"""The rigid-body checks: sliding on friction, tipping about the support polygon."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.mechanics.loads.feet import feet_of, resultant, rigid_check, tipping_load

SQUARE = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])


def _body(weight, h_load, height, direction=0.0, com=(1.0, 1.0, 0.8)):
    """Resultant of a weight at ``com`` and a horizontal load at ``height``
    over the centre of mass, towards ``direction`` (deg)."""
    a = math.radians(direction)
    points = np.array([com, [com[0], com[1], height]])
    forces = np.array([[0.0, 0.0, -weight], [h_load * math.cos(a), h_load * math.sin(a), 0.0]])
    return resultant(points, forces)


@pytest.mark.parametrize("mu", [0.2, 0.5, 0.9])
def test_slides_exactly_past_mu_times_the_vertical_load(mu):
    w = 1000.0
    for factor, slides in ((1 - 1e-9, False), (1 + 1e-9, True)):
        f, m = _body(w, factor * mu * w, 0.1)
        assert rigid_check(SQUARE, f, m, mu).slides is slides


@pytest.mark.parametrize("direction", [0.0, 90.0, 180.0, 45.0])
def test_tipping_load_is_the_weights_restoring_moment_over_the_lever_arm(direction):
    """Centre of mass over (1, 1) in a 2 m square: along an axis the edge is a
    = 1 m away, along the diagonal sqrt(2) m (to the corner); H = W a / h."""
    w, h = 1000.0, 2.5
    a = math.sqrt(2.0) if direction == 45.0 else 1.0
    expected = w * a / h
    assert math.isclose(tipping_load(SQUARE, np.array([1.0, 1.0]), w, h, direction), expected,
                        rel_tol=1e-12)  # fmt: skip
    for factor, tips in ((1 - 1e-6, False), (1 + 1e-6, True)):
        f, m = _body(w, factor * expected, h, direction)
        assert rigid_check(SQUARE, f, m, 10.0).tips is tips


def test_lifted_off_when_the_net_load_pulls_up():
    f, m = _body(-10.0, 0.0, 1.0)
    check = rigid_check(SQUARE, f, m, 0.5)
    assert check.lifts_off and check.tips and check.slides


def test_feet_are_contacts_joined_by_edges():
    edges = np.array([[0, 1], [1, 2], [3, 4], [5, 6]])
    feet = feet_of(np.array([0, 1, 2, 4, 5, 7]), edges)
    assert [f.tolist() for f in feet] == [[0, 1, 2], [4], [5], [7]]
