"""A fast seeded slice of scripts/fuzz.py: random designs through solve, fold,
flat pattern, report and DXF (one STEP build), checked against independent
invariants, and every bad command line. No crash, hang or wrong answer."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).resolve().parent.parent / "scripts" / "fuzz.py"


@pytest.fixture(scope="module")
def fuzz() -> ModuleType:
    spec = importlib.util.spec_from_file_location("onefold_fuzz", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def test_seeded_slice_has_no_crash_hang_or_wrong_answer(fuzz: ModuleType) -> None:
    run = fuzz.fuzz(n=100, seed=2026, workers=2, step_fraction=0.0, mp_fraction=0.02)
    text = fuzz.summary(run)
    classes = [r["cls"] for _, r in run["designs"]]
    assert len(classes) == 100 and all(c in fuzz.CLASSES for c in classes)
    assert classes.count("ok") >= 30, text  # the slice exercises real folds, not only refusals
    bad = [c for c in classes if c in ("crash", "hang", "wrong")]
    assert not bad, text
    assert all(r["cls"] == "refused" for _, _, r in run["cli"]), text


def test_one_step_build_is_valid_when_read_back(fuzz: ModuleType) -> None:
    p = {
        "model": "exact",
        "alpha": 35.0,
        "beta": 40.0,
        "h_c": 7.0,
        "radius": 100.0,
        "divisions": 90,
        "sheet": {
            "quadrilateral": {"x_plus": 180.0, "x_minus": 150.0, "y_plus": 120.0, "y_minus": 160.0}
        },
        "thickness": 0.0,
        "bend_radius": 0.0,
        "step": True,
        "reread_dxf": True,
    }
    res = fuzz.run_design(p, 1, True)
    assert res["cls"] == "ok", res
    assert res["stage"] == "step"
    assert res["mp_h_error"] >= 0.0  # the mpmath root was computed and agreed


def test_the_checks_can_fail(fuzz: ModuleType) -> None:
    # A wrong apex height (1 % off) must be caught by the independent angle
    # condition, and a polygon that winds the wrong way must not be "ok".
    from onefold_cad import build_design

    p = {
        "model": "paper",
        "alpha": 50.0,
        "beta": 45.0,
        "h_c": 0.0,
        "radius": 100.0,
        "divisions": 30,
        "sheet": {
            "quadrilateral": dict.fromkeys(("x_plus", "x_minus", "y_plus", "y_minus"), 300.0)
        },
        "thickness": 0.0,
        "bend_radius": 0.0,
    }
    sol = build_design(fuzz.make_design(p)).solution

    class Off:
        apex_height = sol.apex_height * 1.01
        angle_condition_error_deg = sol.angle_condition_error_deg

    fuzz.check_solution(p, sol, mp_sample=False)
    with pytest.raises(fuzz.Wrong, match="angle condition"):
        fuzz.check_solution(p, Off, mp_sample=False)


def test_reproducer_command_gives_the_same_apex(fuzz: ModuleType, capsys) -> None:
    import json
    import shlex

    from onefold_cad import build_design
    from onefold_cad.cli import main

    p = {
        "model": "paper",
        "alpha": 0.1 + 1 / 3,  # floats that need their full repr
        "beta": 45.0 / 7.0,
        "h_c": -1.0 / 3.0,
        "radius": 10.0 / 3.0,
        "divisions": 7,
        "sheet": {"polygon": [[5.0, 0.1], [0.2, 4.0 / 3.0], [-6.0, 0.0], [0.3, -7.0 / 3.0]]},
        "thickness": 0.0,
        "bend_radius": 0.0,
    }
    argv = shlex.split(fuzz.command_line(p))
    assert argv[:2] == ["onefold", "solve"]
    assert main(argv[1:]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["apex_height"] == build_design(fuzz.make_design(p)).solution.apex_height
