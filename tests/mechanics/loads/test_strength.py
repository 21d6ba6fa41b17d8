"""The STR verdicts of the outdoors check on patkau-one-fold (coarse mesh):
from the J2 load path, not the linear elastic peak."""

from __future__ import annotations

import json

import pytest

from onefold_cad.design import fold_design
from onefold_cad.mechanics.loads.outdoors import outdoors
from onefold_cad.mechanics.loads.plastic_limit import GAMMA_M1, R_MAX, STRAIN_LIMIT
from onefold_cad.mechanics.loads.spec import LoadSpec
from onefold_cad.templates import load_template


@pytest.fixture(scope="module")
def checked():
    """One wind direction, no person; two STR cases checked by their J2 paths:
    the permanent one and the one of the largest elastic peak."""
    design = load_template("patkau-one-fold")
    spec = LoadSpec(wind_speed=25.0, directions=1, person_kN=0.0)
    return outdoors(design, fold_design(design), spec, level="coarse", strength_cases=2)


def test_patkau_carries_its_own_weight(checked):
    """Patkau's sheets stand under their weight: the J2 path carries STR 1.35G
    past gamma_M1 (to R_MAX), though its linear elastic peak (information,
    singular at the relief hole's rim and at H) is several times f_y."""
    g = checked.case("STR 1.35G")
    assert g.utilisation > 2.0, "the elastic peak passes first yield"
    assert g.strength is not None
    assert g.strength.ratio >= GAMMA_M1
    assert g.stands and g.reason == ""
    # at the case itself a few faces have yielded, far from the strain limit
    assert 0.0 < g.strength.max_plastic_strain < STRAIN_LIMIT
    assert 0.0 < g.strength.plastic_area_share < 0.01
    assert g.strength.plastic_at == 1.0


def test_only_the_screened_cases_are_checked_and_the_rest_do_not_stand(checked):
    strs = [c for c in checked.cases if c.kind == "STR"]
    ran = [c.name for c in strs if c.strength is not None]
    top = max((c for c in strs if c.name != "STR 1.35G"), key=lambda c: c.utilisation)
    assert sorted(ran) == sorted(["STR 1.35G", top.name])
    assert checked.strength["cases_checked"] == [c.name for c in checked.cases if c.name in ran]
    for c in strs:
        if c.strength is None and c.utilisation > 1.0:
            assert not c.stands
            assert "not checked" in c.reason
            assert c.name in checked.strength["cases_not_checked"]
    assert any("not checked by a J2 load path" in w for w in checked.warnings)


def test_a_case_that_fails_says_its_load_ratio(checked):
    for c in checked.cases:
        s = c.strength
        if s is None:
            continue
        assert s.stands is (s.ratio >= GAMMA_M1)
        assert c.stands is s.stands
        assert s.ratio <= R_MAX
        if not s.stands:
            assert f"{s.ratio:.4g} x its design actions" in c.reason
            assert s.limit in ("strain", "stalled")


def test_the_report_keeps_the_elastic_peak_as_information(checked):
    data = json.loads(json.dumps(checked.to_data(), allow_nan=False))
    (g,) = [c for c in data["cases"] if c["name"] == "STR 1.35G"]
    assert g["strength"]["load_ratio"] >= GAMMA_M1
    assert len(g["utilisation_at"]) == 2
    assert any("GMNA" in a and "gamma_M1" in a for a in data["assumptions"])
    assert data["strength"]["cpu_s"] > 0.0
