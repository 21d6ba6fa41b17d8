"""The curvature a cone's section keeps after release, and its inverse,
against closed forms: nothing kept below the plane-strain first yield,
Gardiner's springback between the plane-strain bounds, the inverse
returning what it was asked for, and the scaled tensors of bent faces."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.mechanics.j2.law import J2Law
from onefold_cad.mechanics.j2.section import ThicknessRule
from onefold_cad.mechanics.j2.springback import (
    SpringbackTable,
    compensated_curvatures,
    first_yield_curvature,
    released_curvature,
)

E, NU, SY, T = 200e9, 0.29, 215e6, 3.57e-3  # Patkau's stainless sheet
EP = E / (1 - NU**2)
PERFECT = J2Law(E, NU, SY)
HARDENING = J2Law(E, NU, SY, hardening_iso=507e6)  # the shipped 304's
STEPS = 4  # return mappings along the forming path


def _gardiner(x: float) -> float:
    """Gardiner (1957): R_formed / R_released = 4 x^3 - 3 x + 1, x = R sigma / (E t)."""
    return 4 * x**3 - 3 * x + 1


def test_first_yield_is_the_plane_strain_surface_stress():
    """sigma_11 E' t k / 2 reaches sigma_y / sqrt(1 - nu + nu^2) at the surface."""
    k = first_yield_curvature(PERFECT, T)
    assert EP * k * T / 2 == pytest.approx(SY / math.sqrt(1 - NU + NU**2), rel=1e-14)


def test_a_section_formed_below_first_yield_keeps_nothing():
    k1 = first_yield_curvature(PERFECT, T)
    formed = k1 * np.array([0.1, 0.5, 0.9, 0.99])
    kept = released_curvature(PERFECT, ThicknessRule(T, 17), formed, STEPS)
    assert np.all(np.abs(kept) < 1e-12 * formed)


@pytest.mark.parametrize("x", np.linspace(0.02, 0.45, 7))
def test_the_kept_curvature_lies_between_gardiner_s_plane_strain_bounds(x):
    """Perfectly plastic, plane strain: with E' and the yield stress between
    sigma_y / sqrt(1 - nu + nu^2) (first yield) and 2 sigma_y / sqrt 3 (full
    plasticity), Gardiner's ratio brackets kept / formed (x taken with sigma_y)."""
    radius = x * EP * T / SY
    kept = released_curvature(PERFECT, ThicknessRule(T, 33), np.array([1 / radius]), STEPS)[0]
    ratio = kept * radius
    bounds = [_gardiner(radius * s / (EP * T)) for s in
              (SY / math.sqrt(1 - NU + NU**2), 2 * SY / math.sqrt(3))]  # fmt: skip
    assert min(bounds) - 0.004 <= ratio <= max(bounds) + 0.004


def test_hardening_springs_back_further():
    """The same formed curvature keeps less with the hardening modulus (a
    larger moment to unload), and every kept curvature is below the formed."""
    k1 = first_yield_curvature(PERFECT, T)
    formed = k1 * np.geomspace(1.2, 100, 12)
    rule = ThicknessRule(T, 17)
    perfect = released_curvature(PERFECT, rule, formed, STEPS)
    hard = released_curvature(HARDENING, rule, formed, STEPS)
    assert np.all(hard < perfect) and np.all(perfect < formed) and np.all(hard > 0)


@pytest.mark.parametrize("law", [PERFECT, HARDENING], ids=["perfect", "hardening"])
def test_forming_to_the_table_keeps_what_was_asked(law):
    """Released from the table's forming curvature, a section keeps the
    curvature asked for, within 0.3 % (the table's interpolation), from just
    past first yield to a radius of 20 thicknesses."""
    rule = ThicknessRule(T, 9)
    table = SpringbackTable.of(law, rule, STEPS)
    k1 = first_yield_curvature(law, T)
    asked = np.geomspace(0.01 * k1, 1 / (20 * T), 25)
    formed = table.forming(asked)
    assert np.all(formed > asked) and np.all(formed >= k1)
    kept = released_curvature(law, rule, formed, STEPS)
    assert kept == pytest.approx(asked, rel=3e-3)


def test_forming_nothing_forms_nothing():
    table = SpringbackTable.of(PERFECT, ThicknessRule(T, 9), STEPS)
    assert table.forming(np.array([0.0]))[0] == 0.0


def test_a_bent_face_s_tensor_is_scaled_to_its_forming_curvature_in_any_direction():
    """A face bent by k about any direction phi ((k cos^2, k sin^2, 2 k sin cos)
    Cartesian) becomes the same direction's tensor at the table's forming
    curvature; bent the other way, its negative; flat, flat."""
    table = SpringbackTable.of(HARDENING, ThicknessRule(T, 9), STEPS)
    k = 0.3  # 1/m: a cone 3.3 m from its axis
    rows, expected = [], []
    for phi in np.linspace(0, math.pi, 7):
        c, s = math.cos(phi), math.sin(phi)
        for sign in (1.0, -1.0):
            rows.append(sign * k * np.array([c * c, s * s, 2 * s * c]))
            expected.append(
                sign * table.forming(np.array([k]))[0] * np.array([c * c, s * s, 2 * s * c])
            )
    rows.append(np.zeros(3))
    expected.append(np.zeros(3))
    got = compensated_curvatures(np.array(rows), table)
    assert got == pytest.approx(np.array(expected), rel=1e-12, abs=1e-15)
