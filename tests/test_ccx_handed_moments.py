"""The resultants benchmarks/ccx_handed_moments.py compares CalculiX's handed
state with onefold's by: a stress linear through the thickness gives its N
and M back exactly; the projected ratio of a scaled moment is the scale;
principal values by hand. No ccx needed."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import ccx_handed_moments as hm  # noqa: E402
from ccx_release import point_heights  # noqa: E402

T = 0.00357


def test_a_stress_linear_through_the_thickness_gives_its_resultants_back():
    rng = np.random.default_rng(3)
    n_want = rng.normal(size=(5, 3)) * 1e4  # N/m
    m_want = rng.normal(size=(5, 3)) * 1e2  # N m/m
    z = point_heights(T, 2).ravel()
    plane = n_want[:, None, :] / T + 12 * m_want[:, None, :] * z[None, :, None] / T**3
    n, m = hm.resultants(plane, z, T)
    assert n == pytest.approx(n_want, rel=1e-10)
    assert m == pytest.approx(m_want, rel=1e-10)


def test_the_line_through_a_fully_plastic_profile_by_hand():
    # +-1 Pa on either half (M_p = t^2 / 4): the least-squares line through
    # four points at z / t = +-1/8, +-3/8 reads 16 / 15 of it
    z = np.array([-0.375, -0.125, 0.125, 0.375]) * T
    plane = np.zeros((1, 4, 3))
    plane[0, :, 0] = np.sign(z)
    m = hm.resultants(plane, z, T)[1][0, 0]
    # least squares: slope = sum(z s) / sum(z^2) = T / (0.3125 T^2) = 3.2 / T
    assert m == pytest.approx(3.2 * T**2 / 12, rel=1e-12)
    assert m / (T**2 / 4) == pytest.approx(16 / 15, rel=1e-12)


def test_the_projected_ratio_of_a_scaled_moment_is_the_scale():
    m = np.array([[3.0, -1.0, 0.5], [0.0, 2.0, -2.0]])
    assert hm.projected_ratio(0.9 * m, m) == pytest.approx([0.9, 0.9], rel=1e-14)
    # a moment at right angles to the reference (its deviator turned by 45 deg) carries none
    assert hm.projected_ratio(np.array([[0.0, 0.0, 1.0]]), np.array([[1.0, -1.0, 0.0]]))[0] == 0


def test_the_larger_principal_value_by_hand():
    # [[1, 2], [2, -2]]: eigenvalues (-1 +- 5) / 2 = 2, -3
    assert hm.larger_principal(np.array([[1.0, -2.0, 2.0]]))[0] == pytest.approx(3.0)


def test_the_stress_along_the_reference_s_bending_direction():
    ref = np.array([[0.0, 0.0, 1.0]])  # principal directions at 45 deg, values +-1
    plane = np.array([[[2.0, 0.0, 0.0]]])  # uniaxial along x
    along, across = hm._along(plane, ref)
    assert along[0, 0] == pytest.approx(1.0)  # 2 cos^2 45
    assert across[0, 0] == pytest.approx(1.0)
