"""The bend sheet: the CSV and the text table, against the blank and the hand model."""

from __future__ import annotations

import csv
import math
import re

import numpy as np
import pytest

from onefold_cad import Design, ExportError, FrameCurve, Material, Sheet, fold_design
from onefold_cad.export.bend_csv import write_bend_csv
from onefold_cad.export.dxf.notes import flat_pattern_notes
from onefold_cad.fabrication.bend_table import BendRow, bend_rows, bend_table
from onefold_cad.fabrication.flat_pattern import flat_pattern
from tests.hand_bend import arc_point, fan_folds, hand_bend

TEXT_FIELDS = ("half", "direction", "inside_face", "reference", "compensation", "material", "units")
MAT = Material(thickness=2.0, bend_radius=3.0, k_factor=0.44, relief_hole=10.0,
               sheet_surface="OUTSIDE", name="S235, 2 mm")  # fmt: skip


@pytest.fixture(scope="module")
def asym():
    """H off the f-line's middle: the halves fold differently."""
    design = Design("asym", FrameCurve(32, 34, 20, 100, 90), Sheet.rectangle(600, 400, 0.4),
                    material=MAT)  # fmt: skip
    folded = fold_design(design)
    return design, folded, flat_pattern(design, folded)


def test_csv_rows_are_the_hand_model_and_the_blank(tmp_path, asym):
    design, folded, pattern = asym
    path = write_bend_csv(pattern, tmp_path / "asym-bends.csv")
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["half"] for r in rows] == ["plus_x", "minus_x"]
    # each rounded column names its step in the header: "length [0.01 mm]"
    assert [k.split(" [")[0] for k in rows[0]] == [f for f in BendRow.__dataclass_fields__]
    steps = {k.split(" [")[0]: k.split(" [")[1] for k in rows[0] if " [" in k}
    assert steps["fold_angle_deg"] == "0.01 deg]" and steps["length"] == "0.01 mm]"
    assert "thickness" not in steps  # the material's values as given
    for row in rows:  # 0.01 (mm or deg) at most: no 16-digit floats
        for key, value in row.items():
            if " [" in key:
                assert re.fullmatch(r"-?\d+\.\d\d", value), (key, value)
    rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in rows]
    half_step = 0.005 + 1e-9  # the rounding, with the float's own
    hb = [hand_bend(h.fold_angle_deg, h.bend, "OUTSIDE", 2.0, 3.0, 0.44) for h in folded.crease]
    used = (hb[0]["shift"] + hb[1]["shift"]) / 2
    for row, half, b in zip(rows, folded.crease, hb, strict=True):
        num = {k: float(v) for k, v in row.items() if k not in TEXT_FIELDS}
        assert row["direction"] == half.bend
        assert row["inside_face"] == ("top" if half.bend == "UP" else "bottom")
        assert row["reference"] == {0.0: "INSIDE", 1.0: "OUTSIDE"}[b["s"]]
        assert num["fold_angle_deg"] == pytest.approx(half.fold_angle_deg, abs=half_step)
        assert num["included_angle_deg"] == pytest.approx(180 - half.fold_angle_deg, abs=half_step)
        for key, hand in (("setback", "sb"), ("allowance", "ba"), ("deduction", "bd"),
                          ("shift", "shift")):  # fmt: skip
            assert num[key] == pytest.approx(b[hand], abs=half_step)
        assert num["shift_used"] == pytest.approx(used, abs=half_step)
        assert num["width_error"] == pytest.approx(2 * (b["shift"] - used), abs=half_step)
        assert (num["inside_radius"], num["thickness"], num["k_factor"]) == (3.0, 2.0, 0.44)
        assert (row["material"], row["units"], row["compensation"]) == ("S235, 2 mm", "mm", "sharp")
        # the bend line on the blank: from the hole's edge, along the fold line, to the outline
        start = np.array([num["start_x"], num["start_y"]])
        end = np.array([num["end_x"], num["end_y"]])
        assert np.linalg.norm(start - pattern.apex) == pytest.approx(5.0, abs=2 * half_step)
        d = design.sheet.to_sheet.apply_direction(half.end_flat[None, :])[0]
        d /= np.linalg.norm(d)
        for p in (start, end):
            v = p - pattern.apex
            assert abs(v[0] * d[1] - v[1] * d[0]) < 2 * half_step and v @ d > 0
        out = pattern.outline
        a, bb = out, np.roll(out, -1, axis=0)
        e = bb - a
        u = np.clip(((end - a) * e).sum(1) / (e * e).sum(1), 0, 1)
        assert np.min(np.linalg.norm(a + u[:, None] * e - end, axis=1)) < 2 * half_step
        assert num["length"] == pytest.approx(float(np.linalg.norm(end - start)), abs=3 * half_step)


def test_table_has_a_line_per_half_and_is_in_the_notes(asym):
    _, folded, pattern = asym
    table = bend_table(pattern)
    lines = table.splitlines()
    assert "S235, 2 mm" in lines[0] and "t = 2" in lines[0]
    for half in folded.crease:
        line = next(ln for ln in lines if ln.startswith(half.name + ":"))
        assert f"fold {half.fold_angle_deg:.2f}" in line
        assert f"included {180 - half.fold_angle_deg:.2f}" in line
    for line in lines:
        assert line in flat_pattern_notes(pattern)


def test_the_crease_is_set_past_its_fold_by_the_overbend_and_the_table_says_so(tmp_path, asym):
    from dataclasses import replace

    design, folded, _ = asym
    over = design.with_changes(material=replace(MAT, crease_overbend=4.25))
    pattern = flat_pattern(over, folded)
    rows = bend_rows(pattern)
    lines = bend_table(pattern).splitlines()
    for half, row in zip(folded.crease, rows, strict=True):
        assert row.fold_angle_deg == pytest.approx(half.fold_angle_deg, abs=1e-9)  # the cones
        assert row.fold_to_deg == pytest.approx(half.fold_angle_deg + 4.25, abs=1e-9)
        line = next(ln for ln in lines if ln.startswith(half.name + ":"))
        assert f"set to {half.fold_angle_deg + 4.25:.2f} (overbend +4.25)" in line
    # the bend lines' labels on the drawing, and the notes, give the angle to set
    for fh, half in zip(pattern.halves, folded.crease, strict=True):
        want = f"{half.bend} {half.fold_angle_deg:.2f} deg, set to {half.fold_angle_deg + 4.25:.2f}"
        assert fh.label == want
        side = "+x" if half.name == "plus_x" else "-x"
        assert f"fold half {side}: {want} (layer BEND_{half.bend})" in flat_pattern_notes(pattern)
    with (write_bend_csv(pattern, tmp_path / "o.csv")).open(newline="") as f:
        got = [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(f)]
    assert [float(r["fold_to_deg"]) for r in got] == pytest.approx(
        [h.fold_angle_deg + 4.25 for h in folded.crease], abs=0.005 + 1e-9
    )
    # without an overbend the crease is set to its fold angle, and the table says nothing more
    plain = bend_rows(flat_pattern(design, folded))
    assert [r.fold_to_deg for r in plain] == [r.fold_angle_deg for r in plain]
    assert "set to" not in bend_table(flat_pattern(design, folded))
    assert all("set to" not in h.label for h in flat_pattern(design, folded).halves)


def test_from_a_design_atomic_and_nothing_on_failure(tmp_path, asym):
    design, folded, pattern = asym
    a = write_bend_csv(design, tmp_path / "a.csv").read_text()
    assert a == write_bend_csv(pattern, tmp_path / "b.csv").read_text()
    with pytest.raises(ExportError):
        write_bend_csv(pattern, tmp_path / "missing" / "c.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]
    none = write_bend_csv(design, tmp_path / "n.csv", folded, compensation="none").read_text()
    shift_used = [f.split(" [")[0] for f in none.splitlines()[0].split(",")].index("shift_used")
    assert ",none," in none and float(none.splitlines()[1].split(",")[shift_used]) == 0.0


def test_the_paper_fans_ruling_folds_are_rows_too():
    """A 2-division paper fan: one ruling fold per side (the middle division ray), a
    real fold of the two planar triangles. Each gets a row after the crease halves: its
    angle and direction by hand (from the frame curve and the apex), the hand bend
    model, shift_used 0 and width error 2 x shift (the blank does not compensate it);
    build's printed table sums them up in one line."""
    frame = FrameCurve(5.0, 10.0, 0.5 * 100.0 * math.cos(math.radians(5.0)), 100.0, 2)
    mat = Material(thickness=1.0, bend_radius=0.0, k_factor=0.33, name="paper")
    design = Design("fan", frame, Sheet.quadrilateral(60, 340, 300, 280), model="paper",
                    material=mat)  # fmt: skip
    folded = fold_design(design)
    pattern = flat_pattern(design, folded)
    a = math.radians(frame.alpha)
    pts = [arc_point(frame.alpha, frame.beta, frame.h_c, frame.radius, p)
           for p in (-a, math.pi / 2, math.pi + a)]  # fmt: skip
    ((angle, direction),) = fan_folds(pts, folded.apex)
    hb = hand_bend(angle, direction, "MID", 1.0, 0.0, 0.33)
    rows = bend_rows(pattern)
    assert [r.half for r in rows] == ["plus_x", "minus_x", "+y ruling 1", "-y ruling 1"]
    for r in rows[2:]:
        assert (r.direction, r.compensation, r.shift_used) == (direction, "none", 0.0)
        assert r.fold_angle_deg == pytest.approx(angle, abs=1e-9)
        assert r.setback == pytest.approx(hb["sb"], rel=1e-9)
        assert r.allowance == pytest.approx(hb["ba"], rel=1e-9)
        assert r.width_error == pytest.approx(2 * hb["shift"], rel=1e-9)
    short = bend_table(pattern, rulings=False).splitlines()
    assert not any(ln.startswith("+y ruling") for ln in short)
    assert short[-1].startswith(f"2 ruling folds (paper model): {angle:.2f} to {angle:.2f} deg")
    assert any(ln.startswith("+y ruling 1: ") for ln in bend_table(pattern).splitlines())
