"""benchmarks/ccx_split.py: the membrane and the bending part of a layered
shell's stresses, fitted over its elastic levels. Expected values by hand."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import ccx_split as cs  # noqa: E402

T = 3.57e-3  # m
SY = 215e6  # Pa


def test_level_heights_are_two_gauss_points_in_each_equal_layer():
    """One layer: +-t / (2 sqrt 3); four: symmetric, each pair centred on its
    layer's middle, t/4 apart from the next pair."""
    one = cs.level_heights(2.0, 1)
    assert one == pytest.approx([-1 / math.sqrt(3), 1 / math.sqrt(3)], rel=1e-15)
    z = cs.level_heights(T, 4)
    assert z == pytest.approx(-z[::-1], abs=1e-18)
    centres = z.reshape(4, 2).mean(axis=1)
    assert centres == pytest.approx([-3 * T / 8, -T / 8, T / 8, 3 * T / 8], rel=1e-12)


def test_split_recovers_membrane_and_slope_from_the_elastic_levels_alone():
    """sigma = a + z b at the elastic levels; the plastic levels (peeq > 0)
    carry another stress, which the fit must ignore."""
    rng = np.random.default_rng(3)
    m, layers = 5, 4
    z = cs.level_heights(T, layers)
    a = rng.normal(0, 30e6, (m, 3, 6))
    b = rng.normal(0, 2e11, (m, 3, 6))
    sig = a[:, None] + z[None, :, None, None] * b[:, None]
    peeq = np.zeros((m, 2 * layers, 3))
    peeq[:, [0, 1, -2, -1]] = 0.01  # outer layers plastic
    sig[:, [0, 1, -2, -1]] = 1e9  # whatever they carry
    out = cs.split(sig, peeq, T)
    assert out.fitted.all()
    assert out.membrane == pytest.approx(a, rel=1e-9, abs=1e-3)
    assert out.slope == pytest.approx(b, rel=1e-9, abs=1e-3)


def test_a_point_with_one_elastic_level_is_not_fitted_and_counts_as_yielded():
    sig = np.zeros((1, 4, 3, 6))
    peeq = np.full((1, 4, 3), 0.02)
    peeq[0, 1, 0] = 0.0  # one elastic level at point 0
    peeq[0, 1:3, 2] = 0.0  # two at point 2, stress zero
    out = cs.split(sig, peeq, T)
    assert out.fitted.tolist() == [[False, False, True]]
    assert out.bending_yielded(0.5 * T, SY).tolist() == [[True, True, False]]


def _slope(sx: float, sy_: float = 0.0) -> np.ndarray:
    b = np.zeros((1, 1, 6))
    b[0, 0, 0], b[0, 0, 1] = sx, sy_
    return b


def test_bending_alone_yields_at_sigma_y_uniaxially_and_in_plane_strain_at_the_plane_strain_value():
    """Uniaxial: |b| t/2 = sigma_y. Plane strain (sigma_2 = nu sigma_1):
    sigma_1 = sigma_y / sqrt(1 - nu + nu^2) at the surface."""
    nu = 0.29
    ok = np.ones((1, 1), bool)
    zero = np.zeros((1, 1, 6))
    for lo_hi, ratio in ((0.999, False), (1.001, True)):
        b = lo_hi * SY / (0.5 * T)
        assert cs.Split(zero, _slope(b), ok).bending_yielded(0.5 * T, SY)[0, 0] == ratio
        s1 = lo_hi * SY / math.sqrt(1 - nu + nu * nu) / (0.5 * T)
        assert cs.Split(zero, _slope(s1, nu * s1), ok).bending_yielded(0.5 * T, SY)[0, 0] == ratio


def test_the_membrane_stress_tips_a_point_the_bending_alone_leaves_elastic():
    """Bending 0.95 sigma_y at the surface and a membrane stress of 0.1
    sigma_y along it: the trial stress yields one face, the bending alone not."""
    ok = np.ones((1, 1), bool)
    a = _slope(0.1 * SY)
    b = _slope(0.95 * SY / (0.5 * T))
    sp = cs.Split(a, b, ok)
    assert not sp.bending_yielded(0.5 * T, SY)[0, 0]
    assert sp.trial_yielded(0.5 * T, SY)[0, 0]
    assert not sp.trial_yielded(0.25 * T, SY)[0, 0]  # 0.475 + 0.1 sigma_y inside


def test_membrane_at_the_yield_edge_is_the_median_where_the_bending_is_near_yield():
    ratios = np.array([0.5, 0.95, 1.0, 1.05, 1.5])
    membrane = np.array([100e6, 20e6, 30e6, 40e6, 100e6])
    a = np.zeros((5, 1, 6))
    a[:, 0, 0] = membrane
    b = np.zeros((5, 1, 6))
    b[:, 0, 0] = ratios * SY / (0.5 * T)
    sp = cs.Split(a, b, np.ones((5, 1), bool))
    assert sp.membrane_at_edge(T, SY) == pytest.approx(30e6, rel=1e-12)
    assert math.isnan(cs.Split(a[:1], b[:1], np.ones((1, 1), bool)).membrane_at_edge(T, SY))
