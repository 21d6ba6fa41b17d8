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
    build_design,
)
from onefold_cad.geometry.bend import (
    MAX_SETBACK_FRACTION,
    BendReference,
    bend_model,
    blank_move,
    check_bends,
    crease_bends,
)
from tests.hand_bend import FACES, S_TABLE, hand_bend

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


@pytest.mark.parametrize("case", ["up", "down"])
@pytest.mark.parametrize("surface", SURFACES)
def test_reference_place_from_the_folded_geometry(case, surface):
    """Which face is inside each bend, read off the folded surface itself: the top
    face is inside when its normal points into the V the two sides make. That face's
    offset from the reference surface (FACES) is s t."""
    if case == "up":
        design = Design("u", FrameCurve(30, 30, 0, 100, 90), Sheet.rectangle(3048, 7315.2, 0.5))
    else:
        design = Design("d", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper")
    folded = build_design(design)
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
        cos = float(n_up @ n_lo) / (np.linalg.norm(n_up) * np.linalg.norm(n_lo))
        assert math.degrees(math.acos(cos)) == pytest.approx(half.fold_angle_deg, abs=1e-3)
    if case == "down":
        assert [h.bend for h in folded.crease] == ["DOWN", "UP"]


# -- the limits ---------------------------------------------------------------------
@cache
def _diagonal(alpha: float) -> tuple[Design, object]:
    design = Design("diag", FrameCurve(alpha, alpha, 0, 100, 90), Sheet.rectangle(3048, 7315.2))
    return design, build_design(design)


def test_default_template_passes_every_limit():
    design, folded = _diagonal(30.0)
    mat = Material(thickness=3.57, bend_radius=6.0, k_factor=0.44, relief_hole=0)
    assert check_bends(design.with_changes(material=mat), folded) == ()


def test_zero_thickness_has_no_limits():
    design, folded = _diagonal(85.0)
    assert check_bends(design, folded) == ()


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
    problems = check_bends(design.with_changes(material=mat), folded)
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
    kinds = {p.kind for p in check_bends(design.with_changes(material=mat), folded)}
    assert kinds == {"setback"}


def _table1() -> tuple[FrameCurve, object]:
    frame = FrameCurve(50, 45, 0, 100, 90)
    return frame, build_design(Design("t", frame, Sheet.quadrilateral(300, 300, 300, 300)))


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
    problems = check_bends(design, build_design(design))
    if ratio < 1.0:
        assert problems == ()
    else:
        assert [(p.half, p.kind) for p in problems] == [("plus_x", "corner")]
        assert "(150, 8) mm" in problems[0].message


def _down_material_hand(surface: str, t: float, r: float, k: float) -> tuple[object, dict, dict]:
    sheet = Sheet.quadrilateral(60, 340, 300, 280)
    folded = build_design(Design("d", DOWN_FRAME, sheet, model="paper"))
    plus, minus = (hand_bend(h.fold_angle_deg, h.bend, surface, t, r, k) for h in folded.crease)
    return folded, plus, minus


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
    problems = check_bends(design, build_design(design))
    if eps > 0:
        assert problems == ()
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
    problems = check_bends(design, build_design(design))
    assert [(p.half, p.kind) for p in problems] == [("plus_x", "edge")]
    assert "narrower than its bend zone" in problems[0].message


def test_mean_shift_past_a_crease_end_zone_is_no_limit():
    """INSIDE reference, r = 0, K = 1: minus_x bends UP (s = 0), so its set-back is 0
    and its shift -BA-/2; plus_x bends DOWN (s = 1) with a small shift. Their mean d
    lifts plus_x's crease end -d > BA+/2 from the fold line, out of its own zone: the
    blank bridges from the crease end itself (tests/export/test_flat_pattern.py), the
    width error reports the mismatch, and no limit is passed."""
    t, r, k = 1.0, 0.0, 1.0
    _, plus, minus = _down_material_hand("INSIDE", t, r, k)
    d = (plus["shift"] + minus["shift"]) / 2
    assert -d > plus["ba"] / 2  # by hand: the case this test is about
    mat = Material(thickness=t, bend_radius=r, k_factor=k, sheet_surface="INSIDE", relief_hole=0)
    design = Design("m", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper",
                    material=mat)  # fmt: skip
    assert check_bends(design, build_design(design)) == ()


def test_blank_move_is_the_mean_and_its_errors():
    design = Design("d", DOWN_FRAME, Sheet.quadrilateral(60, 340, 300, 280), model="paper")
    folded = build_design(design)
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
    folded = build_design(design)
    v = np.asarray(design.sheet.vertices)
    inner = [p for i, p in enumerate(v) if i not in (0, design.sheet.minus_x_index)]
    problems = check_bends(design, folded)
    assert [(p.half, p.kind) for p in problems] == [("plus_x", "corner"), ("minus_x", "corner")]
    for p, side in zip(problems, (1.0, -1.0), strict=True):
        near = [q for q in inner if abs(q[1]) <= sb and side * q[0] >= 0]
        closest = min(abs(q[1]) for q in near)
        assert f"lies {closest:.4g} mm from the fold line" in p.message
        assert f"(and {len(near) - 1} more corners)" in p.message
