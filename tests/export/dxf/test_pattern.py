"""Round-trip tests of the DXF flat pattern: write, read back with ezdxf, measure."""

from __future__ import annotations

import datetime
import math
import re
from functools import cache
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from ezdxf.tools.juliandate import juliandate
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import (
    Design,
    FabricationError,
    FrameCurve,
    InvalidParameterError,
    Material,
    Model,
    Sheet,
    Units,
    fold_design,
)
from onefold_cad.export.dxf.notes import flat_pattern_notes
from onefold_cad.export.dxf.pattern import LAYERS, draw_flat_pattern, export_design_dxf
from onefold_cad.export.dxf.preview import render_preview
from onefold_cad.fabrication.bend_checks import check_bends
from onefold_cad.fabrication.flat_pattern import flat_pattern
from onefold_cad.templates import load_template
from tests.hand_bend import fan_folds, hand_bend
from tests.shipped import REPO_TEMPLATES

STAR = [(220, 0), (70, 45), (90, 190), (-30, 80), (-150, 150), (-110, 15), (-200, -50),
        (-45, -60), (30, -170), (75, -35)]  # fmt: skip
SHAPES = {
    # Table 1 of the paper: (h_c, alpha, beta, divisions), quadrilateral (X+, X-, Y+, Y-)
    "t1a": ((50, 45, 0, 100, 90), lambda: Sheet.quadrilateral(300, 300, 300, 300)),
    "t1b": ((50, 45, 0, 100, 20), lambda: Sheet.quadrilateral(300, 300, 300, 300)),
    "t1c": ((32, 34, 0, 100, 90), lambda: Sheet.quadrilateral(300, 300, 300, 300)),
    "t1d": ((32, 34, 68, 100, 90), lambda: Sheet.quadrilateral(103, 201, 300, 96)),
    "rect": ((40, 40, 0, 100, 90), lambda: Sheet.rectangle(400, 250, 0.4)),
    "star": ((32, 34, 20, 100, 90), lambda: Sheet.polygon(STAR)),
}
MATERIALS = {
    "bare": Material(),
    "kerf": Material(kerf=0.5),
    # r 2.5: t1d's asymmetric halves keep the blank within the width limit (r <= 2.67)
    "thick": Material(thickness=2.0, bend_radius=2.5, k_factor=0.44, density=7900.0, name="S235"),
    "thick_kerf": Material(thickness=1.5, bend_radius=1.0, k_factor=0.33, kerf=0.4),
    "thick_inside": Material(
        thickness=2.5, bend_radius=0.0, k_factor=0.5, sheet_surface="INSIDE", relief_hole=12.0
    ),
}
CASES = [(s, m) for s in SHAPES for m in MATERIALS]


@cache
def _design(shape: str, mat: str, model: str = "exact") -> tuple[Design, object]:
    frame, sheet = SHAPES[shape]
    design = Design(f"{shape}_{mat}", FrameCurve(*frame), sheet(), model=model,
                    material=MATERIALS[mat])  # fmt: skip
    return design, fold_design(design)


def write_read(tmp_path: Path, design: Design, folded=None, **kw) -> ezdxf.document.Drawing:
    path = export_design_dxf(design, tmp_path / f"{design.name}.dxf", folded, **kw)
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    assert not auditor.has_errors, auditor.errors
    return doc


# -- measuring helpers (independent of the code under test) ----------------------------
def shoelace(p: np.ndarray) -> float:
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]))


def perimeter(p: np.ndarray) -> float:
    return float(np.sum(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)))


def dist_to_polygon(x: np.ndarray, p: np.ndarray) -> float:
    a, b = p, np.roll(p, -1, axis=0)
    e = b - a
    t = np.clip(((x - a) * e).sum(axis=1) / (e * e).sum(axis=1), 0.0, 1.0)
    return float(np.min(np.linalg.norm(a + t[:, None] * e - x, axis=1)))


def inside(x: np.ndarray, p: np.ndarray) -> bool:
    a, b = p - x, np.roll(p, -1, axis=0) - x
    ang = np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(axis=1))
    return abs(float(np.sum(ang))) > math.pi


def line_dist(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    d = (b - a) / np.linalg.norm(b - a)
    v = x - a
    return abs(float(v[0] * d[1] - v[1] * d[0]))


def bend(half, m: Material) -> dict:
    """SB, BA, BD and the shift of a crease half, from the textbook formulas."""
    surface = m.sheet_surface.value
    return hand_bend(
        half.fold_angle_deg, half.bend, surface, m.thickness, m.bend_radius, m.k_factor
    )


def entities(doc, layer: str, kind: str | None = None) -> list:
    return [e for e in doc.modelspace() if e.dxf.layer == layer and kind in (None, e.dxftype())]


def outline_of(doc) -> np.ndarray:
    polys = entities(doc, "CUT", "LWPOLYLINE") + entities(doc, "CUT", "POLYLINE")
    assert len(polys) == 1
    poly = polys[0]
    assert poly.closed if poly.dxftype() == "LWPOLYLINE" else poly.is_closed
    pts = poly.get_points("xy") if poly.dxftype() == "LWPOLYLINE" else poly.points()
    return np.array([(p[0], p[1]) for p in pts], dtype=float)


def seg(e) -> np.ndarray:
    return np.array([[e.dxf.start.x, e.dxf.start.y], [e.dxf.end.x, e.dxf.end.y]])


# -- tests -----------------------------------------------------------------------------
@pytest.mark.parametrize(("shape", "mat"), CASES)
def test_layers_entities_and_hygiene(tmp_path, shape, mat):
    design, folded = _design(shape, mat)
    doc = write_read(tmp_path, design, folded)
    for name in LAYERS:
        assert name in doc.layers
    for layer in ("BEND_UP", "BEND_DOWN"):
        assert doc.layers.get(layer).dxf.linetype == "DASHED"
    assert "DASHED" in doc.linetypes
    scale = design.sheet.size
    seen = set()
    for e in doc.modelspace():
        kind = e.dxftype()
        if kind == "LINE":
            s = seg(e)
            assert np.linalg.norm(s[1] - s[0]) > 1e-6 * scale
            key = (kind, e.dxf.layer, tuple(sorted(map(tuple, np.round(s, 6).tolist()))))
        elif kind == "CIRCLE":
            assert e.dxf.radius > 0.0
            key = (kind, e.dxf.layer, round(e.dxf.center.x, 6), round(e.dxf.center.y, 6),
                   round(e.dxf.radius, 6))  # fmt: skip
        elif kind == "LWPOLYLINE":
            p = outline_of(doc)
            assert np.min(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)) > 1e-6 * scale
            key = (kind, e.dxf.layer, len(p))
        else:
            assert kind == "TEXT"
            key = (kind, e.dxf.text, round(e.dxf.insert.x, 6), round(e.dxf.insert.y, 6))
        assert key not in seen, key
        seen.add(key)
    hole = design.material.relief_hole_diameter
    circles = entities(doc, "CUT", "CIRCLE")
    assert len(circles) == (1 if hole > 0 else 0)
    if circles:
        assert circles[0].dxf.radius == pytest.approx((hole - design.material.kerf) / 2, abs=1e-12)
    # the cross (2 lines), the circle, and with a relief hole its leader and label
    leader = 1 if hole > 0 else 0
    assert len(entities(doc, "APEX", "CIRCLE")) == 1
    assert len(entities(doc, "APEX", "LINE")) == 2 + leader
    assert len(entities(doc, "APEX", "TEXT")) == leader
    assert len(entities(doc, "BEND_ZONE")) == (4 if design.material.thickness > 0 else 0)
    assert len(entities(doc, "RULINGS")) > 0


def _is_leader(line, apex) -> bool:
    """The relief hole's leader: a line from the hole's edge (the cross's
    arms are centred on H)."""
    a, b = seg(line)
    return bool(np.linalg.norm((a + b) / 2 - apex) > 1e-6 * np.linalg.norm(b - a))


def test_the_relief_hole_has_a_leader_and_label_visible_at_sheet_scale(tmp_path):
    """LibreCAD at full-sheet scale shows a 19 mm hole on a 7 m sheet as a
    dot: a leader from its edge, an eighth of the sheet long, and its label."""
    design = load_template(REPO_TEMPLATES / "patkau-one-fold.toml")
    folded = fold_design(design)
    doc = write_read(tmp_path, design, folded)
    centre = entities(doc, "APEX", "CIRCLE")[0].dxf.center
    apex = np.array([centre.x, centre.y])
    hole = entities(doc, "CUT", "CIRCLE")[0].dxf.radius * 2 + design.material.kerf
    (leader,) = [e for e in entities(doc, "APEX", "LINE") if _is_leader(e, apex)]
    a, b = seg(leader)
    assert np.linalg.norm(a - apex) == pytest.approx(hole / 2, rel=1e-9)  # from the hole's edge
    assert np.linalg.norm(b - a) >= design.sheet.size / 10  # seen at sheet scale
    (label,) = entities(doc, "APEX", "TEXT")
    assert label.dxf.text == f"relief hole, diameter {hole:.4g} mm"
    at = np.array([label.dxf.align_point.x, label.dxf.align_point.y])
    assert np.linalg.norm(at - b) <= 2 * label.dxf.height  # at the leader's end


@pytest.mark.parametrize(("shape", "mat"), CASES)
def test_fold_halves_meet_at_apex_and_end_on_outline(tmp_path, shape, mat):
    design, folded = _design(shape, mat)
    doc = write_read(tmp_path, design, folded)
    apex = entities(doc, "APEX", "CIRCLE")[0].dxf.center
    apex = np.array([apex.x, apex.y])
    h = design.sheet.to_sheet.apply(np.zeros((1, 2)))[0]
    assert np.allclose(apex, h, atol=1e-9 * design.sheet.size)
    crosses = [e for e in entities(doc, "APEX", "LINE") if not _is_leader(e, apex)]
    assert len(crosses) == 2
    for cross in crosses:
        assert np.allclose(seg(cross).mean(axis=0), apex, atol=1e-9 * design.sheet.size)
    lines = entities(doc, "BEND_UP", "LINE") + entities(doc, "BEND_DOWN", "LINE")
    assert len(lines) == 2  # the exact model: the crease halves alone
    cut = outline_of(doc)
    nominal = cut if design.material.kerf == 0 else outline_of(
        write_read(tmp_path, design.with_changes(
            name=design.name + "_nokerf", material=design.material.with_changes(kerf=0.0)))
    )  # fmt: skip
    by_name = {}
    for line in lines:
        xd = line.get_xdata("ONEFOLD")
        name, direction, angle = xd[0].value, xd[1].value, xd[2].value
        by_name[name] = (line, direction, angle)
    for half in folded.crease:
        line, direction, angle = by_name[half.name]
        assert line.dxf.layer == f"BEND_{half.bend}" and direction == half.bend
        assert angle == pytest.approx(half.fold_angle_deg, abs=1e-9)
        s = seg(line)
        assert np.allclose(s[0], apex, atol=1e-9 * design.sheet.size)
        assert dist_to_polygon(s[1], nominal) < 1e-9 * design.sheet.size
        if design.material.kerf > 0:  # the cut path runs kerf/2 outside the part's edge
            assert dist_to_polygon(s[1], cut) == pytest.approx(design.material.kerf / 2, abs=1e-9)
        # the half points the way of the crease end (flat fold frame)
        d = design.sheet.to_sheet.apply_direction(half.end_flat[None, :])[0]
        assert np.dot(s[1] - s[0], d) > 0
        assert line_dist(s[1], s[0], s[0] + d) < 1e-9 * design.sheet.size
        label = f"{half.bend} {half.fold_angle_deg:.2f} deg"
        assert any(t.dxf.text == label for t in entities(doc, "NOTES", "TEXT"))
    if design.material.thickness == 0:  # the crease halves run to the sheet's edge exactly
        for half in folded.crease:
            end = design.sheet.to_sheet.apply(half.end_flat[None, :])[0]
            assert np.allclose(seg(by_name[half.name][0])[1], end, atol=1e-9 * design.sheet.size)


@pytest.mark.parametrize("shape", list(SHAPES))
@pytest.mark.parametrize("dxfversion", ["R2000", "R12"])
def test_zero_thickness_outline_is_the_sheet(tmp_path, shape, dxfversion):
    design, folded = _design(shape, "bare")
    doc = write_read(tmp_path, design, folded, dxfversion=dxfversion)
    p = outline_of(doc)
    sheet = design.sheet
    assert shoelace(p) == pytest.approx(sheet.area, rel=1e-9)
    assert perimeter(p) == pytest.approx(sheet.perimeter, rel=1e-9)
    assert np.allclose(p, sheet.to_sheet.apply(sheet.vertices), atol=1e-9 * sheet.size)
    if shape == "rect":  # sheet's own frame: a corner at the origin, sides on the axes
        assert np.allclose(p.min(axis=0), 0.0, atol=1e-9) and np.allclose(p.max(axis=0), (400, 250))


@pytest.mark.parametrize("shape", list(SHAPES))
@pytest.mark.parametrize("mat", ["thick", "thick_kerf", "thick_inside"])
def test_thickness_compensation_and_bend_zones(tmp_path, shape, mat):
    design, folded = _design(shape, mat)
    m = design.material
    nominal_design = design.with_changes(name=design.name + "_n", material=m.with_changes(kerf=0))
    doc = write_read(tmp_path, nominal_design, folded=None)
    place = design.sheet.to_sheet
    hb = [bend(h, m) for h in folded.crease]
    ba = [b["ba"] for b in hb]
    shift = (hb[0]["shift"] + hb[1]["shift"]) / 2.0  # the documented rule: the mean shift
    pattern = flat_pattern(design, folded)
    assert pattern.shift == pytest.approx(shift, rel=1e-12)
    assert pattern.residual == pytest.approx(abs(hb[0]["shift"] - hb[1]["shift"]) / 2.0, abs=1e-12)
    errors = [round(2 * (b["shift"] - shift), 9) + 0.0 for b in hb]  # '-0.0000' is '0.0000
    assert f"{errors[0]:.4f}, {errors[1]:.4f} mm" in " ".join(flat_pattern_notes(pattern))
    if shape in ("t1a", "t1b", "t1c", "rect"):  # symmetric: each side moves by its own shift
        assert shift == pytest.approx(hb[0]["shift"], rel=1e-9) and pattern.residual < 1e-9
    out = place.inverse(outline_of(doc))  # back to the fold frame: fold line = x axis
    v = np.asarray(design.sheet.vertices)
    c = max(ba) / 2.0
    moved = v[np.abs(v[:, 1]) > shift + c + 1e-6]
    moved = moved - np.sign(moved[:, 1])[:, None] * np.array([0.0, shift])
    for q in moved:  # every corner off the fold line moved by `shift` towards it
        assert np.min(np.linalg.norm(out - q, axis=1)) < 1e-9 * design.sheet.size
    edges = np.stack([v, np.roll(v, -1, axis=0)], axis=1)
    # where the mean shift takes a crease end out of its half's zone, the bridge starts at
    # the moved crease end itself
    lp, lm = design.sheet.crease_lengths
    ends = np.array([(lp, -shift), (lp, shift), (-lm, -shift), (-lm, shift)])
    ends = ends[[-shift > ba[0] / 2] * 2 + [-shift > ba[1] / 2] * 2]
    moved = np.vstack([moved, ends])
    for q in out:  # every outline vertex is a moved corner or a bridge point at BA/2
        if np.min(np.linalg.norm(moved - q, axis=1)) < 1e-9 * design.sheet.size:
            continue
        assert min(abs(abs(q[1]) - b / 2) for b in ba) < 1e-9 * design.sheet.size
        side = np.sign(q[1])
        cand = edges[np.sign(edges[:, :, 1]).sum(axis=1) * side > 0] - [0.0, side * shift]
        assert min(line_dist(q, a, b) for a, b in cand) < 1e-9 * design.sheet.size
    # bend-zone lines: parallel to their fold half at BA/2, from over H to the outline
    halves = {ln.get_xdata("ONEFOLD")[0].value: seg(ln) for ln in
              entities(doc, "BEND_UP") + entities(doc, "BEND_DOWN")}  # fmt: skip
    zone = [seg(e) for e in entities(doc, "BEND_ZONE")]
    assert len(zone) == 4
    for half, a in zip(folded.crease, ba, strict=True):
        f = halves[half.name]
        mine = [z for z in zone if np.dot(z[1] - z[0], f[1] - f[0]) > 0]
        assert len(mine) == 2
        for z in mine:
            for x in z:
                assert line_dist(x, f[0], f[1]) == pytest.approx(a / 2.0, abs=1e-9 * 300)
            assert dist_to_polygon(z[1], outline_of(doc)) < 1e-9 * 300
        assert np.linalg.norm(mine[0][0] - mine[1][0]) == pytest.approx(a, abs=1e-9 * 300)


@pytest.mark.parametrize("shape", list(SHAPES))
@pytest.mark.parametrize("mat", ["kerf", "thick_kerf"])
def test_kerf_offset_is_exact(tmp_path, shape, mat):
    design, folded = _design(shape, mat)
    kerf = design.material.kerf
    cut = outline_of(write_read(tmp_path, design, folded))
    plain = design.with_changes(name="plain", material=design.material.with_changes(kerf=0))
    nominal = outline_of(write_read(tmp_path, plain, folded=None))
    assert len(cut) == len(nominal)
    for i in range(len(nominal)):  # edge i of the cut path: parallel, kerf/2 outside edge i
        a, b = nominal[i], nominal[(i + 1) % len(nominal)]
        d = (b - a) / np.linalg.norm(b - a)
        outward = np.array([d[1], -d[0]])
        for x in (cut[i], cut[(i + 1) % len(cut)]):
            assert np.dot(x - a, outward) == pytest.approx(kerf / 2, abs=1e-9)
    assert shoelace(cut) > shoelace(nominal)


@pytest.mark.parametrize(
    ("units", "code", "measurement"), [(Units.MM, 4, 1), (Units.IN, 1, 0), (Units.FT, 2, 0)]
)
def test_units_header(tmp_path, units, code, measurement):
    scale = {Units.MM: 1.0, Units.IN: 1 / 25.4, Units.FT: 1 / 304.8}[units]
    sheet = Sheet.quadrilateral(*(300 * scale,) * 4)
    mat = Material(thickness=2 * scale, bend_radius=3 * scale, kerf=0.2 * scale)
    design = Design("u", FrameCurve(32, 34, 0, 100, 90), sheet, material=mat, units=units)
    doc = write_read(tmp_path, design)
    assert doc.header["$INSUNITS"] == code and doc.units == code
    assert doc.header["$MEASUREMENT"] == measurement
    assert any(f"units: {units.value}" == t.dxf.text for t in entities(doc, "NOTES", "TEXT"))
    # same part in every unit: the outline scales exactly with the unit
    p = outline_of(doc) / scale
    ref = outline_of(write_read(tmp_path, design.with_changes(
        name="mm", units=Units.MM, sheet=Sheet.quadrilateral(300, 300, 300, 300),
        material=Material(thickness=2, bend_radius=3, kerf=0.2))))  # fmt: skip
    assert np.allclose(p, ref, atol=1e-9 * 300)


def test_notes_content_and_mass(tmp_path):
    design, folded = _design("t1d", "thick")
    doc = write_read(tmp_path, design, folded)
    text = "\n".join(t.dxf.text for t in entities(doc, "NOTES", "TEXT"))
    m = design.material
    for needle in ("t1d_thick", "units: mm", "S235", "thickness t = 2 mm",
                   "bend radius r = 2.5 mm", "K-factor = 0.44", "flat size", "area"):  # fmt: skip
        assert needle in text
    for half in folded.crease:
        assert f"{half.bend} {half.fold_angle_deg:.2f} deg" in text
    area = shoelace(outline_of(doc)) - math.pi * m.relief_hole_diameter**2 / 4
    # the unit's power written plainly (ASCII: R12 and R2000 files are in a code
    # page), not DXF's caret escape "^ 3", which LibreCAD shows as is
    assert "^" not in text
    mass = float(re.search(r"mass: ([-0-9.eE+]+) kg \(density 7900 kg/m3\)", text).group(1))
    # 7900 kg/m^3 x t (mm) x area (mm^2), with 1 mm^3 = 1e-9 m^3
    assert mass == pytest.approx(area * m.thickness * 7900.0 * 1e-9, rel=1e-5)
    w, h = np.ptp(outline_of(doc), axis=0)
    assert f"flat size: {w:.3f} x {h:.3f} mm" in text
    assert "mass" not in "\n".join(flat_pattern_notes(flat_pattern(*_design("t1d", "bare"))))


def test_paper_model_rulings_inside_and_optional(tmp_path):
    """The paper model's rulings that are no folds (the rays through the star's corners,
    inside one planar triangle of the fan) are etch lines, inside the blank, off the bend
    zones and the hole, and optional."""
    design, folded = _design("star", "thick", model=Model.PAPER)
    doc = write_read(tmp_path, design, folded)
    outline = outline_of(doc)
    rulings = [seg(e) for e in entities(doc, "RULINGS")]
    assert len(rulings) == sum(1 for x, y in STAR if y != 0)  # one per corner off the x axis
    c = max(bend(h, design.material)["ba"] for h in folded.crease) / 2
    hole_r = design.material.relief_hole_diameter / 2
    for r in rulings:
        for x in r:
            assert inside(x, outline) or dist_to_polygon(x, outline) < 1e-9 * 300
            assert abs(x[1]) >= c - 1e-9 and np.linalg.norm(x) >= hole_r - 1e-9
    doc2 = write_read(tmp_path, design.with_changes(name="norul"), folded=None, rulings=False)
    assert not entities(doc2, "RULINGS")
    assert len(entities(doc2, "BEND_UP") + entities(doc2, "BEND_DOWN")) > 2  # folds stay


def _fan_by_hand(frame: FrameCurve) -> tuple[np.ndarray, float]:
    """The paper fan's division points P_i (from the frame curve's definition) and its
    apex height (the angle condition, solved here)."""
    alpha, beta = math.radians(frame.alpha), math.radians(frame.beta)
    n = frame.divisions
    phi = -alpha + np.arange(n + 1) * (math.pi + 2 * alpha) / n
    x = -frame.h_c + frame.radius * np.cos(phi)
    dd = frame.radius * (math.sin(alpha) + np.sin(phi))
    pts = np.stack([x, dd * math.cos(beta), dd * math.sin(beta)], axis=1)
    return pts, _apex_height_by_hand(pts)


def _fold_lines(doc) -> dict[str, tuple[str, str, float, np.ndarray]]:
    """name -> (layer, direction, angle, segment) of every line on BEND_UP/BEND_DOWN."""
    out = {}
    for line in entities(doc, "BEND_UP", "LINE") + entities(doc, "BEND_DOWN", "LINE"):
        xd = line.get_xdata("ONEFOLD")
        out[xd[0].value] = (line.dxf.layer, xd[1].value, xd[2].value, seg(line))
    return out


def test_paper_fan_rulings_are_bends_with_their_fold_angles(tmp_path):
    """The paper model's fan: two planar triangles meet along each division ray at an
    angle, a real fold. Each is drawn on BEND_UP/BEND_DOWN (DASHED, XDATA), with its fold
    angle and direction derived here from the frame curve and the hand-solved apex
    (fold angle between consecutive triangles' top normals, UP when the next triangle
    turns towards the top side), to 1e-9 deg; in the blank each line runs along its flat
    ray, at the flat angle theta_k = the sum of the fan's apex angles up to it. The
    -y side is the mirror image: '-y ruling k' (k-th from the -x crease) is ray n - k."""
    design, folded = _design("star", "thick", model=Model.PAPER)
    pts, h = _fan_by_hand(design.frame)
    folds = fan_folds(pts, np.array([0.0, 0.0, h]))
    u = pts - [0.0, 0.0, h]
    u /= np.linalg.norm(u, axis=1)[:, None]
    theta = np.concatenate([[0.0], np.cumsum(np.arccos((u[:-1] * u[1:]).sum(axis=1)))])
    doc = write_read(tmp_path, design, folded)
    lines = _fold_lines(doc)
    n = design.frame.divisions
    assert len(lines) == 2 + 2 * (n - 1)
    for k in range(1, n):
        angle, direction = folds[k - 1]
        for name, ray, sign in ((f"+y ruling {k}", k, 1.0), (f"-y ruling {n - k}", k, -1.0)):
            layer, xd_dir, xd_angle, (a, b) = lines[name]
            assert (layer, xd_dir) == (f"BEND_{direction}", direction)
            assert xd_angle == pytest.approx(angle, abs=1e-9)
            d = b - a  # the star is drawn in the fold frame
            assert math.atan2(sign * d[1], d[0]) == pytest.approx(theta[ray], abs=1e-9)
    notes = [t.dxf.text for t in entities(doc, "NOTES", "TEXT")]
    assert any(t.startswith(f"ruling folds: {2 * (n - 1)} rulings") for t in notes)
    assert any(t.startswith(f"+y ruling 1: {folds[0][1]} {folds[0][0]:.2f};") for t in notes)


def test_exact_model_rulings_stay_etch_lines(tmp_path):
    design, folded = _design("star", "thick")
    doc = write_read(tmp_path, design, folded)
    assert set(_fold_lines(doc)) == {"plus_x", "minus_x"}
    assert len(entities(doc, "RULINGS")) == sum(1 for x, y in STAR if y != 0)


def _apex_height_by_hand(points: np.ndarray) -> float:
    """The paper model's apex height, solved here from the angle condition alone: the
    apex angles between consecutive directions from A = (0, 0, h) to the division
    points add up to 180 deg, on the branch past S(h)'s maximum."""
    from scipy.optimize import brentq

    def excess(h: float) -> float:
        u = points - np.array([0.0, 0.0, h])
        u /= np.linalg.norm(u, axis=1)[:, None]
        return float(np.sum(np.arccos(np.clip((u[:-1] * u[1:]).sum(axis=1), -1, 1)))) - math.pi

    hs = np.geomspace(1e-3, 1e4, 2000)
    top = int(np.argmax([excess(h) for h in hs]))
    return brentq(excess, hs[top], 1e4, xtol=1e-14, rtol=1e-15)


def test_down_half_by_hand_layer_width_refusal_and_uncompensated_blank(tmp_path):
    """A DOWN crease half, derived by hand (paper model, alpha 8.3, beta 85, 4 divisions,
    H at 0.8 of the half chord towards +x; the sheet's apex sits near its +x end).

    The division points are P_i = (x_i, d_i cos beta, d_i sin beta), x_i = -h_c + R cos
    phi_i, d_i = R sin alpha + R sin phi_i, phi_i = -alpha + i (180 + 2 alpha) / 4. The
    plus_x crease is the ruling u0 = P0 - A = (a, 0, -h), a = x_0; the +y side's first
    triangle is spanned by u0 and u1 = P1 - A = (b, c, w), b = x_1, c = y_1 > 0,
    w = z_1 - h. Its top normal is u0 x u1 = (h c, -h b - a w, a c) (the flat x-axis
    and the +y side's first ray give +z); the -y side is the mirror image M (y -> -y),
    whose top normal is M (u0 x u1). The half bends UP (the top faces end inside) when
    the +y side, leaving the crease along the part of u1 normal to u0, heads towards
    the -y side's top normal: u1 . M (u0 x u1) = 2 c (b h + a w) > 0 (u0 . M(u0 x u1) = 0
    as M u0 = u0). With R = 100: a = -h_c + R cos(alpha) = 0.2 R cos(8.3) = 19.79,
    phi_1 = 40.85 deg, b = -79.16 + 75.64 = -3.52, d_1 = 100 (0.1444 + 0.6540) = 79.84,
    z_1 = d_1 sin 85 = 79.54; so b h + a (z_1 - h) = 1574 - 23.31 h, positive only for
    h < 67.5. The angle condition puts the apex at h = 86.6 (solved below, by hand), so
    plus_x bends DOWN; its fold angle is the angle between the two top normals.

    minus_x folds UP to 167 deg: the one rigid blank cannot follow both halves' shifts,
    so the compensated DXF is refused naming the width error (by hand: shift+ - shift-,
    each side moved by their mean); --compensation none writes the designed outline,
    with the DOWN half and the fan's DOWN ruling folds on BEND_DOWN.
    """
    frame = FrameCurve(8.3, 85.0, 0.8 * 100.0 * math.cos(math.radians(8.3)), 100.0, 4)
    alpha, beta = math.radians(8.3), math.radians(85.0)
    phi = -alpha + np.arange(5) * (math.pi + 2 * alpha) / 4
    x = -frame.h_c + 100.0 * np.cos(phi)
    dd = 100.0 * (math.sin(alpha) + np.sin(phi))
    pts = np.stack([x, dd * math.cos(beta), dd * math.sin(beta)], axis=1)
    h = _apex_height_by_hand(pts)
    a, (b, c, z1) = pts[0, 0], pts[1]
    assert c > 0 and 67.6 < h and b * h + a * (z1 - h) < 0  # DOWN
    u0, u1 = pts[0] - [0, 0, h], pts[1] - [0, 0, h]
    n = np.cross(u0, u1)
    m = n * [1.0, -1.0, 1.0]
    psi = math.degrees(math.acos(float(n @ m) / float(n @ n)))
    mat = Material(thickness=1.0, bend_radius=1.0, k_factor=0.44, sheet_surface="INSIDE")
    design = Design("down", frame, Sheet.quadrilateral(60, 340, 300, 280), model="paper",
                    material=mat)  # fmt: skip
    folded = fold_design(design)
    assert folded.solution.apex_height == pytest.approx(h, rel=1e-9)
    plus = folded.crease[0]
    assert plus.bend == "DOWN" and plus.fold_angle_deg == pytest.approx(psi, abs=1e-9)
    # INSIDE reference in a DOWN bend is its outside face (s = 1); minus_x is UP (s = 0)
    hb = [hand_bend(hh.fold_angle_deg, hh.bend, "INSIDE", 1.0, 1.0, 0.44) for hh in folded.crease]
    assert hb[0]["s"] == 1.0 and hb[1]["s"] == 0.0
    shift = (hb[0]["shift"] + hb[1]["shift"]) / 2
    width = hb[1]["shift"] - hb[0]["shift"]  # across minus_x, the blank moved by the mean
    target = tmp_path / "down.dxf"
    with pytest.raises(FabricationError) as info:
        export_design_dxf(design, target, folded)
    assert f"{width:+.4g} mm too wide" in str(info.value) and f"d = {shift:.4g} mm" in str(
        info.value
    )
    assert not target.exists()
    doc = write_read(tmp_path, design, folded, compensation="none")
    assert np.allclose(outline_of(doc), [(60, 0), (0, 300), (-340, 0), (0, -280)], atol=1e-9)
    fan = fan_folds(pts, np.array([0.0, 0.0, h]))  # rays 1, 2, 3 of the +y side
    expected = {"plus_x": psi} | {
        name: a
        for k, (a, direction) in enumerate(fan, 1)
        if direction == "DOWN"
        for name in (f"+y ruling {k}", f"-y ruling {4 - k}")
    }
    down = {e.get_xdata("ONEFOLD")[0].value: e for e in entities(doc, "BEND_DOWN", "LINE")}
    assert set(down) == set(expected)
    for name, e in down.items():
        assert e.dxf.linetype == "DASHED"
        assert e.get_xdata("ONEFOLD")[2].value == pytest.approx(expected[name], abs=1e-9)


def test_drawing_into_an_existing_doc():
    design, folded = _design("t1d", "thick")
    pattern = flat_pattern(design, folded)
    doc = ezdxf.new("R2000")
    assert draw_flat_pattern(pattern, doc, rulings=False) is doc
    assert len(entities(doc, "BEND_UP")) == 2 and not entities(doc, "BEND_DOWN")


def raw_header(path: Path, var: str) -> str:
    """The value of header variable ``var`` as written in the file (group code, value)."""
    lines = [ln.strip() for ln in path.read_text().splitlines()]
    return lines[lines.index(var) + 2]


def _fake_clock(monkeypatch, when: datetime.datetime) -> None:
    class Clock(datetime.datetime):
        @classmethod
        def now(cls, tz=None):
            return when if tz is None else when.replace(tzinfo=tz)

    monkeypatch.setattr(ezdxf.document, "datetime", Clock)


@pytest.mark.parametrize("dxfversion", ["R2000", "R12"])
def test_two_writes_are_byte_identical_across_a_clock_change(tmp_path, monkeypatch, dxfversion):
    """ezdxf stamps $TDUPDATE, a random $VERSIONGUID and its own metadata when it
    writes; ours fix every stamp and derive the GUIDs from the design."""
    design, folded = _design("t1d", "thick")
    paths = []
    for i, year in enumerate((2001, 2031)):
        _fake_clock(monkeypatch, datetime.datetime(year, 5, 6, 7, 8, 9))
        paths.append(
            export_design_dxf(design, tmp_path / f"{i}.dxf", folded, dxfversion=dxfversion)
        )
    assert paths[0].read_bytes() == paths[1].read_bytes()
    # the clock does reach ezdxf: a plain save differs between the two times
    plain = []
    for i, year in enumerate((2001, 2031)):
        _fake_clock(monkeypatch, datetime.datetime(year, 5, 6, 7, 8, 9))
        doc = draw_flat_pattern(flat_pattern(design, folded), dxfversion=dxfversion)
        doc.saveas(tmp_path / f"plain{i}.dxf")
        plain.append((tmp_path / f"plain{i}.dxf").read_bytes())
    assert plain[0] != plain[1]
    # (read from the text: ezdxf's reader restamps $TDCREATE of the document it loads)
    for var in ("$TDCREATE", "$TDUPDATE"):  # 2000-01-01 in ezdxf's Julian-date convention
        assert raw_header(paths[0], var) == str(juliandate(datetime.datetime(2000, 1, 1)))
    if dxfversion != "R12":
        other = export_design_dxf(design.with_changes(name="other"), tmp_path / "o.dxf", folded)
        guids = [raw_header(p, "$FINGERPRINTGUID") for p in (paths[0], other)]
        assert guids[0] != guids[1] and re.fullmatch(r"\{[0-9A-F-]{36}\}", guids[0])


def test_compensation_none_is_said_in_the_notes(tmp_path):
    design, folded = _design("t1d", "thick")
    doc = write_read(tmp_path, design, folded, compensation="none")
    text = "\n".join(t.dxf.text for t in entities(doc, "NOTES", "TEXT"))
    assert "thickness compensation: NONE" in text
    assert np.allclose(outline_of(doc), design.sheet.to_sheet.apply(design.sheet.vertices))
    assert not entities(doc, "BEND_ZONE")


@pytest.mark.parametrize(
    ("param", "changes"),
    [("thickness", {"thickness": -1.0}), ("k_factor", {"k_factor": 1.5}),
     ("k_factor", {"k_factor": -0.1}), ("bend_radius", {"bend_radius": -2.0}),
     ("kerf", {"kerf": -0.1})],
)  # fmt: skip
def test_bad_material_is_named(param, changes):
    with pytest.raises(InvalidParameterError) as info:
        Material(**changes)
    assert info.value.parameter == param and param in str(info.value)


@pytest.mark.parametrize(
    ("param", "shape", "material"),
    [
        ("kerf", "t1a", Material(kerf=500.0)),
        ("kerf", "t1a", Material(thickness=1, relief_hole=4.0, kerf=4.0)),
        # fits the sheet (< 424.26), not the compensated blank (sides moved 2.9 mm)
        ("relief_hole", "t1a", Material(thickness=4, bend_radius=6, relief_hole=420.0)),
        ("relief_hole", "t1a", Material(relief_hole=425.0)),  # not even the sheet
        ("thickness", "t1a", Material(thickness=150.0)),  # default hole 3 t = 450
        ("bend_radius", "t1a", Material(thickness=10.0, bend_radius=210.0)),  # 2 (t + r) = 440
        ("bend_radius", "t1d", Material(thickness=60, bend_radius=60, relief_hole=0)),
        ("bend_radius", "star", Material(thickness=10, bend_radius=10, relief_hole=0)),
    ],
)
def test_bad_fabrication_input_leaves_no_file(tmp_path, param, shape, material):
    frame, sheet = SHAPES[shape]
    design = Design("bad", FrameCurve(*frame), sheet(), material=material)
    target = tmp_path / "bad.dxf"
    target.write_text("previous")
    error = InvalidParameterError if param == "kerf" else FabricationError
    with pytest.raises(error) as info:
        export_design_dxf(design, target)
    assert info.value.parameter == param
    assert target.read_text() == "previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.dxf"]


def test_bad_dxfversion(tmp_path):
    design, folded = _design("t1a", "bare")
    with pytest.raises(InvalidParameterError, match="dxfversion"):
        export_design_dxf(design, tmp_path / "x.dxf", folded, dxfversion="R14")
    assert not list(tmp_path.iterdir())


def test_preview_png_and_svg(tmp_path):
    design, folded = _design("rect", "thick_kerf")
    path = export_design_dxf(design, tmp_path / "rect.dxf", folded)
    png = render_preview(path, tmp_path / "rect.png", dpi=40)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    svg = render_preview(ezdxf.readfile(path), tmp_path / "rect.svg").read_text()
    assert svg.lstrip().startswith("<?xml") or "<svg" in svg[:200]
    assert svg.count("<path") > 5
    with pytest.raises(InvalidParameterError, match="out_path"):
        render_preview(path, tmp_path / "rect.jpg")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rect.dxf", "rect.png", "rect.svg"]


@settings(max_examples=25, deadline=None)
@given(
    radii=st.lists(st.floats(60.0, 300.0), min_size=6, max_size=6),
    jitter=st.lists(st.floats(-0.4, 0.4), min_size=6, max_size=6),
    t=st.one_of(st.just(0.0), st.floats(0.01, 4.0)),
    r=st.floats(0.0, 6.0),
    kerf=st.floats(0.0, 1.0),
)
def test_random_star_polygons(radii, jitter, t, r, kerf):
    ang = (np.arange(6) + 0.5 + np.array(jitter)) * (2 * math.pi / 6)
    pts = np.stack([np.cos(ang), np.sin(ang)], axis=1) * np.array(radii)[:, None]
    mat = Material(thickness=t, bend_radius=r, kerf=kerf, relief_hole=0)
    design = Design("rnd", FrameCurve(40, 40, 10, 100, 90), Sheet.polygon(pts), material=mat)
    folded = fold_design(design)
    try:
        pattern = flat_pattern(design, folded)
    except FabricationError as exc:  # the bend model's limits, and only those
        assert (
            t > 0
            and check_bends(folded, design.material, design.units)
            and exc.parameter in ("bend_radius", "hc")
        )
        return
    except InvalidParameterError as exc:  # the kerf's documented refusal
        assert exc.parameter == "kerf"
        return
    doc = draw_flat_pattern(pattern)
    assert not doc.audit().has_errors
    out = pattern.outline
    if t == 0:
        assert shoelace(out) == pytest.approx(design.sheet.area, rel=1e-9)
    else:
        assert 0 < shoelace(out) < design.sheet.area
    for half, crease in zip(pattern.halves, folded.crease, strict=True):
        assert np.allclose(half.start, 0.0) and dist_to_polygon(half.end, out) < 1e-9 * 300
        ba = bend(crease, design.material)["ba"] if t > 0 else 0.0
        for z in half.zone:
            for x in z:
                assert line_dist(x, half.start, half.end) == pytest.approx(ba / 2, abs=1e-6)
    cut = pattern.cut_outline
    for i in range(len(out)):
        a, b = out[i], out[(i + 1) % len(out)]
        d = (b - a) / np.linalg.norm(b - a)
        assert np.dot(cut[i] - a, [d[1], -d[0]]) == pytest.approx(kerf / 2, abs=1e-9)


def test_cones_formed_past_their_springback_are_said_in_the_notes(tmp_path):
    # a DXF built from a compensated template (onefold build, site) tells the shop
    # how to form the cones, not only compensate's own -o
    from onefold_cad.choices import ConeForming

    design, folded = _design("t1d", "thick")
    formed = design.with_changes(
        material=design.material.with_changes(cone_forming=ConeForming.COMPENSATED)
    )
    text = "\n".join(
        t.dxf.text for t in entities(write_read(tmp_path, formed, folded), "NOTES", "TEXT")
    )
    assert f"each station to the radius in {formed.name}-cones.csv" in text
    assert "springback" not in "\n".join(flat_pattern_notes(flat_pattern(design, folded)))
