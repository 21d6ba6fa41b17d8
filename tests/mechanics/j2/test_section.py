"""The section through the thickness against closed forms of strips (values
by hand or from textbooks, never from the model): plane-strain first yield
and fully plastic moment, Gardiner's springback, Masing's reverse branch,
the tension-bending interaction at full plasticity; the rule's convergence."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.j2.law import J2Law
from onefold_cad.mechanics.j2.section import DEFAULT_POINTS, ThicknessRule, section_update
from tests.mechanics.section_paths import NARROW_FREE, WIDE_FREE, Section

E, NU, SY, T = 200e9, 0.29, 215e6, 3.57e-3  # Patkau's stainless sheet
LAW = J2Law(E, NU, SY)
EP = E / (1 - NU**2)
#: The plane-strain yield stress of the bent sheet's surface (sigma_22 = nu sigma_11).
SY_PS = SY / math.sqrt(1 - NU + NU**2)
KY = 2 * SY / (E * T)  # the narrow strip's yield curvature
MP = SY * T**2 / 4  # the narrow strip's fully plastic moment
MY = SY * T**2 / 6


def _rule(points: int = DEFAULT_POINTS) -> ThicknessRule:
    return ThicknessRule(T, points)


def test_the_rule_integrates_polynomials_and_holds_both_surfaces():
    rule = _rule()
    z, w = rule.heights, rule.weights
    assert z[0] == -T / 2 and z[-1] == T / 2 and 0.0 in z
    assert w.sum() == pytest.approx(T, rel=1e-14)
    assert (w * z**2).sum() == pytest.approx(T**3 / 12, rel=1e-13)
    assert (w * np.abs(z)).sum() == pytest.approx(T**2 / 4, rel=1e-13)


def test_an_elastic_section_is_the_plate_s_stiffness():
    """A and D of a plate, no coupling: E' t and E' t^3 / 12 (the model's membrane
    and bending stiffness)."""
    r = section_update(LAW, _rule(), np.zeros((1, 3)), np.zeros((1, 3)), _virgin(1))
    a, b, d = r.tangent[0, :3, :3], r.tangent[0, :3, 3:], r.tangent[0, 3:, 3:]
    c = EP * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    assert np.allclose(a, c * T, rtol=1e-13)
    assert np.allclose(b, 0, atol=1e-12 * EP * T**2)
    assert np.allclose(d, c * T**3 / 12, rtol=1e-13)


def _virgin(m: int):
    from onefold_cad.mechanics.j2.law import J2State

    return J2State.virgin((m, DEFAULT_POINTS))


# -- (b) a wide strip in cylindrical bending (plane strain) ------------------------
def test_a_wide_strip_first_yields_at_the_plane_strain_stress():
    """sigma_11 = sigma_y / sqrt(1 - nu + nu^2) at the surface, reached at
    k = 2 sigma_11 / (E' t); just below no point flows, just above the surfaces do."""
    k_first = 2 * SY_PS / (EP * T)
    below, above = Section(LAW, _rule(), WIDE_FREE), Section(LAW, _rule(), WIDE_FREE)
    r = below.step({3: k_first * (1 - 1e-6)})
    assert not r.plastic.any()
    assert r.stress[0, 0] == pytest.approx(-SY_PS, rel=1e-5)
    assert r.stress[0, 1] == pytest.approx(NU * r.stress[0, 0], rel=1e-9)
    r = above.step({3: k_first * (1 + 1e-6)})
    assert r.plastic[[0, -1]].all() and not r.plastic[1:-1].any()


def test_a_wide_strip_tends_to_the_plane_strain_fully_plastic_moment():
    """M -> (2 / sqrt 3) sigma_y t^2 / 4, 1.15 times the narrow strip's."""
    s = Section(LAW, _rule(), WIDE_FREE)
    for k in np.linspace(0, 60 * KY, 241)[1:]:
        r = s.step({3: k})
    assert r.moment[0] == pytest.approx(2 / math.sqrt(3) * MP, rel=1e-3)


# -- (c) Gardiner's springback --------------------------------------------------------
def _springback(free, x: float, modulus: float, yield_stress: float, points: int) -> float:
    """R_i / R_f of a strip bent to R_i = x E t / sigma_y and released."""
    k = yield_stress / (x * modulus * T)
    s = Section(LAW, _rule(points), free)
    for kk in np.linspace(0, k, 21)[1:]:
        s.step({3: kk})
    s.free = tuple(sorted({*free, 3}))
    s.step({})  # M_11 = 0 too
    return float(s.strain[3] / k)


def _gardiner(x: float) -> float:
    return 4 * x**3 - 3 * x + 1


GARDINER_X = np.linspace(0.02, 0.45, 18)


@pytest.mark.parametrize("x", GARDINER_X)
def test_a_narrow_strip_springs_back_as_gardiner_says(x):
    """Gardiner (1957), uniaxial bending of an elastic-perfectly plastic strip:
    R_i / R_f = 4 x^3 - 3 x + 1, x = R_i sigma_y / (E t); within 0.01 with 17
    points through the thickness."""
    got = _springback(NARROW_FREE, x, E, SY, 17)
    assert got == pytest.approx(_gardiner(x), abs=0.01)


@pytest.mark.parametrize("x", GARDINER_X[::3])
def test_a_wide_strip_springs_back_between_the_plane_strain_bounds(x):
    """With E' and the yield stress between sigma_y / sqrt(1 - nu + nu^2) (first
    yield) and 2 sigma_y / sqrt 3 (full plasticity), Gardiner's formula brackets
    the wide strip's springback."""
    got = _springback(WIDE_FREE, x, E, SY, 17)
    r = x * E * T / SY  # the same radius for both bounds
    bounds = [_gardiner(r * s / (EP * T)) for s in (SY_PS, 2 * SY / math.sqrt(3))]
    assert min(bounds) - 0.005 <= got <= max(bounds) + 0.005


def test_springback_converges_with_the_points_through_the_thickness():
    """The largest error against Gardiner over x in 0.02..0.45 falls as the
    points grow (composite Simpson: about points^-2 between the kinks)."""
    worst = {
        n: max(abs(_springback(NARROW_FREE, x, E, SY, n) - _gardiner(x)) for x in GARDINER_X)
        for n in (5, 9, 17, 33)
    }
    assert worst[5] > worst[9] > worst[17] > worst[33]
    assert worst[33] < 0.004


# -- (d) Masing: bent and bent back -----------------------------------------------
def test_a_narrow_strip_bent_back_follows_masing_s_rule():
    """Perfectly plastic, bent to 3 kappa_y and back: the reverse branch is the
    forward one scaled by two, M_1 - M(dk) = 2 M_fwd(dk / 2), within 1 % of M_1,
    and reverse yield starts after a moment change of 2 M_y."""
    s = Section(LAW, _rule(17), NARROW_FREE)
    k1 = 3 * KY
    ks = np.linspace(0, k1, 61)[1:]
    forward = np.array([s.step({3: k}).moment[0] for k in ks])
    m1 = forward[-1]
    back = np.linspace(k1, -k1, 121)[1:]
    reverse = []
    for k in back:
        r = s.step({3: k})
        reverse.append((k1 - k, m1 - r.moment[0], bool(r.plastic.any())))
    for dk, dm, _ in reverse:
        expected = 2 * np.interp(dk / 2, np.r_[0, ks], np.r_[0, forward])
        assert dm == pytest.approx(expected, abs=0.01 * m1)
    first = next(dm for dk, dm, flowed in reverse if flowed)
    step = (E * T**3 / 12) * (back[0] - back[1])  # one step's elastic moment change
    assert 2 * MY * (1 - 0.005) <= first <= 2 * MY + step


# -- (e) tension and bending at full plasticity -------------------------------------
@pytest.mark.parametrize("offset", [0.0, 0.2, 0.5, 0.8])
def test_tension_and_bending_at_full_plasticity_lie_on_the_interaction_curve(offset):
    """A narrow strip bent far past yield with its neutral axis at ``offset``
    t / 2 from the middle: M / M_p + (N / N_p)^2 = 1 within 1 %."""
    s = Section(LAW, _rule(17), NARROW_FREE)
    for k in np.linspace(0, 200 * KY, 101)[1:]:
        r = s.step({3: k, 0: offset * T / 2 * k})
    n, m = r.force[0], r.moment[0]
    assert n / (SY * T) == pytest.approx(offset, abs=0.01)  # the neutral axis sets N
    assert m / MP + (n / (SY * T)) ** 2 == pytest.approx(1.0, abs=0.01)


def test_an_even_or_small_number_of_points_is_refused():
    for points in (2, 4, 1):
        with pytest.raises(InvalidParameterError) as info:
            ThicknessRule(T, points)
        assert info.value.parameter == "points"
