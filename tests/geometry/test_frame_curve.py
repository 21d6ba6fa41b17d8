"""Every bad input raises a specific error naming the parameter and its range."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    InvalidSheetError,
    Material,
    NoSolutionError,
    Sheet,
    bend_values,
    fold_design,
)
from onefold_cad.fabrication.relief_hole import relief_hole_problem
from onefold_cad.geometry.checks import (
    MAX_LENGTH,
    MAX_SHEET_TO_RADIUS,
    MIN_LENGTH,
    MIN_SHEET_TO_RADIUS,
)
from onefold_cad.geometry.frame_curve import (
    MAX_DESIGN_DIVISIONS,
    MAX_DIVISIONS,
    MIN_ANGLE_DEG,
    arc_geometry,
)
from tests.angles import OPEN_ANGLE, cos_deg, frame_unless_on_end, refused_below_bound

NAN, INF = math.nan, math.inf
UP, DOWN = math.inf, -math.inf


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
        ({"alpha": 50, "beta": 45, "radius": 1e308}, "radius", "[1e-30, 1e+30]"),
        ({"alpha": 50, "beta": 45, "radius": 1e-300}, "radius", "[1e-30, 1e+30]"),
        ({"alpha": 50, "beta": 45, "divisions": 10_000_000}, "divisions", "[1, 100000]"),
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


def test_a_changed_frame_solves_with_the_geometry_of_its_new_values() -> None:
    # the frame keeps the geometry its validation computed: a copy with other
    # values must not carry the old one (L+ = R cos(alpha) - h_c by hand)
    f = FrameCurve(50, 45, 10, 100, 20).with_changes(alpha=60, h_c=-20, radius=50)
    g = arc_geometry(f)
    assert g.alpha == math.radians(60) and g.radius == 50
    assert g.l_plus == pytest.approx((50 * 0.5 + 20) / 50, rel=1e-15)
    assert g.l_minus == pytest.approx((50 * 0.5 - 20) / 50, rel=1e-15)
    assert g.sin_beta == pytest.approx(math.sqrt(0.5), rel=1e-15)


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


# -- caps and magnitude bounds: just inside passes, just outside names the parameter ----
@pytest.mark.parametrize("name", ["alpha", "beta"])
def test_angle_floor_boundary(name: str) -> None:
    other = {"alpha": 50.0, "beta": 45.0}
    assert getattr(FrameCurve(**{**other, name: MIN_ANGLE_DEG}), name) == MIN_ANGLE_DEG
    for bad in (np.nextafter(MIN_ANGLE_DEG, DOWN), 5e-324):
        with pytest.raises(InvalidParameterError, match=f"^{name}: must be in \\(0, 90\\) deg and"):
            FrameCurve(**{**other, name: bad})


def test_divisions_cap_boundary() -> None:
    assert FrameCurve(50, 45, divisions=MAX_DIVISIONS).divisions == 100_000
    with pytest.raises(
        InvalidParameterError, match=r"^divisions: must be an integer in \[1, 100000\], got 100001"
    ):
        FrameCurve(50, 45, divisions=MAX_DIVISIONS + 1)
    sheet = Sheet.quadrilateral(300, 300, 300, 300)
    Design("x", FrameCurve(50, 45, divisions=MAX_DESIGN_DIVISIONS), sheet, model="paper")
    with pytest.raises(
        InvalidParameterError,
        match=r"^frame.divisions: must be an integer in \[1, 10000\] in a design, got 10001 "
        r"\(at 10000 the fan is within 5e-8 R",
    ):
        Design("x", FrameCurve(50, 45, divisions=MAX_DESIGN_DIVISIONS + 1), sheet)


def test_cli_help_states_the_caps_the_design_enforces() -> None:
    # the flags' help is written out (the CLI does not import the core to start);
    # it must name the bounds Design and check_magnitudes enforce
    from onefold_cad.flags.design_flags import DESIGN_FLAGS

    helps = {f.dest: f.help for f in DESIGN_FLAGS}
    assert f"[1, {MAX_DESIGN_DIVISIONS}]" in helps["divisions"]
    assert (MIN_SHEET_TO_RADIUS, MAX_SHEET_TO_RADIUS) == (1e-6, 1e6)
    assert "from 1e-6 to 1e6 times the sheet's size" in helps["radius"]


def test_the_fan_at_the_cap_is_within_5e_8_R_of_the_arc() -> None:
    # the cap's reason, derived independently: the largest chord-to-arc gap of
    # 10 000 equal divisions of an arc of at most 360 deg
    sagitta = 1.0 - math.cos(math.pi / MAX_DESIGN_DIVISIONS)
    assert sagitta < 5e-8 < 1e-7


@pytest.mark.parametrize(
    ("radius", "ok"),
    [
        (MAX_LENGTH, True),
        (np.nextafter(MAX_LENGTH, UP), False),
        (MIN_LENGTH, True),
        (np.nextafter(MIN_LENGTH, DOWN), False),
    ],
)
def test_radius_magnitude_boundary(radius: float, ok: bool) -> None:
    if ok:
        assert FrameCurve(50, 45, radius=radius).radius == radius
    else:
        with pytest.raises(InvalidParameterError, match=r"^radius: must be in \[1e-30, 1e\+30\]"):
            FrameCurve(50, 45, radius=radius)


@pytest.mark.parametrize(
    ("size", "ok"),
    [
        (MIN_SHEET_TO_RADIUS, True),  # radius 1
        (np.nextafter(MIN_SHEET_TO_RADIUS, DOWN), False),
        (MAX_SHEET_TO_RADIUS, True),
        (np.nextafter(MAX_SHEET_TO_RADIUS, UP), False),
    ],
)
def test_sheet_to_radius_boundary(size: float, ok: bool) -> None:
    sheet = Sheet.quadrilateral(size, size, size, size)
    assert sheet.size == size
    frame = FrameCurve(50, 45, radius=1.0)
    if ok:
        Design("x", frame, sheet)
    else:
        with pytest.raises(
            InvalidParameterError, match=r"^frame.radius: must be within \[1e-06, 1e\+06\] times"
        ):
            Design("x", frame, sheet)


@pytest.mark.parametrize("key", ["thickness", "bend_radius", "kerf", "relief_hole"])
def test_material_magnitude_boundary(key: str) -> None:
    frame, sheet = FrameCurve(50, 45, radius=1e29), Sheet.quadrilateral(*[1e30] * 4)
    base = {"relief_hole": 0.0} if key != "relief_hole" else {}
    Design("x", frame, sheet, material=Material(**{**base, key: 0.0}))
    Design("x", frame, sheet, material=Material(**{**base, key: 5e-324}))  # no lower bound
    Design("x", frame, sheet, material=Material(**{**base, key: MAX_LENGTH}))
    with pytest.raises(
        InvalidParameterError, match=f"^material.{key}: must be in \\[0, 1e\\+30\\]"
    ):
        Design("x", frame, sheet, material=Material(**{**base, key: np.nextafter(MAX_LENGTH, UP)}))
    with pytest.raises(InvalidParameterError, match=f"^material.{key}: must be in"):
        Design("x", frame, sheet, material=Material(**{**base, key: 1e300}))


@st.composite
def in_bounds_designs(draw: st.DrawFn) -> Design:
    """Designs over the whole allowed magnitude range: R in [1e-30, 1e30], the
    sheet from 1e-6 to 1e6 R (inside the absolute bounds), H anywhere inside
    the f-line, both models; alpha and beta anywhere in (0, 90) deg from the
    angle bound MIN_ANGLE_DEG up (below it: refused, tests/angles.py)."""
    radius = 10.0 ** draw(st.floats(-30.0, 30.0))
    lo = max(math.log10(MIN_SHEET_TO_RADIUS), math.log10(5.0 * MIN_LENGTH / radius))
    hi = min(math.log10(MAX_SHEET_TO_RADIUS), math.log10(MAX_LENGTH / radius))
    size = radius * 10.0 ** draw(st.floats(lo + 1e-9, hi - 1e-9))  # the edges: tests above
    alpha, beta = draw(OPEN_ANGLE), draw(OPEN_ANGLE)
    frac = draw(st.floats(-1.0, 1.0, exclude_min=True, exclude_max=True))
    model = draw(st.sampled_from(["paper", "exact"]))
    sides = [size] + [size * draw(st.floats(0.2, 1.0)) for _ in range(3)]  # the size is `size`
    n = draw(st.integers(1, 400))
    assume(not refused_below_bound(alpha, beta, lambda: FrameCurve(alpha, beta, 0.0, radius, n)))
    half = radius * cos_deg(alpha)
    h_c = frac * half
    frame = frame_unless_on_end(lambda: FrameCurve(alpha, beta, h_c, radius, n), h_c, half)
    assume(frame is not None)  # H on an end of the f-line by rounding: refused
    assert frame is not None
    sheet = Sheet.quadrilateral(*sides)
    return Design("x", frame, sheet, model=model)


@settings(max_examples=150, deadline=None)
@given(in_bounds_designs())
def test_in_bounds_designs_fold_to_finite_numbers_without_warnings(design: Design) -> None:
    # The bounds' promise: inside them nothing overflows, divides by zero or
    # turns NaN (warnings are errors here); the answer is a finite fold or a
    # NoSolutionError.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            folded = fold_design(design)
        except NoSolutionError:
            return
        assert math.isfinite(folded.solution.apex_height)
        assert np.all(np.isfinite(folded.rulings_3d))
        assert all(math.isfinite(c.fold_angle_deg) for c in folded.crease)
