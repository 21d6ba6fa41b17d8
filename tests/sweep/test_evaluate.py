"""The workers' task: each design's row equals what ``onefold solve --json``
reports for the same flags; a design that fails is a row with its error."""

from __future__ import annotations

import json
import random

import pytest

from onefold_cad.cli.main import main
from onefold_cad.sweep.evaluate import Batch, evaluate_batch, evaluate_design
from onefold_cad.sweep.measures import MEASURES, Column, Measure
from onefold_cad.sweep.plan import make_plan
from onefold_cad.sweep.runner import run_sweep
from onefold_cad.templates import find_template, read_template
from tests.sweep.conftest import table_rows


def _cli_flags(row: dict, plan) -> list[str]:
    out = []
    for s in plan.specs:
        out += [s.flag.flag, str(row[s.dest])]
    return out


def test_three_random_rows_equal_what_solve_json_reports(small_run, capfd):
    plan, folder, _ = small_run
    rows = table_rows(folder)
    for row in random.Random(24).sample(rows, 3):
        capfd.readouterr()
        assert main(["solve", "table1-row1", *_cli_flags(row, plan), "--json"]) == 0
        rep = json.loads(capfd.readouterr().out)
        rest, crease = rep["resting"], rep["crease"]
        assert row["name"] == rep["name"] and row["units"] == rep["units"]
        assert row["apex_height"] == rep["direction_surface"]["apex_height"]
        assert row["height"] == rest["height"] and row["span"] == rest["span"]
        assert row["depth"] == rest["footprint"]["depth"]
        assert row["footprint_area"] == rest["footprint"]["area"]
        assert row["tipping_margin_deg"] == rest["tipping_margin_deg"]
        assert (row["tilt_deg"], row["stable"]) == (rest["tilt_deg"], rest["stable"])
        assert (row["body"], row["touching_points"]) == (rest["body"], rest["touching_points"])
        for half in ("plus_x", "minus_x"):
            assert row[f"fold_angle_{half}_deg"] == rep["fold_angles_deg"][half]
            assert row[f"bend_{half}"] == rep["bend"][half]
            assert row[f"crease_length_{half}"] == crease[half]["length"]
            assert row[f"bend_allowance_{half}"] == crease[half]["bend_allowance"]
            assert row[f"bend_deduction_{half}"] == crease[half]["bend_deduction"]
        assert row["flat_area"] == rep["flat_area"]
        assert row["mass"] == (rep["mass"] or {}).get("value")


def test_the_mass_is_the_report_s_with_a_density(capfd):
    raw = read_template(find_template("patkau-one-fold"))
    row = evaluate_design("patkau-one-fold", raw, {"alpha": 35.0}, ("rest", "mass"))
    capfd.readouterr()
    assert main(["solve", "patkau-one-fold", "--alpha", "35", "--json"]) == 0
    rep = json.loads(capfd.readouterr().out)
    assert row["mass"] == rep["mass"]["value"] and row["mass_unit"] == "kg"
    assert row["name"] == rep["name"] == "patkau-one-fold-alpha35"


def test_a_failing_design_records_its_error_and_the_sweep_goes_on(tmp_path):
    # |h_c| < R cos(alpha) = 17.4 at alpha 80: alone each value is allowed
    plan = make_plan("table1-row1", ["alpha=30,80", "hc=-50,0,50"], images=False)
    run = run_sweep(plan, tmp_path, jobs=1, quiet=True)
    rows = table_rows(tmp_path)
    bad = [r for r in rows if r["status"] == "error"]
    assert run.failed == len(bad) == 2 and len(rows) == 6
    for r in bad:
        assert r["alpha"] == 80.0 and abs(r["hc"]) == 50.0
        assert "--hc: H must lie strictly inside the f-line" in r["error"]
        assert r["height"] is None and r["tipping_margin_deg"] is None
    assert all(r["error"] == "" and r["height"] > 0 for r in rows if r["status"] == "ok")
    data = (tmp_path / "data.csv").read_text().splitlines()
    assert len(data) == 1 + 4  # Design Explorer gets the designs that solved


def test_any_exception_of_a_design_is_its_row_s_error(monkeypatch):
    def boom(design, folded, rest, settings):
        raise ZeroDivisionError("no luck")

    monkeypatch.setitem(
        MEASURES, "boom", Measure("boom", "", (Column("x", "float", "", ""),), boom)
    )
    raw = read_template(find_template("table1-row1"))
    batch = Batch(
        "table1-row1", raw, False, (("k1", {"alpha": 40.0}), ("k2", {})), ("rest", "boom")
    )
    rows = evaluate_batch(batch)
    assert [r["key"] for r in rows] == ["k1", "k2"]
    assert all(r["status"] == "error" and r["error"] == "ZeroDivisionError: no luck" for r in rows)
    assert all(r["x"] is None and r["height"] is None for r in rows)  # nothing half-measured
    assert rows[0]["name"] == "table1-row1-alpha40"


@pytest.mark.parametrize("images", [True])
def test_a_thumbnail_comes_back_as_png_bytes(images):
    raw = read_template(find_template("table1-row1"))
    row = evaluate_design("table1-row1", raw, {}, ("rest",), images=images)
    assert row["png"].startswith(b"\x89PNG\r\n\x1a\n")
