"""The JSON report: complete, JSON-clean, consistent with the fold, written atomically."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from onefold_cad import (
    Design,
    ExportError,
    FrameCurve,
    Material,
    Model,
    Sheet,
    build_design,
)
from onefold_cad.export.report import design_report, report_json, write_report


@pytest.fixture(scope="module")
def steel():
    design = Design(
        "steel",
        FrameCurve(32, 34, h_c=20, divisions=40),
        Sheet.rectangle(600, 400, 0.4),
        material=Material(thickness=2.0, bend_radius=3.0, k_factor=0.4, density=7.85e-6),
    )
    folded = build_design(design)
    return design, folded, design_report(design, folded, files=["out/steel.step"])


@pytest.fixture(scope="module")
def paper():
    design = Design(
        "paper",
        FrameCurve(50, 45, divisions=30),
        Sheet.quadrilateral(300, 200, 250, 150),
        model=Model.PAPER,
    )
    folded = build_design(design)
    return design, folded, design_report(design, folded)


def test_report_is_strict_json_with_the_issue_s_keys(steel):
    _, _, rep = steel
    again = json.loads(report_json(rep))
    assert again == rep
    for key in (
        "inputs",
        "apex_height",
        "angle_condition_error_deg",
        "gammas_deg",
        "fold_angles_deg",
        "bend",
        "relief_hole_diameter",
        "flat_size",
        "flat_area",
        "surface_area",
        "resting",
        "developability",
        "crease",
        "timings_s",
        "files",
    ):
        assert key in rep, key
    assert set(rep["fold_angles_deg"]) == {"plus_x", "minus_x"}
    assert set(rep["timings_s"]) == {"direction_surface", "final_surface"}
    assert rep["files"] == ["steel.step"]
    assert rep["inputs"]["frame"]["alpha"] == 32.0
    assert rep["inputs"]["sheet"]["rectangle"]["apex_fraction"] == 0.4


def test_fold_angles_and_bend_values_per_half(steel):
    design, folded, rep = steel
    t, r, k = 2.0, 3.0, 0.4
    for half in folded.crease:
        entry = rep["crease"][half.name]
        assert rep["fold_angles_deg"][half.name] == entry["fold_angle_deg"] == half.fold_angle_deg
        assert rep["bend"][half.name] == half.bend in ("UP", "DOWN")
        psi = math.radians(entry["fold_angle_deg"])
        ba = psi * (r + k * t)
        sb = (r + t / 2) * math.tan(psi / 2)  # the MID reference surface's setback
        assert entry["bend_allowance"] == pytest.approx(ba, rel=1e-12)
        assert entry["bend_deduction"] == pytest.approx(2 * sb - ba, rel=1e-12)
    # An asymmetric design (H off the f-line's midpoint) folds its halves differently.
    a, b = rep["fold_angles_deg"].values()
    assert abs(a - b) > 0.1


def test_resting_form_stands_on_the_ground(steel):
    _, folded, rep = steel
    rest = rep["resting"]
    lo, hi = np.array(rest["bounding_box"]["min"]), np.array(rest["bounding_box"]["max"])
    size = folded.sheet.size
    assert abs(lo[2]) < 1e-9 * size
    assert rest["height"] == pytest.approx(hi[2] - lo[2])
    assert rest["footprint"]["width"] == pytest.approx(hi[0] - lo[0])
    assert 0 < rest["footprint"]["area"] <= rest["footprint"]["width"] * rest["footprint"]["depth"]
    # The folded form is a rigid copy of the flat sheet: it fits in the sheet's disc about H.
    assert np.linalg.norm(hi - lo) <= 2 * size * (1 + 1e-9)


def test_areas_sizes_and_mass(steel):
    design, _, rep = steel
    assert rep["sheet"]["size"] == pytest.approx([600, 400])
    assert rep["sheet"]["area"] == pytest.approx(600 * 400)
    # Developable: the folded surface keeps the sheet's area.
    assert rep["surface_area"] == pytest.approx(600 * 400, rel=1e-3)
    hole = rep["relief_hole_diameter"]
    assert hole == design.material.relief_hole_diameter > 0
    assert 0 < rep["solid_min_relief_hole"] < hole  # the default hole is wide enough
    # The cut part loses the bend deductions and the hole, so it is smaller.
    assert rep["flat_area"] < 600 * 400 - math.pi * hole**2 / 4 + 1e-6
    assert rep["flat_size"][0] <= 600 + 1e-9 and rep["flat_size"][1] <= 400 + 1e-9
    assert rep["mass"] == pytest.approx(7.85e-6 * 2.0 * rep["flat_area"])
    dev = rep["developability"]
    assert dev["area_rel_error"] < 1e-3 and dev["boundary_length_rel_error"] < 1e-3


def test_paper_model_reports_its_gammas(paper, steel):
    design, folded, rep = paper
    gam = np.array(rep["gammas_deg"])
    assert gam.shape == (design.frame.divisions,)
    # The angle condition: one side's apex angles add up to 180 deg.
    assert gam.sum() == pytest.approx(180.0, abs=1e-6)
    assert rep["angle_condition_error_deg"] < 1e-6
    assert steel[2]["gammas_deg"] is None  # exact model: no fan
    assert rep["apex_height"] == folded.solution.apex_height > 0
    assert rep["relief_hole_diameter"] == 0.0
    assert rep["solid_min_relief_hole"] is None  # paper model: no solid
    assert rep["mass"] is None


def test_write_report_atomically(tmp_path, paper):
    rep = paper[2]
    out = write_report(tmp_path / "paper.json", rep)
    assert json.loads(out.read_text()) == rep
    assert sorted(p.name for p in tmp_path.iterdir()) == ["paper.json"]


def test_write_report_leaves_nothing_on_failure(tmp_path, paper):
    bad = dict(paper[2], apex_height=float("nan"))
    with pytest.raises(ExportError):
        write_report(tmp_path / "bad.json", bad)
    with pytest.raises(ExportError):
        write_report(tmp_path / "missing-dir" / "r.json", paper[2])
    assert list(tmp_path.iterdir()) == []
