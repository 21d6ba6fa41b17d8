"""Wind, snow and the point load: EN values by hand, resultants by statics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics import flat_positions, mesh_sheet
from onefold_cad.mechanics.loads.combinations import combinations
from onefold_cad.mechanics.loads.feet import resultant
from onefold_cad.mechanics.loads.point import grid_points, point_load
from onefold_cad.mechanics.loads.snow import shape_coefficient, snow_load
from onefold_cad.mechanics.loads.spec import LoadSpec
from onefold_cad.mechanics.loads.wind import (
    peak_velocity_pressure,
    terrain,
    wind_load,
    windward_weights,
)


def _plate(length=2.0, width=1.0, h=0.05):
    mesh = mesh_sheet([[0, 0], [length, 0], [length, width], [0, width]], size=(h, 0.0, h))
    return mesh, flat_positions(mesh)


def test_peak_velocity_pressure_category_ii_at_10_m():
    """EN 1991-1-4 at z = 10 m, category II: c_r = 0.19 ln(200), I_v = 1 / ln(200),
    so q_p / q_b = (1 + 7 / ln 200) (0.19 ln 200)^2 = 2.35, Figure 4.2's
    exposure factor there (read 2.3 to 2.4)."""
    v_b = 25.0
    q_b = 0.5 * 1.25 * v_b**2
    ratio = peak_velocity_pressure(v_b, 10.0, terrain("II")) / q_b
    assert 2.3 <= ratio <= 2.4
    log = math.log(200.0)
    assert math.isclose(ratio, (1 + 7 / log) * (0.19 * log) ** 2, rel_tol=1e-12)


def test_below_z_min_the_pressure_is_that_at_z_min():
    cat = terrain("IV")
    assert peak_velocity_pressure(20.0, 3.0, cat) == peak_velocity_pressure(20.0, 10.0, cat)


@pytest.mark.parametrize("name", ["V", "open", "", "2.5"])
def test_unknown_terrain_category(name):
    with pytest.raises(InvalidParameterError, match="^terrain: .*0, I, II, III, IV"):
        terrain(name)


def test_wind_resultant_a_quarter_depth_from_the_windward_edge():
    """On a flat plate the wind's mean pressure is c q_p and its centre of
    pressure lies d / 4 from the windward edge (EN 1991-1-4 Figure 7.16),
    whatever the direction along the axes."""
    mesh, x = _plate(2.0, 1.0, 0.02)
    for direction, (axis, lo, depth) in {0.0: (0, 0.0, 2.0), 180.0: (0, 2.0, -2.0),
                                         90.0: (1, 0.0, 1.0)}.items():  # fmt: skip
        w = windward_weights(x, mesh.triangles, direction)
        load = wind_load(x, mesh.triangles, 500.0, -0.5, direction)
        f, m = resultant(x, load)
        assert math.isclose(f[2], 0.5 * 500.0 * 2.0, rel_tol=2e-3)  # lifts: +z
        centre = np.array([-m[1] / f[2], m[0] / f[2]])
        assert abs(centre[axis] - (lo + depth / 4)) < 2e-3 * abs(depth)
        assert math.isclose(np.average(w), 1.0, rel_tol=5e-3)


def test_snow_shape_coefficient_table_5_2():
    assert np.allclose(shape_coefficient([0.0, 30.0, 45.0, 60.0, 80.0]), [0.8, 0.8, 0.4, 0.0, 0.0])


@pytest.mark.parametrize("slope", [0.0, 20.0, 45.0])
def test_snow_on_a_tilted_plate(slope):
    """A plate tilted by ``slope`` carries mu_1 C_e C_t s_k on its plan A cos(slope)."""
    mesh, x = _plate()
    a = math.radians(slope)
    tilted = np.column_stack([x[:, 0] * math.cos(a), x[:, 1], x[:, 0] * math.sin(a)])
    load = snow_load(tilted, mesh.triangles, 1000.0, 1.2, 0.9)
    mu = 0.8 if slope <= 30 else 0.8 * (60 - slope) / 30
    assert math.isclose(
        -load[:, 2].sum(), mu * 1.2 * 0.9 * 1000.0 * 2.0 * math.cos(a), rel_tol=1e-9
    )


def test_point_load_acts_at_its_point():
    mesh, x = _plate()
    p = np.array([0.73, 0.41])
    load = point_load(mesh.nodes, mesh.triangles, p, 1000.0)
    f, m = resultant(x, load)
    assert math.isclose(f[2], -1000.0, rel_tol=1e-12)
    assert np.allclose([-m[1] / f[2], m[0] / f[2]], p, atol=1e-12)


def test_point_load_outside_the_sheet_is_refused():
    mesh, _ = _plate()
    with pytest.raises(InvalidParameterError, match="^person_at: must lie on the flat sheet"):
        point_load(mesh.nodes, mesh.triangles, np.array([2.5, 0.5]), 1000.0)


def test_grid_points_lie_on_the_sheet():
    mesh, _ = _plate()
    pts = grid_points(mesh.nodes, mesh.triangles, 4)
    assert len(pts) == 16


def test_combinations_follow_en_1990():
    """Per direction: uplift and down-pressure in EQU, STR and SLS; with snow,
    the two leading-action STR cases and an SLS one; the person alone."""
    base = combinations([0.0, 90.0], snow=False, person=False)
    assert len(base) == 2 + 2 * 6
    full = combinations([0.0, 90.0], snow=True, person=True)
    assert len(full) == 2 + 2 * 9 + 2 + 2
    names = {c.name for c in full}
    assert "STR 1.35G + 1.5W+0 + 0.75S" in names
    assert "STR 1.35G + 1.5S + 0.9W+90" in names
    assert "EQU 0.9G + 1.5W-90" in names
    assert "STR G + 1.5W-0" in names
    for c in full:
        if "P" in c.factor:
            assert set(c.factor) == {"G", "P"}
        if any(k.startswith("W-") for k in c.factor):
            assert "S" not in c.factor


@pytest.mark.parametrize(
    ("changes", "name"),
    [
        ({"wind_speed": -3.0}, "wind_speed"),
        ({"wind_speed": None}, "wind_speed"),
        ({"terrain": "V"}, "terrain"),
        ({"snow_kPa": -1.0}, "snow_kPa"),
        ({"cf_up": 0.3}, "cf_up"),
        ({"friction": 0.0}, "friction"),
        ({"supports": "glued"}, "supports"),
        ({"directions": 0}, "directions"),
        ({"person_kN": float("nan")}, "person_kN"),
        ({"velocity_pressure_kPa": 0.5}, "velocity_pressure_kPa"),
    ],
)
def test_spec_refuses_bad_values(changes, name):
    values = {"wind_speed": 25.0, **changes}
    with pytest.raises(InvalidParameterError) as err:
        LoadSpec(**values)
    assert err.value.parameter == name
