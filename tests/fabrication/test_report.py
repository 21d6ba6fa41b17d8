"""The JSON report: complete, JSON-clean, finite, consistent with the fold, written atomically."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.spatial import ConvexHull

from onefold_cad import (
    Design,
    ExportError,
    FrameCurve,
    Material,
    Model,
    Sheet,
    fold_design,
)
from onefold_cad.export.report_file import write_report
from onefold_cad.fabrication.bend_checks import bend_error, check_bends
from onefold_cad.fabrication.report import (
    REPORT_VERSION,
    check_finite,
    design_report,
    design_warnings,
    report_json,
)
from onefold_cad.fabrication.rules import resting_placement
from onefold_cad.geometry.developability import developability


@pytest.fixture(scope="module")
def steel():
    design = Design(
        "steel",
        FrameCurve(32, 34, h_c=20, divisions=40),
        Sheet.rectangle(600, 400, 0.4),
        material=Material(thickness=2.0, bend_radius=3.0, k_factor=0.4, density=7850.0),
    )
    folded = fold_design(design)
    return design, folded, design_report(design, folded, files=["out/steel.step"])


@pytest.fixture(scope="module")
def paper():
    design = Design(
        "paper",
        FrameCurve(50, 45, divisions=30),
        Sheet.quadrilateral(300, 200, 250, 150),
        model=Model.PAPER,
    )
    folded = fold_design(design)
    return design, folded, design_report(design, folded)


def test_report_is_strict_json_with_the_documented_keys(steel):
    _, _, rep = steel
    again = json.loads(report_json(rep))
    assert again == rep
    assert rep["report_version"] == REPORT_VERSION == 2
    for key in (
        "inputs", "sources", "direction_surface", "angle_condition_error_deg", "gammas_deg",
        "fold_angles_deg", "bend", "relief_hole_diameter", "flat_size", "flat_area",
        "surface_area", "mass", "resting", "developability", "crease", "warnings",
        "timings_s", "files",
    ):  # fmt: skip
        assert key in rep, key
    assert "apex_height" not in rep  # moved under direction_surface, named for what it is
    assert set(rep["fold_angles_deg"]) == {"plus_x", "minus_x"}
    assert set(rep["timings_s"]) == {"direction_surface", "final_surface"}
    assert rep["files"] == ["steel.step"]
    assert rep["inputs"]["frame"]["alpha"] == 32.0
    assert rep["inputs"]["sheet"]["rectangle"]["apex_fraction"] == 0.4
    assert rep["warnings"] == []


def test_direction_surface_height_is_the_paper_s_h_at_frame_radius(steel):
    design, folded, rep = steel
    ds = rep["direction_surface"]
    assert ds["apex_height"] == folded.solution.apex_height > 0
    assert ds["frame_radius"] == design.frame.radius == 100.0
    assert ds["apex"] == [0.0, 0.0, ds["apex_height"]]
    assert "frame curve of radius R" in ds["meaning"]


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


def _dense_resting_form(design, folded, per_edge: int) -> np.ndarray:
    """The resting form's outline and apex, sampled here: ``per_edge`` points
    on each edge of the flat sheet and the rulings' ends (where the paper
    model's folded outline has its kinks), folded by the fold map, then moved
    by the design's resting placement (p' = R p + T)."""
    v = folded.sheet.vertices
    t = np.arange(per_edge)[:, None] / per_edge
    edges = [a + (b - a) * t for a, b in zip(v, np.roll(v, -1, axis=0), strict=True)]
    flat = np.vstack([*edges, folded.rulings_flat[:, 1]])
    pts = np.vstack([folded.map_points(flat), folded.apex])
    place = resting_placement(design, folded)
    rot, move = place.rotation, place.translation
    np.testing.assert_allclose(rot @ rot.T, np.eye(3), atol=1e-15)  # a rotation ...
    assert np.linalg.det(rot) == pytest.approx(1.0, abs=1e-15)  # ... not a reflection
    return np.einsum("ij,kj->ki", rot, pts) + move


def test_resting_section_is_the_placement_the_step_is_written_in(steel):
    design, folded, rep = steel
    rest = rep["resting"]
    place = resting_placement(design, folded)
    assert rest["body"] == place.body == "solid"  # exact model with a thickness
    assert rest["span"] == rest["footprint"]["width"] == place.width
    assert rest["height"] == place.height > 0
    assert rest["apex"] == pytest.approx(place.apply(folded.apex[None, :])[0].tolist())
    # The centre of mass lies over the support polygon when the margin is positive.
    assert rest["stable"] == (rest["tipping_margin_deg"] > 0)


def test_shell_resting_box_height_and_footprint_from_a_dense_outline(paper):
    """A zero-thickness paper-model sheet stands as its reference surface. Its
    outline is straight between ruling ends, sampled here 50 000 points per
    sheet edge: its box agrees with the report's to 1e-9 of the sheet's size."""
    design, folded, rep = paper
    rest = rep["resting"]
    assert rest["body"] == "shell"
    size = folded.sheet.size
    dense = _dense_resting_form(design, folded, 50_000)
    lo, hi = np.array(rest["bounding_box"]["min"]), np.array(rest["bounding_box"]["max"])
    np.testing.assert_allclose(lo, dense.min(axis=0), rtol=0, atol=1e-9 * size)
    np.testing.assert_allclose(hi, dense.max(axis=0), rtol=0, atol=1e-9 * size)
    assert abs(dense[:, 2].min()) < 1e-9 * size  # it stands on the ground, nothing below
    height, width, depth = (dense.max(axis=0) - dense.min(axis=0))[[2, 0, 1]]
    assert rest["height"] == pytest.approx(height, rel=0, abs=1e-9 * size)
    assert rest["footprint"]["width"] == pytest.approx(width, rel=0, abs=1e-9 * size)
    assert rest["footprint"]["depth"] == pytest.approx(depth, rel=0, abs=1e-9 * size)
    # Footprint area: qhull (an independent hull) on the dense ground points.
    assert rest["footprint"]["area"] == pytest.approx(ConvexHull(dense[:, :2]).volume, rel=1e-9)


def test_areas_sizes_and_mass(steel):
    design, folded, rep = steel
    assert rep["sheet"]["size"] == pytest.approx([600, 400], rel=1e-12)
    assert rep["sheet"]["area"] == pytest.approx(600 * 400, rel=1e-12)
    assert rep["surface_area"] == developability(folded).area_3d
    hole = rep["relief_hole_diameter"]
    assert hole == 2 * (2.0 + 3.0)  # the default: max(3 t, 2 (t + r)) = 10
    assert 0 < rep["solid_min_relief_hole"] < hole  # the default hole is wide enough
    # The cut part loses the bend deductions and the hole, so it is smaller.
    assert rep["flat_area"] < 600 * 400 - math.pi * hole**2 / 4
    assert rep["flat_size"][0] <= 600 + 1e-9 and rep["flat_size"][1] <= 400 + 1e-9
    # 7850 kg/m^3 x 2 mm x flat area (mm^2) x 1e-9 m^3 per mm^3.
    assert rep["mass"] == {
        "value": pytest.approx(7850.0 * 2.0 * rep["flat_area"] * 1e-9, rel=1e-14),
        "unit": "kg",
        "density": 7850.0,
    }


def test_paper_model_reports_its_gammas(paper, steel):
    design, folded, rep = paper
    gam = np.array(rep["gammas_deg"])
    assert gam.shape == (design.frame.divisions,)
    # The angle condition: one side's apex angles add up to 180 deg.
    assert abs(gam.sum() - 180.0) <= 1e-9
    assert rep["angle_condition_error_deg"] <= 1e-9
    assert steel[2]["gammas_deg"] is None  # exact model: no fan
    assert rep["relief_hole_diameter"] == 0.0
    assert rep["solid_min_relief_hole"] is None  # paper model: no solid
    assert rep["mass"] is None


def test_a_flat_pattern_past_the_bend_limits_is_a_warning():
    """Past the bend model's limits the report keeps the geometry, describes the
    uncompensated blank (what --compensation none would write) and the
    warning names the limit it passes."""
    design = Design(
        "corner",
        FrameCurve(60, 70),
        Sheet.rectangle(40, 100, 0.5),
        material=Material(thickness=3.57, bend_radius=6.0),
    )
    folded = fold_design(design)
    rep = design_report(design, folded)
    assert rep["flat_pattern"]["compensation"] == "none"
    assert rep["flat_pattern"]["shift"] == 0.0 and rep["flat_pattern"]["bend_problems"]
    # the uncompensated blank is the designed sheet less the relief hole
    hole = rep["flat_pattern"]["hole_diameter"]
    assert abs(rep["flat_area"] - (40 * 100 - math.pi * hole**2 / 4)) <= 1e-9 * 4000
    assert rep["direction_surface"]["apex_height"] > 0 and rep["resting"]["height"] > 0
    bends = [w for w in rep["warnings"] if w.startswith("bend_radius: ")]
    assert len(bends) == 1 and "build refuses the DXF" in bends[0]
    json.loads(report_json(rep))


def _corner_design() -> tuple[Design, object]:
    design = Design("corner", FrameCurve(60, 70), Sheet.rectangle(40, 100, 0.5),
                    material=Material(thickness=3.57, bend_radius=6.0))  # fmt: skip
    return design, fold_design(design)


def test_the_bend_warning_says_what_build_does_with_the_compensation():
    """'sharp' (solve, and build by default): the flat pattern's files and a STEP solid
    are refused. 'none': build writes the uncompensated blank and the STEP; the warning
    says so and refuses nothing. The limit's own line is the same."""
    design, folded = _corner_design()
    error = str(bend_error(check_bends(folded, design.material, design.units)))
    stability = resting_placement(design, folded).to_data()["warnings"]  # its own, if any
    *rest1, sharp = design_warnings(design, folded)
    *rest2, none = design_warnings(design, folded, "none")
    assert len(rest1) == len(stability) and rest1 == rest2
    assert sharp == (
        f"{error}; build refuses the DXF, cut DXF, bend sheet and flat preview and a STEP "
        "solid and its GLB (--compensation none writes the uncompensated blank)"
    )
    assert none == (
        f"{error}; with --compensation none build writes the uncompensated blank (the "
        "designed outline; its notes say so) and the STEP as designed"
    )
    rep = design_report(design, folded, compensation="none")
    assert rep["warnings"] == [*rest2, none] and rep["flat_pattern"]["compensation"] == "none"


def test_a_width_problem_alone_does_not_refuse_the_solid():
    """The blank's width limit is the flat pattern's: the STEP solid is the designed
    part, so the warning does not list it."""
    design = Design("asym", FrameCurve(5, 60, -60), Sheet.quadrilateral(3000, 1000, 2000, 1500),
                    material=Material(thickness=10.0, bend_radius=10.0))  # fmt: skip
    folded = fold_design(design)
    assert {p.kind for p in check_bends(folded, design.material, design.units)} == {"width"}
    (w,) = design_warnings(design, folded)
    assert w.endswith("build refuses the DXF, cut DXF, bend sheet and flat preview "
                      "(--compensation none writes the uncompensated blank)")  # fmt: skip


def test_a_default_relief_hole_that_does_not_fit_is_one_warning():
    """t = 1100 on a 3000 mm square with H at its centre: the default hole
    max(3 t, 2 (t + r)) = 3300 exceeds 2 x 1500, the sheet's width about H. One
    warning says so (named after the thickness), not a second one from the
    flat pattern's own check of the same hole."""
    design = Design(
        "thick",
        FrameCurve(3, 3),
        Sheet.rectangle(3000, 3000, 0.5),
        material=Material(thickness=1100.0, bend_radius=0.0),
    )
    rep = design_report(design, fold_design(design))
    holes = [w for w in rep["warnings"] if "relief hole" in w or "relief_hole" in w]
    assert len(holes) == 1 and holes[0].startswith("thickness: "), rep["warnings"]
    assert "3300 mm must be < 3000 mm" in holes[0]


def test_given_warnings_sources_and_timings_are_reported(paper):
    design, folded, _ = paper
    rep = design_report(
        design,
        folded,
        sources={"material.thickness": "--thickness"},
        timings={"step": 1.5},
        warnings=["stability: example"],
    )
    assert rep["sources"] == {"material.thickness": "--thickness"}
    assert rep["timings_s"]["step"] == 1.5
    assert rep["warnings"] == ["stability: example"]


def test_check_finite_names_the_key():
    rep = {"name": "x", "a": {"b": [1.0, 2.0, {"c": float("nan")}]}}
    with pytest.raises(ExportError, match=r"a\.b\[2\]\.c = nan"):
        check_finite(rep)
    with pytest.raises(ExportError, match=r"resting\.height = inf"):
        report_json({"name": "x", "resting": {"height": float("inf")}})
    check_finite({"name": "x", "ok": [1.0, None, "text", {"n": 3}]})


def test_write_report_atomically(tmp_path, paper):
    rep = paper[2]
    out = write_report(tmp_path / "paper.json", rep)
    assert json.loads(out.read_text()) == rep
    assert sorted(p.name for p in tmp_path.iterdir()) == ["paper.json"]


def test_write_report_leaves_nothing_on_failure(tmp_path, paper):
    bad = dict(paper[2], surface_area=float("nan"))
    with pytest.raises(ExportError, match="surface_area = nan"):
        write_report(tmp_path / "bad.json", bad)
    with pytest.raises(ExportError):
        write_report(tmp_path / "missing-dir" / "r.json", paper[2])
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(("hole", "kerf"), [(0.0, 0.0), (6.0, 0.0), (6.0, 0.5)])
def test_the_cut_length_is_the_blank_s_perimeter_and_the_hole_s_circle(hole, kerf):
    from onefold_cad.templates import load_template

    base = load_template("paper-square")  # 200 x 200 mm, folded along its diagonal
    design = base.with_changes(material=base.material.with_changes(relief_hole=hole, kerf=kerf))
    rep = design_report(design, fold_design(design), compensation="none")
    # uncompensated: the designed square, offset outwards by kerf/2 (its corners rounded
    # or mitred: between the two), and the hole's cutting circle of diameter hole - kerf
    side = 200.0 + kerf
    circle = math.pi * (hole - kerf) if hole else 0.0
    got = rep["flat_pattern"]["cut_length"]
    lo, hi = 4 * 200.0 + math.pi * kerf, 4 * side
    assert lo - 1e-9 <= got - circle <= hi + 1e-9
    if kerf == 0.0:
        assert got == pytest.approx(800.0 + circle, rel=1e-12)
