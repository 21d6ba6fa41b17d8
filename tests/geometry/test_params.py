"""Every bad input raises a specific error naming the parameter and its range."""

from __future__ import annotations

import math

import pytest

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    InvalidSheetError,
    Material,
    Sheet,
    bend_values,
)
from onefold_cad.design import relief_hole_problem

NAN, INF = math.nan, math.inf


@pytest.mark.parametrize(
    ("kwargs", "param", "allowed"),
    [
        ({"alpha": 0, "beta": 45}, "alpha", "(0, 90)"),
        ({"alpha": 90, "beta": 45}, "alpha", "(0, 90)"),
        ({"alpha": -10, "beta": 45}, "alpha", "(0, 90)"),
        ({"alpha": 50, "beta": 0}, "beta", "(0, 90)"),
        ({"alpha": 50, "beta": 95}, "beta", "(0, 90)"),
        ({"alpha": NAN, "beta": 45}, "alpha", "finite"),
        ({"alpha": 50, "beta": INF}, "beta", "finite"),
        ({"alpha": 50, "beta": 45, "h_c": NAN}, "h_c", "finite"),
        ({"alpha": 60, "beta": 45, "h_c": 60.0}, "h_c", "|h_c| < radius*cos(alpha)"),
        ({"alpha": 60, "beta": 45, "h_c": -50.1}, "h_c", "(-50, 50)"),
        ({"alpha": 50, "beta": 45, "radius": 0}, "radius", "> 0"),
        ({"alpha": 50, "beta": 45, "radius": -5}, "radius", "> 0"),
        ({"alpha": 50, "beta": 45, "radius": NAN}, "radius", "finite"),
        ({"alpha": 50, "beta": 45, "divisions": 0}, "divisions", "integer in [1, "),
        ({"alpha": 50, "beta": 45, "divisions": 2.5}, "divisions", "integer"),
        ({"alpha": 50, "beta": 45, "divisions": "20"}, "divisions", "integer"),
        ({"alpha": 50, "beta": 45, "divisions": True}, "divisions", "integer"),
        ({"alpha": "50", "beta": 45}, "alpha", "finite number"),
    ],
)
def test_bad_frame_inputs(kwargs: dict, param: str, allowed: str) -> None:
    with pytest.raises(InvalidParameterError) as err:
        FrameCurve(**kwargs)
    assert err.value.parameter == param
    assert str(err.value).startswith(f"{param}: ")
    assert allowed in str(err.value)
    assert isinstance(err.value, ValueError)


def test_good_frame_is_kept() -> None:
    f = FrameCurve(50, 45, 10, 100, 20.0)
    assert f.divisions == 20 and isinstance(f.divisions, int)
    assert f.half_chord == pytest.approx(100 * math.cos(math.radians(50)))
    with pytest.raises(InvalidParameterError, match="alpha"):
        f.with_changes(alpha=95)


@pytest.mark.parametrize(
    ("args", "param"),
    [
        ((0, 1, 1, 1), "x_plus"),
        ((1, -1, 1, 1), "x_minus"),
        ((1, 1, NAN, 1), "y_plus"),
        ((1, 1, 1, INF), "y_minus"),
    ],
)
def test_bad_quadrilateral(args: tuple, param: str) -> None:
    with pytest.raises(InvalidParameterError, match=f"^{param}: must be"):
        Sheet.quadrilateral(*args)


@pytest.mark.parametrize(
    ("args", "param", "allowed"),
    [
        ((0, 10, 0.5), "width", "> 0"),
        ((10, -1, 0.5), "height", "> 0"),
        ((10, 10, 0.0), "apex_fraction", "(0, 1)"),
        ((10, 10, 1.0), "apex_fraction", "(0, 1)"),
        ((10, 10, NAN), "apex_fraction", "finite"),
    ],
)
def test_bad_rectangle(args: tuple, param: str, allowed: str) -> None:
    with pytest.raises(InvalidParameterError) as err:
        Sheet.rectangle(*args)
    assert err.value.parameter == param and allowed in str(err.value)


@pytest.mark.parametrize(
    ("points", "message"),
    [
        ([(1, 0), (0, 1)], "at least 3 vertices"),
        ([(1, 0), (0, 1), (NAN, 0), (0, -1)], "finite"),
        ([(2, 0), (-1, 1), (1, 1), (-2, -1), (2, -1)], "self-intersects"),  # bow tie
        ([(1, 1), (2, 1), (2, 2), (1, 2)], "strictly inside"),  # H outside
        ([(1, 0), (0, 1), (-1, 0), (0, 0)], "strictly inside"),  # H on a vertex
        ([(1, 0), (1, 1), (-1, 1), (-1, 0)], "strictly inside"),  # H on an edge
        ([(-5, -1), (1, -1), (1, 1), (-3, 1), (-3, 5), (-5, 5)], "star-shaped"),  # L, H in an arm
        ([(3, -1), (3, 3), (-3, 3), (-3, -1), (-1, -1), (-1, 1), (1, 1), (1, -1)], "inside"),
        ([(1, 0), (1, 0), (0, 1), (-1, 0)], "coincide"),
        ("not points", "(x, y) pairs"),
    ],
)
def test_bad_polygons(points: object, message: str) -> None:
    with pytest.raises(InvalidSheetError) as err:
        Sheet.polygon(points)
    assert err.value.parameter == "polygon"
    assert message in str(err.value)


def test_polygon_is_normalised() -> None:
    # clockwise input, closed, no vertex on the x axis: becomes CCW with the crossings inserted
    pts = [(2, 1), (2, -1), (-1, -2), (-1, 2), (2, 1)]
    s = Sheet.polygon(pts[::-1])
    v = s.vertices
    assert v[0, 1] == 0 and v[0, 0] == pytest.approx(2)
    assert v[s.minus_x_index, 1] == 0 and v[s.minus_x_index, 0] == pytest.approx(-1)
    assert s.area > 0
    assert s.area == pytest.approx(3 * 4 - 0.5 * 3 * 1 * 2)  # trapezoid (2,+-1)..(-1,+-2)
    with pytest.raises(ValueError):
        v[0, 0] = 5.0  # read-only


def test_rectangle_frames_roundtrip() -> None:
    s = Sheet.rectangle(3048.0, 7315.2, 0.4)
    corners = s.to_sheet.apply(s.vertices)
    assert {tuple(c) for c in corners.round(9)} == {(0, 0), (3048, 0), (3048, 7315.2), (0, 7315.2)}
    assert s.area == pytest.approx(3048 * 7315.2, rel=1e-12)
    assert s.to_sheet.apply([[0.0, 0.0]])[0] == pytest.approx([0.4 * 3048, 0.4 * 7315.2])
    d = math.hypot(3048, 7315.2)
    assert s.crease_lengths == pytest.approx((0.6 * d, 0.4 * d))


def test_ray_lengths_are_exact() -> None:
    s = Sheet.quadrilateral(103, 201, 300, 96)
    psi = [0, math.pi / 2, math.pi, -math.pi / 2]
    assert s.ray_lengths(psi) == pytest.approx([103, 300, 201, 96], rel=1e-15)
    # a ray at 45 deg meets x/103 + y/300 = 1
    r = s.ray_lengths([math.pi / 4])[0]
    assert r * math.cos(math.pi / 4) / 103 + r * math.sin(math.pi / 4) / 300 == pytest.approx(1)


@pytest.mark.parametrize(
    ("kwargs", "param"),
    [
        ({"thickness": -1}, "thickness"),
        ({"bend_radius": -0.5}, "bend_radius"),
        ({"k_factor": 1.5}, "k_factor"),
        ({"k_factor": -0.1}, "k_factor"),
        ({"kerf": NAN}, "kerf"),
        ({"relief_hole": -2}, "relief_hole"),
        ({"density": 0}, "density"),
        ({"sheet_surface": "TOP"}, "sheet_surface"),
    ],
)
def test_bad_material(kwargs: dict, param: str) -> None:
    with pytest.raises(InvalidParameterError) as err:
        Material(**kwargs)
    assert err.value.parameter == param


def test_relief_hole_must_fit_the_sheet() -> None:
    frame, sheet = FrameCurve(50, 45), Sheet.quadrilateral(10, 10, 10, 10)
    # A fabrication limit, not a geometry one: the design is made, the writers refuse.
    d = Design("x", frame, sheet, material=Material(relief_hole=15))
    problem = relief_hole_problem(d)
    assert problem is not None and problem.parameter == "relief_hole"
    assert str(problem).startswith("relief_hole: diameter 15 mm must be < 14.1421 mm")
    with pytest.raises(InvalidParameterError, match="^name: "):
        Design("bad name/..", frame, sheet)
    with pytest.raises(InvalidParameterError, match="^units: "):
        Design("ok", frame, sheet, units="cubit")
    with pytest.raises(InvalidParameterError, match="^model: "):
        Design("ok", frame, sheet, model="fancy")


def test_bend_values_formulas() -> None:
    m = Material(thickness=2.0, bend_radius=3.0, k_factor=0.4)
    b = bend_values(90.0, m)
    assert b.allowance == pytest.approx(math.pi / 2 * (3 + 0.8))
    assert b.outside_setback == pytest.approx(5.0)
    # MID reference: the setback is the mid-surface's, (r + t/2) tan(psi/2) = 4
    assert b.setback == pytest.approx(4.0)
    assert b.deduction == pytest.approx(8.0 - math.pi / 2 * 3.8)
    with pytest.raises(InvalidParameterError, match="angle_deg"):
        bend_values(180.0, m)
