"""The measures' registry: ``--measure simulate`` gives each design the values
``onefold simulate --json`` reports for the same flags and settings, and a
sweep resumes a design only with the settings it was simulated with."""

from __future__ import annotations

import json
from dataclasses import replace

import pyarrow.parquet as pq
import pytest

from onefold_cad.cli.main import main
from onefold_cad.flags.parser import UsageError
from onefold_cad.sweep.evaluate import evaluate_design
from onefold_cad.sweep.measures import MEASURES, measure_help
from onefold_cad.sweep.plan import SIMULATION_SETTINGS, make_plan
from onefold_cad.sweep.runner import run_sweep
from onefold_cad.templates import find_template, read_template
from tests.sweep.conftest import table_rows

#: ``onefold simulate``'s flags for each setting.
_FLAGS = {"supports": "--supports", "reference": "--reference", "crease": "--crease",
          "law": "--law", "mesh": "--mesh"}  # fmt: skip


def _simulate_json(capfd, flags: list[str], settings: dict) -> dict:
    args = [a for k, v in settings.items() if k != "check" for a in (_FLAGS[k], v)]
    args.append("--check" if settings["check"] else "--no-check")
    capfd.readouterr()
    assert main(["simulate", "patkau-one-fold", *flags, *args, "--json", "-q"]) == 0
    return json.loads(capfd.readouterr().out)["simulation"]


@pytest.mark.parametrize(
    "settings",
    [
        # formed, sprung back and standing, with the mesh check (sim_mesh_change)
        {
            "supports": "anchored",
            "reference": "flat",
            "crease": "held",
            "law": "moment",
            "mesh": "coarse",
            "check": True,
        },
        # the designed form as stress-free, the crease elastic: the designed columns
        {
            "supports": "anchored",
            "reference": "designed",
            "crease": "elastic",
            "law": "moment",
            "mesh": "coarse",
            "check": False,
        },
    ],  # fmt: skip
)
def test_a_simulated_row_is_what_simulate_json_reports(capfd, settings):
    raw = read_template(find_template("patkau-one-fold"))
    row = evaluate_design(
        "patkau-one-fold", raw, {"thickness": 4.0}, ("rest", "simulate"), settings=settings
    )
    assert row["status"] == "ok", row["error"]
    sim = _simulate_json(capfd, ["--thickness", "4"], settings)
    assert (sim["supports"], sim["reference"], sim["crease"]) == (
        settings["supports"], settings["reference"], settings["crease"])  # fmt: skip
    formed, released = sim.get("formed") or {}, sim.get("released") or {}
    standing, designed = sim["standing"], sim.get("designed") or {}
    assert row["sim_weight_N"] == sim["weight_N"] and row["sim_nodes"] == sim["mesh"]["nodes"]
    assert row["sim_mesh_change"] == (sim["convergence"] or {}).get("max_deviation_change")
    assert (row["sim_mesh_change"] is not None) == settings["check"]
    assert row["formed_bending_energy_J"] == formed.get("bending_energy_J")
    assert row["formed_plastic_share"] == formed.get("plastic_area_share")
    assert row["released_max_deviation"] == released.get("max_deviation")
    assert row["released_rms_deviation"] == released.get("rms_deviation")
    assert row["standing_stands"] == standing["stands"]
    assert row["standing_reason"] == (standing["reason"] or "")
    for key in ("load_factor", "max_deviation", "rms_deviation", "max_displacement", "height",
                "tipping_margin_deg", "max_stress_MPa", "utilisation"):  # fmt: skip
        assert row[f"standing_{key}"] == standing[key], key
    assert row["designed_max_displacement"] == designed.get("max_displacement")
    assert row["designed_max_stress_MPa"] == designed.get("max_stress_MPa")
    assert row["sim_warnings"] == len(sim["warnings"])
    # each reference fills its own stages' columns, and only those
    flat = settings["reference"] == "flat"
    assert (row["formed_plastic_share"] is not None) == flat
    assert (row["released_max_deviation"] is not None) == flat
    assert (row["designed_max_stress_MPa"] is not None) == (not flat)
    assert set(row) >= {c.name for c in MEASURES["simulate"].columns}


def test_the_settings_default_to_simulate_s_and_need_the_measure():
    plan = make_plan("patkau-one-fold", ["thickness=3,4"], measures=["simulate"], images=False)
    assert plan.settings == {"supports": "anchored", "reference": "flat", "crease": "held",
                             "law": "j2", "mesh": "normal", "check": True}  # fmt: skip
    coarse = make_plan("patkau-one-fold", ["thickness=3,4"], measures=["simulate"],
                       simulation={"mesh": "coarse"})  # fmt: skip
    assert coarse.settings["check"] is False  # as `onefold simulate --mesh coarse`
    assert tuple(coarse.settings) == SIMULATION_SETTINGS
    assert make_plan("patkau-one-fold", ["thickness=3,4"]).settings == {}
    with pytest.raises(UsageError, match="^--supports: is a setting of --measure simulate"):
        make_plan("patkau-one-fold", ["thickness=3,4"], simulation={"supports": "frictionless"})
    with pytest.raises(UsageError, match="^--mesh: mesh_level: must be one of coarse"):
        make_plan("patkau-one-fold", ["alpha=30"], measures=["simulate"],
                  simulation={"mesh": "medium"})  # fmt: skip


def test_a_varied_value_simulate_cannot_take_is_refused_before_any_design_runs():
    with pytest.raises(UsageError, match=r"^--vary model=exact,paper: model: simulate needs"):
        make_plan("patkau-one-fold", ["model=exact,paper"], measures=["simulate"])
    # allowed without the measure: the paper model solves, folds and stands
    assert len(make_plan("patkau-one-fold", ["model=exact,paper"]).points) == 2


def test_a_rerun_with_other_settings_simulates_again(tmp_path, monkeypatch):
    """The journal keeps each row's settings: the same settings resume, others
    simulate every design again (the real simulation is the test above's)."""
    seen = []

    def fake(design, folded, rest, settings):
        seen.append(dict(settings))
        return {"sim_weight_N": 1.0 if settings["supports"] == "anchored" else 2.0,
                "standing_max_stress_MPa": 3.0, "standing_stands": True}  # fmt: skip

    monkeypatch.setitem(MEASURES, "simulate", replace(MEASURES["simulate"], compute=fake))

    def run(**simulation):
        plan = make_plan("patkau-one-fold", ["alpha=30,40"], measures=["simulate"],
                         images=False, simulation=simulation)  # fmt: skip
        return plan, run_sweep(plan, tmp_path, jobs=1, quiet=True)

    plan, first = run(mesh="coarse")
    assert first.evaluated == 2 and [s["mesh"] for s in seen] == ["coarse", "coarse"]
    assert run(mesh="coarse")[1].evaluated == 0  # the same settings: resumed
    plan, other = run(mesh="coarse", supports="frictionless")
    assert other.evaluated == 2 and other.skipped == 0
    assert [r["sim_weight_N"] for r in table_rows(tmp_path)] == [2.0, 2.0]
    table = pq.read_table(tmp_path / "results.parquet")
    unit = {f.name: f.metadata[b"unit"].decode() for f in table.schema}
    assert (unit["sim_weight_N"], unit["standing_max_stress_MPa"]) == ("N", "MPa")
    assert unit["standing_max_deviation"] == "mm" and unit["formed_bending_energy_J"] == "J"
    meta = json.loads(table.schema.metadata[b"onefold.sweep"])
    assert meta["simulation"] == plan.settings and meta["measures"] == ["rest", "simulate"]


def test_the_help_lists_every_measure_with_its_columns():
    text = measure_help()
    for m in MEASURES.values():
        assert f"  {m.name} " in text
        assert all(c.name in text for c in m.columns)
