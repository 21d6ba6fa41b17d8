"""Round-trip tests of the DXF flat pattern: write, read back with ezdxf, measure."""

from __future__ import annotations

import math
import re
from dataclasses import replace
from functools import cache
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    Material,
    Model,
    Sheet,
    Units,
    build_design,
)
from onefold_cad.export.dxf import LAYERS, draw_flat_pattern, export_design_dxf
from onefold_cad.export.dxf_preview import render_preview
from onefold_cad.export.flat_pattern import flat_pattern

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
    "thick": Material(thickness=2.0, bend_radius=3.0, k_factor=0.44, density=7900.0, name="S235"),
    "thick_kerf": Material(thickness=1.5, bend_radius=1.0, k_factor=0.33, kerf=0.4),
}
CASES = [(s, m) for s in SHAPES for m in MATERIALS]


@cache
def _design(shape: str, mat: str, model: str = "exact") -> tuple[Design, object]:
    frame, sheet = SHAPES[shape]
    design = Design(f"{shape}_{mat}", FrameCurve(*frame), sheet(), model=model,
                    material=MATERIALS[mat])  # fmt: skip
    return design, build_design(design)


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


def bend(psi_deg: float, m: Material) -> tuple[float, float]:
    """(BA, BD) from the textbook formulas."""
    psi = math.radians(psi_deg)
    ba = psi * (m.bend_radius + m.k_factor * m.thickness)
    return ba, 2.0 * (m.bend_radius + m.thickness) * math.tan(psi / 2.0) - ba


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
    assert len(entities(doc, "APEX", "CIRCLE")) == 1 and len(entities(doc, "APEX", "LINE")) == 2
    assert len(entities(doc, "BEND_ZONE")) == (4 if design.material.thickness > 0 else 0)
    assert len(entities(doc, "RULINGS")) > 0


@pytest.mark.parametrize(("shape", "mat"), CASES)
def test_fold_halves_meet_at_apex_and_end_on_outline(tmp_path, shape, mat):
    design, folded = _design(shape, mat)
    doc = write_read(tmp_path, design, folded)
    apex = entities(doc, "APEX", "CIRCLE")[0].dxf.center
    apex = np.array([apex.x, apex.y])
    h = design.sheet.to_sheet.apply(np.zeros((1, 2)))[0]
    assert np.allclose(apex, h, atol=1e-9 * design.sheet.size)
    for cross in entities(doc, "APEX", "LINE"):
        assert np.allclose(seg(cross).mean(axis=0), apex, atol=1e-9 * design.sheet.size)
    lines = entities(doc, "BEND_UP", "LINE") + entities(doc, "BEND_DOWN", "LINE")
    assert len(lines) == 2
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
@pytest.mark.parametrize("mat", ["thick", "thick_kerf"])
def test_thickness_compensation_and_bend_zones(tmp_path, shape, mat):
    design, folded = _design(shape, mat)
    m = design.material
    nominal_design = design.with_changes(name=design.name + "_n", material=m.with_changes(kerf=0))
    doc = write_read(tmp_path, nominal_design, folded=None)
    place = design.sheet.to_sheet
    ba, bd = zip(*(bend(h.fold_angle_deg, m) for h in folded.crease), strict=True)
    shift = (bd[0] + bd[1]) / 4.0  # the documented rule: each side moves by the mean BD / 2
    pattern = flat_pattern(design, folded)
    assert pattern.residual == pytest.approx(abs(bd[0] - bd[1]) / 2.0, abs=1e-12)
    assert f"{pattern.residual:.4f}" in " ".join(pattern.notes)
    if shape in ("t1a", "t1b", "t1c", "rect"):  # symmetric: the outline moves by BD/2 per side
        assert shift == pytest.approx(bd[0] / 2.0, abs=1e-9) and pattern.residual < 1e-9
    out = place.inverse(outline_of(doc))  # back to the fold frame: fold line = x axis
    v = np.asarray(design.sheet.vertices)
    c = max(ba) / 2.0
    moved = v[np.abs(v[:, 1]) > shift + c + 1e-6]
    moved = moved - np.sign(moved[:, 1])[:, None] * np.array([0.0, shift])
    for q in moved:  # every corner off the fold line moved by `shift` towards it
        assert np.min(np.linalg.norm(out - q, axis=1)) < 1e-6
    edges = np.stack([v, np.roll(v, -1, axis=0)], axis=1)
    for q in out:  # every outline vertex is a moved corner or a bridge point at BA/2
        if np.min(np.linalg.norm(moved - q, axis=1)) < 1e-6:
            continue
        assert min(abs(abs(q[1]) - b / 2) for b in ba) < 1e-9 * design.sheet.size
        side = np.sign(q[1])
        cand = edges[np.sign(edges[:, :, 1]).sum(axis=1) * side > 0] - [0.0, side * shift]
        assert min(line_dist(q, a, b) for a, b in cand) < 1e-6
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
                assert line_dist(x, f[0], f[1]) == pytest.approx(a / 2.0, abs=1e-6)
            assert dist_to_polygon(z[1], outline_of(doc)) < 1e-6
        assert np.linalg.norm(mine[0][0] - mine[1][0]) == pytest.approx(a, abs=1e-6)


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
                   "bend radius r = 3 mm", "K-factor = 0.44", "flat size", "area"):  # fmt: skip
        assert needle in text
    for half in folded.crease:
        assert f"{half.bend} {half.fold_angle_deg:.2f} deg" in text
    area = shoelace(outline_of(doc)) - math.pi * m.relief_hole_diameter**2 / 4
    # ("^ " is how DXF text writes a caret)
    mass = float(re.search(r"mass: ([-0-9.eE+]+) kg \(density 7900 kg/m\^ 3\)", text).group(1))
    # 7900 kg/m^3 x t (mm) x area (mm^2), with 1 mm^3 = 1e-9 m^3
    assert mass == pytest.approx(area * m.thickness * 7900.0 * 1e-9, rel=1e-5)
    w, h = np.ptp(outline_of(doc), axis=0)
    assert f"flat size: {w:.3f} x {h:.3f} mm" in text
    assert "mass" not in "\n".join(flat_pattern(*_design("t1d", "bare")).notes)


def test_paper_model_rulings_inside_and_optional(tmp_path):
    design, folded = _design("star", "thick", model=Model.PAPER)
    doc = write_read(tmp_path, design, folded)
    outline = outline_of(doc)
    rulings = [seg(e) for e in entities(doc, "RULINGS")]
    assert len(rulings) > 50  # the paper model's fan
    c = max(bend(h.fold_angle_deg, design.material)[0] for h in folded.crease) / 2
    hole_r = design.material.relief_hole_diameter / 2
    for r in rulings:
        for x in r:
            assert inside(x, outline) or dist_to_polygon(x, outline) < 1e-9 * 300
            assert abs(x[1]) >= c - 1e-9 and np.linalg.norm(x) >= hole_r - 1e-9
    doc2 = write_read(tmp_path, design.with_changes(name="norul"), folded=None, rulings=False)
    assert not entities(doc2, "RULINGS")


def test_bend_down_layer_and_existing_doc():
    design, folded = _design("t1d", "thick")
    pattern = flat_pattern(design, folded)
    down = replace(pattern.halves[1], bend="DOWN")
    pattern = replace(pattern, halves=(pattern.halves[0], down))
    doc = ezdxf.new("R2000")
    assert draw_flat_pattern(pattern, doc, rulings=False) is doc
    assert len(entities(doc, "BEND_UP")) == 1 and len(entities(doc, "BEND_DOWN")) == 1
    assert entities(doc, "BEND_DOWN")[0].get_xdata("ONEFOLD")[1].value == "DOWN"


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
        ("relief_hole", "t1a", Material(thickness=4, bend_radius=6, relief_hole=420.0)),
        ("thickness", "t1d", Material(thickness=60, bend_radius=60, relief_hole=0)),
        ("thickness", "star", Material(thickness=10, bend_radius=10, relief_hole=0)),
    ],
)
def test_bad_fabrication_input_leaves_no_file(tmp_path, param, shape, material):
    frame, sheet = SHAPES[shape]
    design = Design("bad", FrameCurve(*frame), sheet(), material=material)
    target = tmp_path / "bad.dxf"
    target.write_text("previous")
    with pytest.raises(InvalidParameterError) as info:
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
    folded = build_design(design)
    try:
        pattern = flat_pattern(design, folded)
    except InvalidParameterError as exc:  # only the documented refusals
        assert exc.parameter in ("thickness", "kerf")
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
        ba = bend(crease.fold_angle_deg, design.material)[0] if t > 0 else 0.0
        for z in half.zone:
            for x in z:
                assert line_dist(x, half.start, half.end) == pytest.approx(ba / 2, abs=1e-6)
    cut = pattern.cut_outline
    for i in range(len(out)):
        a, b = out[i], out[(i + 1) % len(out)]
        d = (b - a) / np.linalg.norm(b - a)
        assert np.dot(cut[i] - a, [d[1], -d[0]]) == pytest.approx(kerf / 2, abs=1e-9)
