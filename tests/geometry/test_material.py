"""The material's elastic-plastic values: Young's modulus, Poisson's ratio and
the yield stress, their ranges at both ends, and their trip through a template."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.material import (
    DENSITY_RANGE,
    MAX_MODULUS_GPA,
    MIN_MODULUS_GPA,
    MIN_YIELD_MPA,
    Material,
)
from onefold_cad.templates import design_to_data, load_template


@given(
    st.floats(MIN_MODULUS_GPA, MAX_MODULUS_GPA),
    st.floats(-1.0, 0.5, exclude_min=True, exclude_max=True),
    st.floats(0.0, 1.0),
)
def test_every_value_in_range_is_kept(e, nu, share):
    # from the smallest yield stress up to the modulus itself, in MPa
    sy = min(MIN_YIELD_MPA + share * (e * 1e3 - MIN_YIELD_MPA), e * 1e3)
    m = Material(youngs_modulus=e, poisson=nu, yield_stress=sy)
    assert (m.youngs_modulus, m.poisson, m.yield_stress) == (e, nu, sy)


@pytest.mark.parametrize(
    ("changes", "name"),
    [
        ({"youngs_modulus": 0.0}, "youngs_modulus"),
        ({"youngs_modulus": math.nextafter(MIN_MODULUS_GPA, 0.0)}, "youngs_modulus"),
        ({"yield_stress": math.nextafter(MIN_YIELD_MPA, 0.0)}, "yield_stress"),
        ({"yield_stress": 1e-320}, "yield_stress"),
        ({"youngs_modulus": math.nextafter(MAX_MODULUS_GPA, math.inf)}, "youngs_modulus"),
        ({"youngs_modulus": math.nan}, "youngs_modulus"),
        ({"poisson": 0.5}, "poisson"),
        ({"poisson": -1.0}, "poisson"),
        ({"poisson": math.inf}, "poisson"),
        ({"yield_stress": 0.0}, "yield_stress"),
        ({"youngs_modulus": 193.0, "yield_stress": math.nextafter(193e3, 1e6)}, "yield_stress"),
        ({"yield_stress": math.nextafter(MAX_MODULUS_GPA * 1e3, math.inf)}, "yield_stress"),
        # a mass that underflows (1e-320 made simulate's best fit divide 0 by 0) or overflows
        ({"density": math.nextafter(DENSITY_RANGE[0], 0.0)}, "density"),
        ({"density": math.nextafter(DENSITY_RANGE[1], math.inf)}, "density"),
        ({"density": 1e-320}, "density"),
        # hardening: not negative, not as stiff as the steel itself, a share of it kinematic
        ({"hardening_modulus": -1.0}, "hardening_modulus"),
        ({"hardening_modulus": math.nan}, "hardening_modulus"),
        ({"youngs_modulus": 193.0, "hardening_modulus": 193e3}, "hardening_modulus"),
        ({"kinematic_hardening": -0.1}, "kinematic_hardening"),
        ({"kinematic_hardening": 1.5}, "kinematic_hardening"),
    ],
)
def test_values_outside_the_range_name_the_parameter(changes, name):
    with pytest.raises(InvalidParameterError) as info:
        Material(**changes)
    assert info.value.parameter == name


def test_the_edges_inside_the_range_are_allowed():
    m = Material(youngs_modulus=MAX_MODULUS_GPA, poisson=math.nextafter(0.5, 0.0))
    assert m.poisson < 0.5
    assert Material(youngs_modulus=193.0, yield_stress=193e3).yield_stress == 193e3
    assert Material(poisson=math.nextafter(-1.0, 0.0)).poisson > -1.0
    assert [Material(density=d).density for d in DENSITY_RANGE] == list(DENSITY_RANGE)
    low = Material(youngs_modulus=MIN_MODULUS_GPA, yield_stress=MIN_YIELD_MPA)
    assert (low.youngs_modulus, low.yield_stress) == (MIN_MODULUS_GPA, MIN_YIELD_MPA)


def test_the_stainless_template_has_its_data_and_writes_it_back():
    design = load_template("patkau-one-fold")
    m = design.material
    assert (m.youngs_modulus, m.poisson, m.yield_stress) == (193.0, 0.29, 215.0)
    data = design_to_data(design)["material"]
    assert (data["youngs_modulus"], data["poisson"], data["yield_stress"]) == (193.0, 0.29, 215.0)


def test_a_material_without_them_writes_none():
    data = design_to_data(load_template("paper-square"))["material"]
    assert not {"youngs_modulus", "poisson", "yield_stress"} & set(data)


@pytest.mark.parametrize(
    ("overbend", "number"), [(None, 0.0), (0.0, 0.0), (6.0, 6.0), (-45.0, -45.0)]
)
def test_the_overbend_is_a_number_and_sets_the_crease_past_its_fold(overbend, number) -> None:
    m = Material(thickness=3.0, crease_overbend=overbend)
    assert m.overbend_deg == number
    assert m.crease_set_angle(82.5) == 82.5 + number


@pytest.mark.parametrize("overbend", [-45.01, 45.01, float("nan")])
def test_an_overbend_past_its_range_is_refused_naming_it(overbend) -> None:
    with pytest.raises(InvalidParameterError, match="crease_overbend"):
        Material(thickness=3.0, crease_overbend=overbend)
