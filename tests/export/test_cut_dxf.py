"""The cut-only DXF: layer CUT alone, one closed outline, the hole, nothing else."""

from __future__ import annotations

import datetime

import ezdxf
import numpy as np
import pytest

from onefold_cad import Design, FabricationError, FrameCurve, Material, Sheet, Units, fold_design
from onefold_cad.export.cut_dxf import export_design_cut_dxf
from onefold_cad.export.dxf import export_design_dxf
from tests.hand_bend import hand_bend

MAT = Material(thickness=2.0, bend_radius=3.0, k_factor=0.44, kerf=0.3, relief_hole=10.0)


def _design(units: Units = Units.MM, **changes) -> tuple[Design, object]:
    design = Design(
        "cut", FrameCurve(32, 34, 20, 100, 90), Sheet.rectangle(400, 250, 0.4), units=units,
        material=MAT.with_changes(**changes),
    )  # fmt: skip
    return design, fold_design(design)


def _cut_path_by_hand(folded) -> np.ndarray:
    """The kerf path of the 400 x 250 rectangle's blank, in its own frame, by hand.

    The fold runs along the diagonal O = (0, 0) (the -x crease end) to D = (400, 250)
    (+x), H = 0.4 D; n is the diagonal's left normal (the +y side holds T = (0, 250), the
    -y side R = (400, 0)). Each side moves by the mean d of the two halves' hand shifts
    towards the diagonal; the outline is cut at each half's bend zone, |y| = BA/2 from
    the diagonal, and bridged there. The kerf path is each edge's line moved kerf/2
    outwards, the corners where neighbouring lines meet (counter-clockwise polygon)."""
    d_end = np.array([400.0, 250.0])
    f = d_end / np.linalg.norm(d_end)
    n = np.array([-f[1], f[0]])
    h = 0.4 * d_end
    hb = [hand_bend(c.fold_angle_deg, c.bend, "MID", 2.0, 3.0, 0.44) for c in folded.crease]
    d = (hb[0]["shift"] + hb[1]["shift"]) / 2
    c_plus, c_minus = hb[0]["ba"] / 2, hb[1]["ba"] / 2

    def y(p):
        return float((p - h) @ n)

    def at(a, b, level):  # the point of segment a b at distance `level` from the diagonal
        return a + (level - y(a)) / (y(b) - y(a)) * (b - a)

    o, r, t = np.zeros(2), np.array([400.0, 0.0]), np.array([0.0, 250.0])
    up = [p - d * n for p in (d_end, t, o)]  # the +y side, moved
    lo = [p + d * n for p in (o, r, d_end)]  # the -y side, moved
    blank = [at(lo[0], lo[1], -c_minus), lo[1], at(lo[1], lo[2], -c_plus),
             at(up[0], up[1], c_plus), up[1], at(up[1], up[2], c_minus)]  # fmt: skip
    k = len(blank)
    lines = []
    for i in range(k):
        a, b = blank[i], blank[(i + 1) % k]
        e = (b - a) / np.linalg.norm(b - a)
        lines.append((a + 0.15 * np.array([e[1], -e[0]]), e))  # kerf 0.3: 0.15 outwards
    out = []
    for i in range(k):
        (p0, e0), (p1, e1) = lines[i - 1], lines[i]
        s = np.linalg.solve(np.column_stack([e0, -e1]), p1 - p0)
        out.append(p0 + s[0] * e0)
    return np.array(out)


@pytest.mark.parametrize("dxfversion", ["R2000", "R12"])
def test_only_the_cut_layer_one_closed_outline_and_the_hole(tmp_path, dxfversion):
    design, folded = _design()
    path = export_design_cut_dxf(design, tmp_path / "cut-cut.dxf", folded, dxfversion=dxfversion)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    msp = list(doc.modelspace())
    assert {e.dxf.layer for e in msp} == {"CUT"}
    kinds = sorted(e.dxftype() for e in msp)
    outline_kind = "LWPOLYLINE" if dxfversion == "R2000" else "POLYLINE"
    assert kinds == sorted(["CIRCLE", outline_kind])  # no text, no splines, nothing twice
    poly = next(e for e in msp if e.dxftype() == outline_kind)
    if dxfversion == "R2000":
        assert poly.closed
        pts = np.array([(p[0], p[1]) for p in poly.get_points("xy")])
    else:
        assert poly.is_closed
        pts = np.array([(p[0], p[1]) for p in poly.points()])
    # the cutting path by hand: the compensated blank, offset by kerf/2
    expected = _cut_path_by_hand(folded)
    assert len(pts) == len(expected)
    for q in expected:
        assert np.min(np.linalg.norm(pts - q, axis=1)) < 1e-9 * 400
    assert len({tuple(p) for p in np.round(pts, 9).tolist()}) == len(pts)  # no duplicate vertex
    hole = next(e for e in msp if e.dxftype() == "CIRCLE")
    assert hole.dxf.radius == pytest.approx((10.0 - 0.3) / 2, rel=1e-12)
    h = 0.4 * np.array([400.0, 250.0])  # H, 0.4 along the diagonal
    assert np.allclose([hole.dxf.center.x, hole.dxf.center.y], h, atol=1e-9 * 400)
    assert len(doc.blocks.get("*Model_Space")) == 2
    # the same cutting path as the annotated DXF's CUT layer
    annotated = ezdxf.readfile(export_design_dxf(design, tmp_path / "a.dxf", folded))
    (poly,) = annotated.modelspace().query("LWPOLYLINE[layer=='CUT']")
    assert np.allclose(np.array(poly.get_points("xy")), pts, atol=1e-12 * 400)


@pytest.mark.parametrize(("units", "code"), [(Units.MM, 4), (Units.IN, 1), (Units.FT, 2)])
def test_insunits(tmp_path, units, code):
    scale = {Units.MM: 1.0, Units.IN: 1 / 25.4, Units.FT: 1 / 304.8}[units]
    design = Design(
        "u", FrameCurve(32, 34, 20, 100, 90), Sheet.rectangle(400 * scale, 250 * scale, 0.4),
        units=units, material=Material(thickness=2 * scale, bend_radius=3 * scale),
    )  # fmt: skip
    doc = ezdxf.readfile(export_design_cut_dxf(design, tmp_path / "u.dxf"))
    assert doc.header["$INSUNITS"] == code
    assert doc.header["$MEASUREMENT"] == (1 if units is Units.MM else 0)


def test_deterministic_and_distinct_from_the_annotated_file(tmp_path, monkeypatch):
    design, folded = _design()
    out = []
    for year in (2001, 2040):

        class Clock(datetime.datetime):
            @classmethod
            def now(cls, tz=None, _y=year):
                return datetime.datetime(_y, 1, 2, 3, 4, 5, tzinfo=tz)

        monkeypatch.setattr(ezdxf.document, "datetime", Clock)
        out.append(export_design_cut_dxf(design, tmp_path / f"{year}.dxf", folded).read_bytes())
    assert out[0] == out[1]
    annotated = export_design_dxf(design, tmp_path / "a.dxf", folded).read_text()
    guid = [ln for ln in out[0].decode().splitlines()]
    i = guid.index("$FINGERPRINTGUID")
    assert guid[i + 2] not in annotated  # its own GUIDs


def test_refused_blank_writes_nothing_unless_none(tmp_path):
    design, folded = _design(thickness=20.0, bend_radius=20.0, kerf=0.0)
    with pytest.raises(FabricationError):
        export_design_cut_dxf(design, tmp_path / "x.dxf", folded)
    assert list(tmp_path.iterdir()) == []
    path = export_design_cut_dxf(design, tmp_path / "x.dxf", folded, compensation="none")
    pts = ezdxf.readfile(path).modelspace().query("LWPOLYLINE")[0].get_points("xy")
    sheet = design.sheet
    assert np.allclose(np.array(pts)[:, :2], sheet.to_sheet.apply(sheet.vertices), atol=1e-9 * 400)
