"""The outdoors check of patkau-one-fold on the coarse mesh: statics of every
case, the supports' answers and the report's data."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from onefold_cad.design import fold_design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.loads.feet import three_feet_reactions
from onefold_cad.mechanics.loads.outdoors import outdoors
from onefold_cad.mechanics.loads.spec import LoadSpec
from onefold_cad.templates import load_template


@pytest.fixture(scope="module")
def patkau():
    design = load_template("patkau-one-fold")
    return design, fold_design(design)


@pytest.fixture(scope="module")
def anchored(patkau):
    return outdoors(*patkau, LoadSpec(wind_speed=25.0, snow_kPa=1.0, directions=4), level="coarse")


def test_every_case_is_in_equilibrium(anchored):
    """The feet's reactions balance each case's loads: the weight times its
    factor plus the variable loads (their sum to 1e-9 of the feet's forces), and on three feet
    their vertical parts are the statics' (the moments about the ground's
    axes, within 2 % of the weight: the linear response balances moments on
    the standing form, the statics on the form it moves to)."""
    o = anchored
    assert len(o.feet) == 3
    g = o.case("STR 1.35G")
    assert math.isclose(g.reactions_N[:, 2].sum(), 1.35 * o.weight_N, rel_tol=1e-9)
    for c in o.cases:
        # to 1e-9 of the forces the feet carry (a sum of +-5 kN feet can be -0.4 kN)
        scale = float(np.abs(c.reactions_N).sum())
        assert math.isclose(
            c.reactions_N[:, 2].sum(), c.vertical_N, rel_tol=0, abs_tol=1e-9 * scale
        )
    at = np.array([f.at for f in o.feet]) * 1e-3
    up = o.case("EQU 0.9G + 1.5W-0")
    assert up.reactions_N[:, 2].min() < 0.0  # an anchor pulls
    # the statics of the same case: force and moment from the reactions themselves
    force = -np.array([0.0, 0.0, up.reactions_N[:, 2].sum()])
    moment = -np.cross(np.column_stack([at, np.zeros(3)]), up.reactions_N).sum(axis=0)
    assert np.allclose(
        three_feet_reactions(at, force, moment), up.reactions_N[:, 2], atol=1e-6 * o.weight_N
    )


def test_anchors_take_the_largest_pull_and_push(anchored):
    o = anchored
    uls = [c for c in o.cases if c.kind in ("EQU", "STR")]
    for i, foot in enumerate(o.feet):
        assert math.isclose(foot.tension_N, max(0.0, max(-c.reactions_N[i, 2] for c in uls)))
        assert foot.compression_N >= o.case("STR 1.35G").reactions_N[i, 2] - 1e-9
    assert o.governing in {c.name for c in o.cases}
    data = json.loads(json.dumps(o.to_data(), allow_nan=False))
    assert data["totals"]["tension_N"] == pytest.approx(sum(f.tension_N for f in o.feet))


def test_friction_feet_slide_or_lift_under_the_wind(patkau):
    """On friction feet (mu 0.3) the 25 m/s wind that makes an anchor pull lifts
    a foot: that case does not stand, and says why."""
    o = outdoors(*patkau, LoadSpec(wind_speed=25.0, directions=2, person_kN=0.0,
                                   supports="friction"), level="coarse")  # fmt: skip
    up = o.case("EQU 0.9G + 1.5W-0")
    assert not up.stands
    assert "lift" in up.reason or "tips" in up.reason
    spec = LoadSpec(wind_speed=0.0, directions=1, person_kN=0.0, supports="friction", friction=0.9)
    calm = outdoors(*patkau, spec, level="coarse")
    for c in (c for c in calm.cases if c.kind == "EQU"):
        # on still air nothing slides as a whole; a foot slips where its own
        # thrust passes mu times its load, and then the case says so
        h = np.hypot(c.reactions_N[:, 0], c.reactions_N[:, 1])
        slips = bool((h > 0.9 * c.reactions_N[:, 2]).any())
        assert c.slide_ratio < 1e-6
        assert c.stands is not slips
        assert ("slips" in c.reason) is slips


def test_ballast_lifts_no_foot_and_slips_none(patkau):
    """The ballast found for each foot (counted at 0.9 of its weight) balances
    the largest pull at that foot in every EQU case, and holds its horizontal
    force by friction."""
    o = outdoors(*patkau, LoadSpec(wind_speed=25.0, directions=2, person_kN=0.0,
                                   supports="ballast"), level="coarse")  # fmt: skip
    for c in o.cases:
        if c.kind != "EQU":
            continue
        held = c.reactions_N[:, 2] + 0.9 * 9.80665 * np.array([f.ballast_kg for f in o.feet])
        assert held.min() >= -1e-9 * o.weight_N
        h = np.hypot(c.reactions_N[:, 0], c.reactions_N[:, 1])
        assert (h <= 0.3 * held * (1 + 1e-9) + 1e-9 * o.weight_N).all()


def test_a_person_outside_the_sheet_is_refused(patkau):
    with pytest.raises(InvalidParameterError, match="^person_at: must lie on the flat sheet"):
        outdoors(*patkau, LoadSpec(wind_speed=10.0, person_at=(9000.0, 0.0)), level="coarse")


def test_full_model_agrees_with_the_linear_cases_under_a_light_wind(patkau):
    """At 8 m/s the governing case solved again with the full model (Newton,
    the loads ramped) carries all of it; its feet's vertical reactions (three
    feet: statically determinate) are the linear ones' to 1 % of the weight,
    and it moves the sheet as the linear response does to 25 % (the weight's
    own 0.35 G is not linear: 13 % apart, measured)."""
    o = outdoors(*patkau, LoadSpec(wind_speed=8.0, directions=1, person_kN=0.0),
                 level="coarse", nonlinear=True)  # fmt: skip
    assert o.nonlinear
    for check in o.nonlinear:
        lin = o.case(check.case)
        assert check.reached == 1.0
        assert np.allclose(check.reactions_N[:, 2], lin.reactions_N[:, 2], atol=0.01 * o.weight_N)
        assert abs(check.max_deflection / check.linear_deflection - 1) < 0.25


def test_a_velocity_pressure_given_directly_scales_the_wind(patkau, anchored):
    """q_p given directly is used as given, and the wind's share of a case's
    reactions scales with it (the responses are linear in the loads)."""
    q = anchored.peak_velocity_pressure_kPa
    spec = LoadSpec(velocity_pressure_kPa=2 * q, snow_kPa=1.0, directions=4)
    double = outdoors(*patkau, spec, level="coarse")
    assert double.peak_velocity_pressure_kPa == 2 * q
    name, weight = "SLS G + W-90", "SLS G"
    wind = anchored.case(name).reactions_N - anchored.case(weight).reactions_N
    wind2 = double.case(name).reactions_N - double.case(weight).reactions_N
    assert np.allclose(wind2, 2 * wind, rtol=1e-9, atol=1e-9 * anchored.weight_N)
