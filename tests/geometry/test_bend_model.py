"""The bend model and its limits (geometry/bend.py), against hand derivations."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    bend_values,
    fold_design,
)
from onefold_cad.fabrication.bend_checks import (
    MAX_SETBACK_FRACTION,
    MAX_WIDTH_ERROR_FRACTION,
    check_bends,
)
from onefold_cad.geometry.bend_model import BendReference, bend_model, blank_move, crease_bends
from tests.hand_bend import (
    FACES,
    S_TABLE,
    arc_point,
    arc_tangent,
    crease_angle,
    fan_folds,
    hand_bend,
)

SURFACES = ("INSIDE", "MID", "OUTSIDE")
#: paper model, alpha 8.3, beta 85, H at 0.8 of the half chord: plus_x DOWN (71.5 deg),
#: minus_x UP (167.1 deg); derived by hand in tests/export/test_dxf.py
DOWN_FRAME = FrameCurve(8.3, 85.0, 0.8 * 100.0 * math.cos(math.radians(8.3)), 100.0, 4)


@pytest.mark.parametrize("surface", SURFACES)
@pytest.mark.parametrize("direction", ["UP", "DOWN"])
@pytest.mark.parametrize(
    ("psi", "t", "r", "k"),
    [(0.0, 2.0, 3.0, 0.44), (35.0, 0.5, 0.0, 0.0), (90.0, 2.0, 3.0, 0.4), (125.24, 3.57, 6.0, 1.0),
     (179.9, 1.0, 0.5, 0.33)],
)  # fmt: skip
def test_bend_model_is_the_textbook_formulas(surface, direction, psi, t, r, k):
    mat = Material(thickness=t, bend_radius=r, k_factor=k, sheet_surface=surface)
    b = bend_model(psi, direction, mat, half="plus_x")
    hand = hand_bend(psi, direction, surface, t, r, k)
    assert b.s == hand["s"]
    assert b.reference == {0.0: "INSIDE", 0.5: "MID", 1.0: "OUTSIDE"}[hand["s"]]
    for key, field in (("sb", "setback"), ("ba", "allowance"), ("bd", "deduction")):
        assert getattr(b, field) == pytest.approx(hand[key], rel=1e-12, abs=1e-15)
    assert b.shift == pytest.approx(hand["shift"], rel=1e-12, abs=1e-15)
    assert b.outside_setback == pytest.approx((r + t) * math.tan(math.radians(psi) / 2), rel=1e-12)
    assert b.included_deg == pytest.approx(180.0 - psi, abs=1e-12)
    assert b.inside_face == ("top" if direction == "UP" else "bottom")
    assert (b.half, b.direction, b.radius, b.thickness, b.k_factor) == (
        "plus_x", direction, r, t, k
    )  # fmt: skip


def test_zero_thickness_is_a_sharp_crease():
    b = bend_model(120.0, "DOWN", Material(thickness=0.0, bend_radius=5.0))
    assert (b.setback, b.allowance, b.deduction, b.shift, b.radius) == (0, 0, 0, 0, 0)


def test_bend_values_calls_the_model_and_needs_a_direction_off_mid():
    mid = Material(thickness=2.0, bend_radius=3.0, k_factor=0.4)
    assert bend_values(90.0, mid) == bend_model(90.0, "UP", mid)
    down = bend_model(90.0, "DOWN", mid)  # MID: the same numbers either way
    plain = bend_values(90.0, mid)
    assert (down.setback, down.allowance, down.shift) == (
        plain.setback,
        plain.allowance,
        plain.shift,
    )
    inside = mid.with_changes(sheet_surface="INSIDE")
    assert bend_values(90.0, inside, "DOWN").reference is BendReference.OUTSIDE
    with pytest.raises(InvalidParameterError, match="^bend: "):
        bend_values(90.0, inside)
    with pytest.raises(InvalidParameterError, match="^bend: "):
        bend_values(90.0, inside, "SIDEWAYS")
    with pytest.raises(InvalidParameterError, match="^angle_deg: "):
        bend_values(180.0, mid)


def _finite_difference_frames(folded, x: float) -> tuple[np.ndarray, ...]:
    """At the flat point (x, 0) of the crease: the in-surface directions into the +y and
    -y sides and both sides' top normals, by finite differences of the fold map."""
    size = folded.sheet.size
    e = 1e-6 * size
    p0 = folded.map_points([(x, 0.0)])[0]
    into_up = folded.map_points([(x, e)])[0] - p0
    into_lo = folded.map_points([(x, -e)])[0] - p0
    normals = []
    for y in (e, -e):  # top normal = d/dx x d/dy on each side (the fold keeps orientation)
        px = folded.map_points([(x + e, y)])[0] - folded.map_points([(x - e, y)])[0]
        py = folded.map_points([(x, y + 0.5 * e)])[0] - folded.map_points([(x, y - 0.5 * e)])[0]
        normals.append(np.cross(px, py))
    return into_up, into_lo, normals[0], normals[1]


def _crease_normals_by_hand(design, apex) -> list[np.ndarray]:
    """The +y side's top normal along each crease half, from the frame curve: the exact
    cone's tangent plane along the ruling to the arc's end, spanned by P - A and the
    arc's tangent P'; the paper fan's first (last) triangle (A, P_0, P_1) ((A, P_n-1,
    P_n)). Orientation does not matter for the fold angle."""
    f = design.frame
    ends = (-math.radians(f.alpha), math.pi + math.radians(f.alpha))
    point = lambda phi: arc_point(f.alpha, f.beta, f.h_c, f.radius, phi)  # noqa: E731
    if design.model.value == "exact":
        return [np.cross(point(p) - apex, arc_tangent(f.alpha, f.beta, f.radius, p)) for p in ends]
    step = (ends[1] - ends[0]) / f.divisions
    return [
        np.cross(point(ends[0]) - apex, point(ends[0] + step) - apex),
        np.cross(point(ends[1] - step) - apex, point(ends[1]) - apex),
    ]


@pytest.mark.parametrize("case", ["up", "down"])
@pytest.mark.parametrize("surface", SURFACES)
def test_reference_place_from_the_folded_geometry(case, surface):
    """Which face is inside each bend, read off the folded surface itself: the top
    face is inside when its normal points into the V the two sides make. That face's
    offset from the reference surface (FACES) is s t. The fold angle, twice the angle
    between the +y side's top normal along the crease and the plane of symmetry, from
    the frame curve by hand, to 1e-9 deg."""
    if case == "up":
        design = Design("u", FrameCurve(30, 30, 0, 100, 90), Sheet.rectangle(3048, 7315.2, 0.5))
    else:
        design = Design("d", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper")
    folded = fold_design(design)
    mat = Material(thickness=2.0, bend_radius=1.0, sheet_surface=surface)
    for half, b in zip(folded.crease, crease_bends(folded, mat), strict=True):
        x = 0.5 * half.end_flat[0]
        up, lo, n_up, n_lo = _finite_difference_frames(folded, x)
        into = up / np.linalg.norm(up) + lo / np.linalg.norm(lo)  # into the V
        top_inside = float(n_up @ into) > 0.0
        assert float(n_lo @ into) > 0.0 if top_inside else float(n_lo @ into) < 0.0
        assert half.bend == ("UP" if top_inside else "DOWN") == b.direction
        lo_off, hi_off = FACES[surface]
        assert b.s == (hi_off if top_inside else -lo_off)
    by_hand = [crease_angle(n) for n in _crease_normals_by_hand(design, folded.apex)]
    for half, psi in zip(folded.crease, by_hand, strict=True):
        assert half.fold_angle_deg == pytest.approx(psi, abs=1e-9)
    if case == "down":
        assert [h.bend for h in folded.crease] == ["DOWN", "UP"]


# -- the limits ---------------------------------------------------------------------
@cache
def _diagonal(alpha: float) -> tuple[Design, object]:
    design = Design("diag", FrameCurve(alpha, alpha, 0, 100, 90), Sheet.rectangle(3048, 7315.2))
    return design, fold_design(design)


def test_default_template_passes_every_limit():
    design, folded = _diagonal(30.0)
    mat = Material(thickness=3.57, bend_radius=6.0, k_factor=0.44, relief_hole=0)
    assert check_bends(folded, mat, design.units) == ()


def test_zero_thickness_has_no_limits():
    design, folded = _diagonal(85.0)
    assert check_bends(folded, design.material, design.units) == ()


@pytest.mark.parametrize("factor", [1.0 - 1e-6, 1.0 + 1e-6])
def test_setback_limit_is_a_tenth_of_the_narrower_flange(factor):
    """10 x 24 ft sheet, H mid-diagonal: beside each half one side has a corner
    W H / D = 2813 mm away, the other only the edge met by the perpendicular at H,
    W D / (2 H) = 1651 mm away: the narrower flange is 1651 mm."""
    w, h = 3048.0, 7315.2
    depth = w * math.hypot(w, h) / (2.0 * h)
    design, folded = _diagonal(30.0)
    psi = folded.crease[0].fold_angle_deg
    r = factor * MAX_SETBACK_FRACTION * depth / math.tan(math.radians(psi) / 2) - 0.5 * 3.57
    mat = Material(thickness=3.57, bend_radius=r, k_factor=0.44, relief_hole=0)
    problems = check_bends(folded, mat, design.units)
    if factor < 1.0:
        assert problems == ()
        return
    assert [(p.half, p.kind, p.parameter) for p in problems] == [
        ("plus_x", "setback", "bend_radius"), ("minus_x", "setback", "bend_radius")
    ]  # fmt: skip
    sb = (r + 0.5 * 3.57) * math.tan(math.radians(psi) / 2)
    msg = problems[0].message
    assert f"fold angle {psi:.2f} deg" in msg and f"{sb:.4g} mm" in msg and f"{depth:.4g} mm" in msg
    assert "bend_radius <= " in msg and "\n" not in msg


def test_setback_limit_catches_the_fold_near_180_deg():
    design, folded = _diagonal(85.0)
    assert folded.crease[0].fold_angle_deg > 179.0
    mat = Material(thickness=3.57, bend_radius=6.0, k_factor=0.44)
    kinds = {p.kind for p in check_bends(folded, mat, design.units)}
    assert kinds == {"setback"}


def _table1() -> tuple[FrameCurve, object]:
    frame = FrameCurve(50, 45, 0, 100, 90)
    return frame, fold_design(Design("t", frame, Sheet.quadrilateral(300, 300, 300, 300)))


@pytest.mark.parametrize("ratio", [1.0 - 1e-6, 1.0 + 1e-6])
def test_corner_limit_a_corner_closer_than_the_setback(ratio):
    """A symmetric fold moves each side by its own shift SB - BA/2: a corner y from the
    fold line stays out of the bend zone (|y| - shift > BA/2) iff y > SB."""
    frame, ref = _table1()
    psi = ref.crease[0].fold_angle_deg
    t, k, y = 1.0, 0.44, 8.0
    r = ratio * y / math.tan(math.radians(psi) / 2) - 0.5 * t  # SB = ratio y
    sheet = Sheet.polygon([(300, 0), (150, y), (0, 300), (-300, 0), (0, -300)])
    mat = Material(thickness=t, bend_radius=r, k_factor=k, relief_hole=0)
    design = Design("c", frame, sheet, material=mat)
    problems = check_bends(fold_design(design), design.material, design.units)
    if ratio < 1.0:
        assert problems == ()
    else:
        assert [(p.half, p.kind) for p in problems] == [("plus_x", "corner")]
        assert "(150, 8) mm" in problems[0].message


def _down_material_hand(surface: str, t: float, r: float, k: float) -> tuple[object, dict, dict]:
    sheet = Sheet.quadrilateral(60, 340, 300, 280)
    folded = fold_design(Design("d", DOWN_FRAME, sheet, model="paper"))
    plus, minus = (hand_bend(h.fold_angle_deg, h.bend, surface, t, r, k) for h in folded.crease)
    return folded, plus, minus


def _geometric(problems: tuple) -> list:
    """The problems but the width ones (DOWN_FRAME's halves fold to 71 and 167 deg: the
    one rigid blank is far off the bend model across them; tested on their own below)."""
    return [p for p in problems if p.kind != "width"]


@pytest.mark.parametrize("eps", [-0.01, 0.01])
def test_edge_limit_an_edge_passing_over_h_inside_the_wider_zone(eps):
    """Asymmetric fold (BA+ < BA-): both corners next to H clear their own half's zone,
    yet the edge between them passes H at their mean height, inside the wider zone
    unless it clears d + BA-/2 (d: the mean shift). Deep flanges elsewhere keep the
    set-back limit quiet."""
    t, r, k = 0.2, 0.3, 0.44
    _, plus, minus = _down_material_hand("MID", t, r, k)
    d = (plus["shift"] + minus["shift"]) / 2
    c_p, c_m = plus["ba"] / 2, minus["ba"] / 2
    assert c_p < c_m
    y_right = d + c_p + 0.001  # clears the plus zone only
    y_left = d + c_m + 0.001
    y_mid = (y_right + y_left) / 2  # the edge at x = 0
    lift = (d + c_m) - y_mid + eps  # eps < 0: the edge still dips into the minus zone
    pts = [(2000, 0), (1000, 50), (1, y_right + lift), (-1, y_left + lift), (-1000, 50),
           (-2000, 0), (-1000, -300), (1000, -300)]  # fmt: skip
    mat = Material(thickness=t, bend_radius=r, k_factor=k, relief_hole=0)
    design = Design("e", DOWN_FRAME, Sheet.polygon(pts), model="paper", material=mat)
    problems = _geometric(check_bends(fold_design(design), design.material, design.units))
    if eps > 0:
        assert problems == []
    else:
        assert [(p.half, p.kind) for p in problems] == [("minus_x", "edge")]
        assert "passes" in problems[0].message and "from H" in problems[0].message


def test_edge_limit_a_half_whose_sheet_is_narrower_than_its_zone_up_to_h():
    """OUTSIDE reference, r small: plus_x (DOWN, s = 0) has a tiny set-back, minus_x
    (UP, s = 1) a large one, so the mean shift d is far larger than plus_x's own. The
    edge from the plus end rises to a corner beside minus_x; it reaches d + BA+/2
    only past H, so the plus half's bend zone would run over H."""
    t, r, k = 1.0, 0.05, 0.44
    _, plus, minus = _down_material_hand("OUTSIDE", t, r, k)
    d = (plus["shift"] + minus["shift"]) / 2
    corner_y = d + minus["ba"] / 2 + 0.2  # clears minus_x's zone
    x_j = -20.0
    y0 = corner_y * 60 / (60 - x_j)  # the first edge at x = 0
    assert 10 * plus["sb"] < y0 < d + plus["ba"] / 2  # set-back fine, zone not reached at H
    pts = [(60, 0), (x_j, corner_y), (-1000, 200), (-1200, 0), (0, -300)]
    mat = Material(thickness=t, bend_radius=r, k_factor=k, sheet_surface="OUTSIDE", relief_hole=0)
    design = Design("n", DOWN_FRAME, Sheet.polygon(pts), model="paper", material=mat)
    problems = _geometric(check_bends(fold_design(design), design.material, design.units))
    assert [(p.half, p.kind) for p in problems] == [("plus_x", "edge")]
    assert "narrower than its bend zone" in problems[0].message


def test_mean_shift_past_a_crease_end_zone_is_no_geometric_limit_but_a_width_error():
    """INSIDE reference, r = 0, K = 1: minus_x bends UP (s = 0), so its set-back is 0
    and its shift -BA-/2; plus_x bends DOWN (s = 1) with a small shift. Their mean d
    lifts plus_x's crease end -d > BA+/2 from the fold line, out of its own zone: the
    blank would bridge from the crease end itself (tests/export/test_flat_pattern.py)
    and no set-back, corner or edge limit is passed; but the halves' shifts differ by
    far more than 0.1 t, which the width limit refuses, with the hand numbers."""
    t, r, k = 1.0, 0.0, 1.0
    _, plus, minus = _down_material_hand("INSIDE", t, r, k)
    d = (plus["shift"] + minus["shift"]) / 2
    assert -d > plus["ba"] / 2  # by hand: the case this test is about
    mat = Material(thickness=t, bend_radius=r, k_factor=k, sheet_surface="INSIDE", relief_hole=0)
    design = Design("m", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper",
                    material=mat)  # fmt: skip
    problems = check_bends(fold_design(design), design.material, design.units)
    crease = [p for p in problems if p.half in ("plus_x", "minus_x")]
    width = plus["shift"] - minus["shift"]  # across plus_x: 2 (shift+ - d)
    assert width > MAX_WIDTH_ERROR_FRACTION * t  # the blank is too wide across plus_x
    assert [(p.half, p.kind) for p in crease] == [("plus_x", "width")]
    assert f"the blank is {width:+.4g} mm too wide across it and {-width:+.4g} mm" in (
        crease[0].message
    )
    assert {p.kind for p in problems} == {"width"}  # (the rest: the fan's ruling folds)


def _t1d(r: float, t: float = 2.0, k: float = 0.44) -> tuple[Design, object]:
    """Table 1 row 4 (H_c 68: an asymmetric fold, both halves UP), exact model, MID."""
    mat = Material(thickness=t, bend_radius=r, k_factor=k, relief_hole=0)
    design = Design("t1d", FrameCurve(32, 34, 68, 100, 90), Sheet.quadrilateral(103, 201, 300, 96),
                    material=mat)  # fmt: skip
    return design, fold_design(design)


@pytest.mark.parametrize("factor", [1.0 - 1e-6, 1.0 + 1e-6])
def test_width_limit_is_a_tenth_of_the_thickness(factor):
    """Across each half the one rigid blank is shift_own - shift_other wider than the
    bend model asks (each side moves by the mean). By hand that difference is linear in
    r: the radius that makes it exactly 0.1 t (x factor) is refused just past it."""
    t = 2.0
    design, folded = _t1d(0.0, t)
    psi = [h.fold_angle_deg for h in folded.crease]
    assert psi[1] > psi[0]  # minus_x folds more: its shift is larger

    def width(r: float) -> float:  # across minus_x, by hand
        hp, hm = (hand_bend(p, "UP", "MID", t, r, 0.44) for p in psi)
        return hm["shift"] - hp["shift"]

    slope = width(1.0) - width(0.0)
    r_edge = (MAX_WIDTH_ERROR_FRACTION * t - width(0.0)) / slope
    assert r_edge > 0.0 and slope > 0.0
    r = factor * r_edge
    design, folded = _t1d(r, t)
    problems = check_bends(folded, design.material, design.units)
    if factor < 1.0:
        assert problems == ()
        return
    (p,) = problems
    assert (p.half, p.kind, p.parameter) == ("minus_x", "width", "bend_radius")
    assert f"{width(r):+.4g} mm too wide across it" in p.message
    assert f"limit +-{MAX_WIDTH_ERROR_FRACTION * t:.4g} mm" in p.message
    assert f"bend_radius <= {r_edge:.4g}" in p.message and "--compensation none" in p.message


def test_width_limit_names_hc_when_no_bend_radius_helps():
    """The reviewers' reproducer (alpha 5, beta 60, h_c -60, t 10, r 10): the halves fold
    to 115 and 79 deg; by hand the width error across plus_x is +6.72 mm, and already
    at r = 0 it is over 0.1 t, growing with r: only a smaller |h_c| (or no
    compensation) helps."""
    t = 10.0
    mat = Material(thickness=t, bend_radius=10.0, k_factor=0.44, relief_hole=0)
    design = Design("asym", FrameCurve(5, 60, -60, 100, 90),
                    Sheet.quadrilateral(3000, 1000, 2000, 1500), material=mat)  # fmt: skip
    folded = fold_design(design)
    psi = [h.fold_angle_deg for h in folded.crease]

    def width(r: float) -> float:  # across plus_x, by hand
        hp, hm = (hand_bend(p, "UP", "MID", t, r, 0.44) for p in psi)
        return hp["shift"] - hm["shift"]

    assert width(10.0) == pytest.approx(6.72, abs=5e-3)
    assert width(0.0) > MAX_WIDTH_ERROR_FRACTION * t and width(1.0) > width(0.0)
    (p,) = check_bends(folded, design.material, design.units)
    assert (p.half, p.kind, p.parameter) == ("plus_x", "width", "hc")
    assert f"the blank is {width(10.0):+.4g} mm too wide across it" in p.message
    assert "h_c nearer 0" in p.message and "bend_radius <=" not in p.message


def test_ruling_folds_of_the_paper_fan_have_the_width_limit_too():
    """The paper model's fan folds along its division rays, and the blank does not
    compensate those folds: across each the blank is 2 x its shift too wide. DOWN_FRAME's
    4-division fan, t 1, r 1, K 0.44, MID: its ruling folds by hand (from the frame curve
    and the apex), the largest width error first, and how many more pass the limit."""
    t, r, k = 1.0, 1.0, 0.44
    mat = Material(thickness=t, bend_radius=r, k_factor=k, relief_hole=0)
    design = Design("fan", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper",
                    material=mat)  # fmt: skip
    folded = fold_design(design)
    f = DOWN_FRAME
    a = math.radians(f.alpha)
    phi = -a + np.arange(5) * (math.pi + 2 * a) / 4
    pts = [arc_point(f.alpha, f.beta, f.h_c, f.radius, p) for p in phi]
    folds = fan_folds(pts, folded.apex)  # the +y side's; the -y side is its mirror image
    widths = [2 * hand_bend(ang, bend, "MID", t, r, k)["shift"] for ang, bend in folds]
    over = [(abs(w), w, i) for i, w in enumerate(widths) if abs(w) > MAX_WIDTH_ERROR_FRACTION * t]
    _, worst, i = max(over)
    (p,) = [q for q in check_bends(folded, design.material, design.units) if "ruling" in q.half]
    # the -y side's rulings are the +y side's mirror images: either may come first
    assert p.half in (f"+y ruling {i + 1}", f"-y ruling {i + 1}")
    assert (p.kind, p.parameter) == ("width", "divisions")
    assert f"the blank is {worst:+.4g} mm off" in p.message
    assert f"fold angle {folds[i][0]:.2f} deg, {folds[i][1]}" in p.message
    assert f"; {2 * len(over) - 1} more ruling folds past the limit" in p.message


def test_blank_move_is_the_mean_and_its_errors():
    design = Design("d", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper")
    folded = fold_design(design)
    mat = Material(thickness=1.0, bend_radius=1.0, sheet_surface="INSIDE")
    bends = crease_bends(folded, mat)
    hb = [hand_bend(h.fold_angle_deg, h.bend, "INSIDE", 1.0, 1.0, 0.44) for h in folded.crease]
    move = blank_move(bends)
    assert move.shift == pytest.approx((hb[0]["shift"] + hb[1]["shift"]) / 2, rel=1e-12)
    assert move.errors[0] == pytest.approx(hb[0]["shift"] - hb[1]["shift"], rel=1e-12)
    assert move.errors[1] == pytest.approx(hb[1]["shift"] - hb[0]["shift"], rel=1e-12)
    assert move.residual == pytest.approx(abs(hb[0]["shift"] - hb[1]["shift"]) / 2, rel=1e-12)
    none = blank_move(bends, "none")
    assert none.shift == 0.0
    assert none.errors == pytest.approx((2 * hb[0]["shift"], 2 * hb[1]["shift"]), rel=1e-12)
    assert S_TABLE[("INSIDE", "DOWN")] == bends[0].s == 1.0


def test_corners_in_a_zone_are_one_problem_per_half_naming_the_closest():
    """A finely sampled edge running obliquely into a crease end puts many polygon
    corners within SB of the fold line (symmetric fold: |y| <= SB): one problem per half,
    naming the closest corner and how many more there are."""
    frame, ref = _table1()
    psi = ref.crease[0].fold_angle_deg
    t, r, k = 2.0, 3.0, 0.44
    sb = (r + 0.5 * t) * math.tan(math.radians(psi) / 2)
    n = 400
    ang = (np.arange(n) + 0.5) * 2 * math.pi / n
    rad = 200 + 50 * np.sin(7 * ang)
    pts = np.stack([np.cos(ang), np.sin(ang)], axis=1) * rad[:, None]
    mat = Material(thickness=t, bend_radius=r, k_factor=k, relief_hole=0)
    design = Design("fine", frame, Sheet.polygon(pts), material=mat)
    folded = fold_design(design)
    v = np.asarray(design.sheet.vertices)
    inner = [p for i, p in enumerate(v) if i not in (0, design.sheet.minus_x_index)]
    problems = check_bends(folded, design.material, design.units)
    assert [(p.half, p.kind) for p in problems] == [("plus_x", "corner"), ("minus_x", "corner")]
    for p, side in zip(problems, (1.0, -1.0), strict=True):
        near = [q for q in inner if abs(q[1]) <= sb and side * q[0] >= 0]
        closest = min(abs(q[1]) for q in near)
        assert f"lies {closest:.4g} mm from the fold line" in p.message
        assert f"(and {len(near) - 1} more corners)" in p.message
