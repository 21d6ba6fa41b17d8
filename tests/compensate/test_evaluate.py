"""Measuring a standing form against a target (onefold_cad.compensate.evaluate),
on forms whose distance from the target is known by construction."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.path import Path
from scipy.spatial import Delaunay

from onefold_cad.compensate.evaluate import (
    Standing,
    _interpolate,
    _planar_fit,
    crease_springback,
    node_weights,
    standing_measures,
    target_form,
)
from onefold_cad.templates import find_template, load_template
from tests.compensate.fake_steel import flat_mesh


def _standing(flat: np.ndarray, faces: np.ndarray, x: np.ndarray) -> Standing:
    return Standing(True, "", flat, faces, x, 1.0, 1.0, 1.0, 5.0, None, None, 0.0, ())


def _turn(phi: float) -> np.ndarray:
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_node_weights_are_area_shares() -> None:
    # a unit square in two triangles: the corners on both get 1/3 of 1/2 each
    flat = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    faces = np.array([[0, 1, 2], [0, 2, 3]])
    assert node_weights(flat, faces) == pytest.approx([1 / 3, 1 / 6, 1 / 3, 1 / 6])


def test_interpolation_is_exact_for_a_linear_field() -> None:
    rng = np.random.default_rng(1)
    p = np.concatenate([rng.random((40, 2)), [[0, 0], [1, 0], [1, 1], [0, 1]]])
    faces = Delaunay(p).simplices
    field = np.column_stack([2 * p[:, 0] - 3 * p[:, 1] + 1, p[:, 0], p[:, 1]])
    q = rng.random((200, 2)) * 0.6 + 0.2
    got = _interpolate(p, faces, field, q)
    assert got[:, 0] == pytest.approx(2 * q[:, 0] - 3 * q[:, 1] + 1, abs=1e-12)


def test_planar_fit_undoes_a_turn_and_shift() -> None:
    rng = np.random.default_rng(2)
    y = rng.random((30, 3))
    x = (y - [0.3, -0.2, 0.0]) @ _turn(0.4)  # y turned by -0.4 about z, shifted
    rot, shift = _planar_fit(x, y, np.full(30, 1 / 30))
    assert x @ rot.T + shift == pytest.approx(y, abs=1e-12)


def test_the_target_turned_and_shifted_on_the_ground_deviates_nothing() -> None:
    design = load_template(find_template("broken-vault"))
    flat, faces = flat_mesh(design)
    x = target_form(design, flat) @ _turn(0.3).T + [5.0, -7.0, 0.0]
    m = standing_measures(design, flat, node_weights(flat, faces), _standing(flat, faces, x))
    assert m.max_deviation < 1e-6 * design.sheet.size
    assert np.abs(m.residual).max() < 1e-6 * design.sheet.size


def test_a_lifted_form_deviates_by_at_most_the_lift() -> None:
    # lifted by 1 in, every node lies at most 1 in from the target's surface (away
    # from the sheet's edge, where the distance is an upper bound on the sampled
    # rulings), and the top of the vault (normal about vertical) nearly 1 in
    design = load_template(find_template("broken-vault"))
    flat, faces = flat_mesh(design)
    x = target_form(design, flat) + [0.0, 0.0, 1.0]
    m = standing_measures(design, flat, node_weights(flat, faces), _standing(flat, faces, x))
    inner = Path(0.8 * design.sheet.vertices).contains_points(flat)
    assert np.all(m.deviation[inner] <= 1.0 + 1e-9)
    assert m.deviation[inner].max() > 0.8


def test_the_designed_form_has_no_crease_springback() -> None:
    design = load_template(find_template("broken-vault"))
    flat, faces = flat_mesh(design)
    back = crease_springback(design, _standing(flat, faces, target_form(design, flat)))
    assert back == {"+x": pytest.approx(0.0, abs=1e-9), "-x": pytest.approx(0.0, abs=1e-9)}
