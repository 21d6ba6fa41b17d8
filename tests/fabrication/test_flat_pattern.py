"""The flat blank against the bend model, measured independently.

Expected values come from :mod:`tests.hand_bend` (the textbook formulas
and a 2D cross-section built as geometry), never from the code under test.
"""

from __future__ import annotations

import math
import subprocess
import sys
import tempfile
from functools import cache
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from hypothesis import assume, event, given, settings
from hypothesis import strategies as st

from onefold_cad import (
    Design,
    FabricationError,
    FrameCurve,
    InvalidParameterError,
    Material,
    NoSolutionError,
    Sheet,
    fold_design,
)
from onefold_cad.export.dxf import export_design_dxf
from onefold_cad.fabrication.bend_checks import check_bends
from onefold_cad.fabrication.flat_pattern import flat_pattern
from tests.hand_bend import hand_bend, neutral_length, polygon_span_at

SURFACES = ("INSIDE", "MID", "OUTSIDE")
DIAGONAL = Sheet.rectangle(3048.0, 7315.2, 0.5)  # 10 x 24 ft, folded on its diagonal


def dxf_outline(path: Path) -> np.ndarray:
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    polys = [e for e in doc.modelspace() if e.dxf.layer == "CUT" and e.dxftype() == "LWPOLYLINE"]
    assert len(polys) == 1 and polys[0].closed
    return np.array([(p[0], p[1]) for p in polys[0].get_points("xy")], dtype=float)


def line_distance(p: np.ndarray, a: np.ndarray, d: np.ndarray) -> float:
    """Signed distance of ``p`` from the line through ``a`` along unit ``d``."""
    v = p - a
    return float(v[0] * d[1] - v[1] * d[0])


#: K-factor per reference surface that keeps the DOWN design's blank within every limit
#: (the halves fold alike, one UP, one DOWN: for INSIDE/OUTSIDE their shifts differ by
#: t tan(psi/2), which the width limit allows only for small psi; the fan's one ruling fold
#: per side is not compensated, 2 x its shift must stay under 0.1 t too)
DOWN_K = {"INSIDE": 1.0, "MID": 0.33, "OUTSIDE": 0.0}


@cache
def _down_design(surface: str) -> tuple[Design, object]:
    """The paper model at alpha 5, beta 10, H at half the half chord towards +x, 2
    divisions: plus_x bends DOWN, minus_x UP, both about 9.96 deg (the same DOWN
    geometry as test_dxf.py's hand derivation, on a fan that passes the limits)."""
    frame = FrameCurve(5.0, 10.0, 0.5 * 100.0 * math.cos(math.radians(5.0)), 100.0, 2)
    mat = Material(thickness=1.0, bend_radius=0.0, k_factor=DOWN_K[surface], sheet_surface=surface)
    sheet = Sheet.quadrilateral(60.0, 340.0, 300.0, 280.0)  # H near the +x end
    design = Design(f"down-{surface}", frame, sheet, model="paper", material=mat)
    return design, fold_design(design)


@cache
def _up_design(surface: str) -> tuple[Design, object]:
    """Table 1's square at alpha 45, beta 0: both halves UP, symmetric."""
    mat = Material(thickness=3.0, bend_radius=4.0, k_factor=0.35, sheet_surface=surface)
    sheet = Sheet.quadrilateral(300.0, 300.0, 300.0, 300.0)
    design = Design(f"up-{surface}", FrameCurve(50, 45, 0, 100, 90), sheet, material=mat)
    return design, fold_design(design)


@pytest.mark.parametrize("surface", SURFACES)
@pytest.mark.parametrize("case", ["up", "down"])
def test_blank_width_across_each_half_is_the_neutral_line_of_its_cross_section(
    tmp_path, surface, case
):
    """The DXF blank's width across each crease half, read back with ezdxf, against
    the neutral line's length of a 2D cross-section of the bent sheet (flange + arc
    + flange) built as geometry. Each side moves rigidly, by the mean of the two
    halves' shifts: the blank's width at x across half h is the designed width
    minus the mean of both halves' reductions (designed width - neutral length)."""
    design, folded = (_up_design if case == "up" else _down_design)(surface)
    assert {h.bend for h in folded.crease} == ({"UP"} if case == "up" else {"UP", "DOWN"})
    m = design.material
    path = export_design_dxf(design, tmp_path / "b.dxf", folded)
    blank = design.sheet.to_sheet.inverse(dxf_outline(path))
    sheet = np.asarray(design.sheet.vertices)
    reductions, spans = [], []
    for half, length in zip(folded.crease, design.sheet.crease_lengths, strict=True):
        x = (0.4 if half.name == "plus_x" else -0.4) * length
        lo, hi = polygon_span_at(sheet, x)
        neutral = neutral_length(
            half.fold_angle_deg, half.bend, surface, m.thickness, m.bend_radius, m.k_factor,
            hi, -lo,
        )  # fmt: skip
        reductions.append((hi - lo) - neutral)
        spans.append((x, lo, hi))
    for x, lo, hi in spans:
        b_lo, b_hi = polygon_span_at(blank, x)
        expected = (hi - lo) - (reductions[0] + reductions[1]) / 2.0
        assert b_hi - b_lo == pytest.approx(expected, rel=1e-9)
        assert hi - b_hi == pytest.approx(b_lo - lo, rel=1e-9)  # both sides moved alike


@pytest.mark.parametrize("surface", SURFACES)
def test_done_when_10x24ft_diagonal_shift_per_side(tmp_path, surface):
    """10 x 24 ft sheet on its diagonal, t 3.57, r 6, K 0.44: the DXF's shift per side
    (designed corner's distance from the diagonal minus the blank corner's) equals
    (r + s t) tan(psi/2) - BA/2 within 1e-3 mm (s = 0, 1/2, 1 for an UP bend)."""
    mat = Material(thickness=3.57, bend_radius=6.0, k_factor=0.44, sheet_surface=surface)
    design = Design(f"diag-{surface}", FrameCurve(30, 30, 0, 100, 90), DIAGONAL, material=mat)
    folded = fold_design(design)
    assert [h.bend for h in folded.crease] == ["UP", "UP"]
    psi = math.radians(folded.crease[0].fold_angle_deg)
    s = {"INSIDE": 0.0, "MID": 0.5, "OUTSIDE": 1.0}[surface]
    expected = (6.0 + s * 3.57) * math.tan(psi / 2.0) - psi * (6.0 + 0.44 * 3.57) / 2.0
    blank = dxf_outline(export_design_dxf(design, tmp_path / "d.dxf", folded))
    d = np.array([3048.0, 7315.2]) / math.hypot(3048.0, 7315.2)
    for corner in (np.array([3048.0, 0.0]), np.array([0.0, 7315.2])):
        moved = blank[np.argmin(np.linalg.norm(blank - corner, axis=1))]
        shift = abs(line_distance(corner, np.zeros(2), d)) - abs(
            line_distance(moved, np.zeros(2), d)
        )
        assert shift == pytest.approx(expected, abs=1e-3)
        assert abs(float((moved - corner) @ d)) < 1e-9 * 7315.2  # moved across the fold only


def test_patkau_reproducer_is_refused_and_none_writes_the_designed_outline(tmp_path):
    """alpha = beta = 85 folds the 10 x 24 ft sheet to ~179 deg: its set-back is over
    the limit, so the compensated blank is refused naming the half and its angle; the
    uncompensated one is written on request and says so."""
    mat = Material(thickness=3.57, bend_radius=6.0, k_factor=0.44, sheet_surface="MID")
    design = Design("p85", FrameCurve(85, 85, 0, 100, 90), DIAGONAL, material=mat)
    folded = fold_design(design)
    psi = folded.crease[0].fold_angle_deg
    assert psi > 179.0
    target = tmp_path / "p85.dxf"
    with pytest.raises(FabricationError) as info:
        export_design_dxf(design, target, folded)
    assert info.value.parameter == "bend_radius"
    msg = str(info.value)
    assert "plus_x" in msg and f"{psi:.2f} deg" in msg and "\n" not in msg
    sb = (6.0 + 0.5 * 3.57) * math.tan(math.radians(psi) / 2.0)
    assert f"{sb:.4g} mm" in msg
    assert list(tmp_path.iterdir()) == []
    path = export_design_dxf(design, target, folded, compensation="none")
    out = dxf_outline(path)
    assert np.allclose(out, DIAGONAL.to_sheet.apply(DIAGONAL.vertices), atol=1e-9 * 7315.2)
    notes = [e.dxf.text for e in ezdxf.readfile(path).modelspace() if e.dxftype() == "TEXT"]
    assert any("compensation: NONE" in t for t in notes)
    assert any(t.startswith("limit passed: plus_x") for t in notes)
    assert flat_pattern(design, folded, "none").compensation == "none"


def test_mean_shift_past_a_zone_bridges_from_the_moved_crease_end():
    """Table 1 row 4 (H_c 68), exact model, both halves UP, INSIDE reference, r = 0,
    K = 1: each half's set-back is 0 and its shift -BA/2, so the mean shift d lies below
    -BA+/2 (plus_x folds less) and plus_x's crease end moves -d from the fold line, past
    its own zone's edge: the outline bridges straight across at the moved crease end,
    the zone lines end on that bridge and the width error across plus_x is 2 (shift+ -
    d), within the width limit (K t (psi- - psi+) / 2 < 0.1 t)."""
    frame = FrameCurve(32, 34, 68, 100, 90)
    mat = Material(thickness=1.0, bend_radius=0.0, k_factor=1.0, sheet_surface="INSIDE")
    design = Design("m", frame, Sheet.quadrilateral(103, 201, 300, 96), material=mat)
    folded = fold_design(design)
    assert [h.bend for h in folded.crease] == ["UP", "UP"]
    hb = [hand_bend(h.fold_angle_deg, h.bend, "INSIDE", 1.0, 0.0, 1.0) for h in folded.crease]
    d = (hb[0]["shift"] + hb[1]["shift"]) / 2
    assert -d > hb[0]["ba"] / 2
    p = flat_pattern(design, folded)
    for q in ((103.0, -d), (103.0, d)):
        assert np.min(np.linalg.norm(p.outline - q, axis=1)) < 1e-12 * 300
    zone = p.halves[0].zone
    c = hb[0]["ba"] / 2
    assert np.allclose(zone[:, 1], [[103.0, c], [103.0, -c]], atol=1e-12 * 300)
    assert np.allclose(p.halves[0].end, [103.0, 0.0], atol=1e-12 * 300)
    assert p.move.errors[0] == pytest.approx(2 * (hb[0]["shift"] - d), rel=1e-12)


def test_compensation_is_checked():
    design, folded = _up_design("MID")
    with pytest.raises(InvalidParameterError, match="^compensation: "):
        flat_pattern(design, folded, "round")


def test_flat_pattern_and_bend_model_import_no_cad_library():
    code = (
        "import sys, onefold_cad.fabrication.flat_pattern, onefold_cad.geometry.bend_model\n"
        "top = {m.split('.')[0] for m in sys.modules}\n"
        "heavy = {'ezdxf', 'build123d', 'OCP', 'matplotlib'} & top\n"
        "print(sorted(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


@settings(max_examples=40, deadline=None)
@given(
    alpha=st.floats(0.0, 90.0, exclude_min=True, exclude_max=True, allow_subnormal=False),
    beta=st.floats(0.0, 90.0, exclude_min=True, exclude_max=True, allow_subnormal=False),
    hc=st.floats(-1.0, 1.0, exclude_min=True, exclude_max=True),
    radii=st.lists(st.floats(40.0, 400.0), min_size=6, max_size=6),
    jitter=st.lists(st.floats(-0.4, 0.4), min_size=6, max_size=6),
    t=st.floats(0.01, 6.0),
    r=st.floats(0.0, 12.0),
    k=st.floats(0.0, 1.0),
    surface=st.sampled_from(SURFACES),
)
def test_blank_corners_where_the_bend_model_puts_them(
    alpha, beta, hc, radii, jitter, t, r, k, surface
):
    """Over the whole open range of alpha, beta, h_c: a design the limits accept has
    every sheet corner moved across the fold line by the mean of the two halves' hand
    shifts, and every other outline point on a moved edge at BA/2 of its half; a
    design they reject raises FabricationError, and compensation 'none' still writes
    the designed outline (but for a crease folded onto itself, beta within rounding
    of 90 deg, which has no bend model at all: hypothesis found alpha 71, beta
    89.99999999999997)."""
    try:
        frame = FrameCurve(alpha, beta, hc * 100.0 * math.cos(math.radians(alpha)), 100.0, 90)
    except InvalidParameterError:  # |h_c| rounded onto the open range's end
        assume(False)
    ang = (np.arange(6) + 0.5 + np.array(jitter)) * (2 * math.pi / 6)
    pts = np.stack([np.cos(ang), np.sin(ang)], axis=1) * np.array(radii)[:, None]
    mat = Material(thickness=t, bend_radius=r, k_factor=k, sheet_surface=surface, relief_hole=0)
    design = Design("rnd", frame, Sheet.polygon(pts), material=mat)
    try:
        folded = fold_design(design)
    except (NoSolutionError, InvalidParameterError):  # e.g. H on the f-line's end to 40 digits
        assume(False)
    assert all(math.isfinite(h.fold_angle_deg) for h in folded.crease)
    v = np.asarray(design.sheet.vertices)
    size = design.sheet.size
    problems = check_bends(folded, design.material, design.units)
    event("refused: " + ", ".join(sorted({q.kind for q in problems})) if problems else "accepted")
    if problems:
        with pytest.raises(FabricationError) as info:
            flat_pattern(design, folded)
        assert problems[0].message in str(info.value)
        if problems[0].kind == "closed":  # folded onto itself: no bend model to write
            with pytest.raises(FabricationError, match="^beta: "):
                flat_pattern(design, folded, "none")
            return
        with tempfile.TemporaryDirectory() as tmp:
            path = export_design_dxf(design, Path(tmp) / "n.dxf", folded, compensation="none")
            out = dxf_outline(path)
        assert np.allclose(out, design.sheet.to_sheet.apply(v), atol=1e-9 * size)
        return
    pattern = flat_pattern(design, folded)
    hb = [hand_bend(h.fold_angle_deg, h.bend, surface, t, r, k) for h in folded.crease]
    d = (hb[0]["shift"] + hb[1]["shift"]) / 2.0
    out = design.sheet.to_sheet.inverse(pattern.outline)
    corners = np.array([p for i, p in enumerate(v) if i not in (0, design.sheet.minus_x_index)])
    moved = corners - np.sign(corners[:, 1])[:, None] * np.array([0.0, d])
    for q in moved:
        assert np.min(np.linalg.norm(out - q, axis=1)) < 1e-9 * size
    # a crease end the mean shift takes out of its half's zone starts the bridge itself
    lp, lm = design.sheet.crease_lengths
    for length, b in ((lp, hb[0]), (-lm, hb[1])):
        if -d > b["ba"] / 2:
            moved = np.vstack([moved, [(length, -d), (length, d)]])
    edges = np.stack([v, np.roll(v, -1, axis=0)], axis=1)
    for q in out:
        if np.min(np.linalg.norm(moved - q, axis=1)) < 1e-9 * size:
            continue
        half = 0 if q[0] > 0 else 1
        assert abs(q[1]) == pytest.approx(hb[half]["ba"] / 2.0, abs=1e-9 * size)
        dist = []  # from the sheet's edges on q's side, moved with that side
        for side in (1.0, -1.0):
            if side * q[1] >= 0.0:
                mine = edges[np.sign(edges[:, :, 1]).sum(axis=1) * side > 0] - [0.0, side * d]
                dist += [abs(line_distance(q, a, (b - a) / np.linalg.norm(b - a))) for a, b in mine]
        assert min(dist) < 1e-9 * size
    assert len(v) <= len(out) <= len(v) + 2  # the bridges replace the two crease ends
