"""The cones' forming sheet and the sheet formed past its springback: the
stations on the blank, the cone's radius against its closed form (r over the
directrix's geodesic curvature, from the fold's own frames), the radius to
form to against the J2 section released from it, and ``simulate`` of a sheet
so formed: its springback a small fraction of the design-formed sheet's."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.choices import Model
from onefold_cad.design import fold_design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.mechanics.cone_forming import STATIONS, cone_stations
from onefold_cad.mechanics.j2.law import J2Law
from onefold_cad.mechanics.j2.section import ThicknessRule
from onefold_cad.mechanics.j2.springback import released_curvature
from onefold_cad.mechanics.j2.stages import FORMING_STEPS
from onefold_cad.mechanics.model import check_cone_forming
from onefold_cad.mechanics.simulate import run
from onefold_cad.templates import load_template


def _with_cones(design, forming):
    return design.with_changes(material=design.material.with_changes(cone_forming=forming))


@pytest.fixture(scope="module")
def patkau():
    design = load_template("patkau-one-fold")
    return design, fold_design(design)


def _geodesic_curvature(folded, theta):
    """k(theta) = (de/dtheta) . n from the cone's frames (a finite difference
    on a fine grid), as tests/mechanics/test_simulate.py's closed form."""
    surface = folded.solution.surface
    grid = np.linspace(1e-7, surface.total_angle - 1e-7, 20001)
    u, e = surface.frames(grid)
    k = np.einsum("ij,ij->i", np.gradient(e, grid, axis=0), np.cross(u, e))
    return np.interp(theta, grid, k)


def test_the_stations_lie_along_rulings_from_the_hole_to_the_edge(patkau):
    design, folded = patkau
    rows = cone_stations(design, folded)
    hole = relief_hole_diameter(design, folded) / 2
    for side, sign in (("+y", 1.0), ("-y", -1.0)):
        mine = [r for r in rows if r.side == side]
        assert len(mine) % STATIONS == 0 and len(mine) >= 10 * STATIONS
        for r in mine:
            assert math.hypot(r.x, r.y) == pytest.approx(r.distance, rel=1e-12)
            t = math.radians(r.ruling_deg)
            assert (r.x, r.y) == pytest.approx(
                (r.distance * math.cos(t), sign * r.distance * math.sin(t))
            )
        firsts, lasts = mine[::STATIONS], mine[STATIONS - 1 :: STATIONS]
        assert all(r.distance == pytest.approx(hole) for r in firsts)
        for r in lasts:  # on the sheet's edge
            edge = design.sheet.ray_lengths(np.array([sign * math.radians(r.ruling_deg)]))[0]
            assert r.distance == pytest.approx(edge, rel=1e-9)


def test_the_cone_radius_is_r_over_the_geodesic_curvature(patkau):
    design, folded = patkau
    rows = cone_stations(design, folded)
    theta = np.radians([r.ruling_deg for r in rows])
    inner = (theta > 1e-3) & (theta < math.pi - 1e-3)  # the grid's ends are one-sided
    k = np.abs(_geodesic_curvature(folded, theta))
    got = np.array([r.cone_radius for r in rows])
    want = np.array([r.distance for r in rows]) / k
    assert got[inner] == pytest.approx(want[inner], rel=1e-4)


def test_formed_to_the_design_the_form_radius_is_the_cone_s(patkau):
    design, folded = patkau
    for forming in (None, "design"):
        rows = cone_stations(_with_cones(design, forming), folded)
        assert all(r.form_radius == r.cone_radius for r in rows)


def test_formed_past_the_springback_a_section_released_keeps_the_cone_s_radius(patkau):
    """The J2 section of the sheet (its E, nu, sigma_y, hardening; 9 points),
    formed to the sheet's radius and released to no moment in plane strain,
    keeps the cone's radius within 0.5 %; every station is formed tighter."""
    design, folded = patkau
    rows = cone_stations(_with_cones(design, "compensated"), folded)
    m, metres = design.material, design.units.mm / 1000.0
    law = J2Law(m.youngs_modulus * 1e9, m.poisson, m.yield_stress * 1e6, m.hardening_modulus * 1e6)
    form = np.array([r.form_radius for r in rows]) * metres
    cone = np.array([r.cone_radius for r in rows]) * metres
    assert np.all(form < cone)
    kept = released_curvature(law, ThicknessRule(m.thickness * 1e-3), 1 / form, FORMING_STEPS)
    assert 1 / kept == pytest.approx(cone, rel=5e-3)


def test_the_paper_model_has_no_cones_to_list():
    design = load_template("table1-row1")  # the paper's fan of planar triangles
    assert design.model is Model.PAPER
    with pytest.raises(InvalidParameterError) as info:
        cone_stations(design, fold_design(design))
    assert info.value.parameter == "model"


def test_compensated_cones_need_the_steel_s_values():
    design = _with_cones(load_template("paper-square"), "compensated")  # no E, nu, sigma_y
    with pytest.raises(InvalidParameterError) as info:
        cone_stations(design, fold_design(design))
    assert info.value.parameter in (
        "youngs_modulus",
        "poisson",
        "yield_stress",
        "density",
        "thickness",
    )


def test_compensated_cones_are_refused_with_the_moment_law(patkau):
    design = _with_cones(patkau[0], "compensated")
    with pytest.raises(InvalidParameterError) as info:
        check_cone_forming(design, "moment", "flat")
    assert info.value.parameter == "cone_forming" and "--law j2" in str(info.value)
    check_cone_forming(design, "j2", "flat")
    check_cone_forming(design, "moment", "designed")  # the designed form: no forming
    check_cone_forming(patkau[0], "moment", "flat")


def test_formed_past_its_springback_the_sheet_springs_back_a_fiftieth(patkau):
    """Coarse mesh, J2: the design-formed sheet springs back some 440 mm
    (docs/mechanics.md); formed past its springback, under a fiftieth of it,
    and nearly all of it has yielded in forming."""
    design, folded = patkau
    plain = run(design, folded, level="coarse", law="j2")
    past = run(_with_cones(design, "compensated"), folded, level="coarse", law="j2")
    assert plain.cone_forming == "design" and past.cone_forming == "compensated"
    assert plain.released.max_deviation > 300.0
    assert past.released.max_deviation < plain.released.max_deviation / 50
    assert past.formed.plastic_area_share > 0.95 > plain.formed.plastic_area_share
    assert past.to_data()["cone_forming"] == "compensated"
