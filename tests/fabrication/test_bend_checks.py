"""The bend model's limits on a fold (fabrication/bend_checks.py) at the end
of the range: a crease folded flat onto itself (beta within rounding of 90
deg) is a bend problem naming beta, which solve warns about and every writer
of the blank refuses, whatever the compensation; solve still answers."""

from __future__ import annotations

import json
import math

import pytest

from onefold_cad import fold_design
from onefold_cad.errors import FabricationError
from onefold_cad.fabrication.bend_checks import check_bends
from onefold_cad.fabrication.flat_pattern import flat_pattern
from onefold_cad.fabrication.rules import resting_placement, solid_problem
from onefold_cad.flags.jobs import load_jobs
from tests.cli.test_main import run

#: beta a rounding error short of 90 deg: the crease folds 180.0 deg exactly,
#: and 1e-7 deg short: a fold too close to flat for the solid's mitre.
CLOSED, NEAR = math.nextafter(90.0, 0.0), 89.9999999


def _design(beta: float, **flags):
    (job,) = load_jobs(["patkau-one-fold"], {"alpha": 71.0, "beta": beta, **flags}, None)
    return job.design


@pytest.mark.parametrize("thickness", [0.0, 3.57])
def test_a_crease_folded_onto_itself_is_a_problem_naming_beta(thickness):
    design = _design(CLOSED, thickness=thickness)
    folded = fold_design(design)
    assert [c.fold_angle_deg for c in folded.crease] == [180.0, 180.0]
    problems = check_bends(folded, design.material, design.units)
    assert [(p.half, p.kind, p.parameter) for p in problems] == [
        ("plus_x", "closed", "beta"), ("minus_x", "closed", "beta")]  # fmt: skip
    for comp in ("sharp", "none"):  # no compensation gives it a bend
        with pytest.raises(FabricationError, match="^beta: plus_x: folds 180 deg"):
            flat_pattern(design, folded, comp)


def test_solve_answers_with_warnings_and_build_refuses_in_one_line(tmp_path):
    proc = run("solve", "patkau-one-fold", "--alpha", "71", "--beta", repr(CLOSED), "--json")
    assert proc.returncode == 0, proc.stderr
    rep = json.loads(proc.stdout)
    assert rep["crease"]["plus_x"]["bend_allowance"] is None
    assert rep["crease"]["plus_x"]["fold_angle_deg"] == 180.0
    assert any(w.startswith("beta: plus_x: folds 180 deg") for w in rep["warnings"])
    out = tmp_path / "b"
    proc = run("build", "patkau-one-fold", "--alpha", "71", "--beta", repr(CLOSED), "-o",
               str(out), "-q")  # fmt: skip
    assert proc.returncode == 2 and proc.stderr.startswith("onefold: error: beta: plus_x: folds")
    assert proc.stderr.count("\n") == 1 and not out.exists()


def test_a_default_solid_that_cannot_be_made_stands_as_its_surface_and_says_so():
    design = _design(NEAR)
    folded = fold_design(design)
    why = solid_problem(design, folded)
    assert why is not None and why.parameter == "alpha" and "no mitre" in str(why)
    rest = resting_placement(design, folded)
    assert rest.body == "shell" and rest.com_outside == 0.0
    proc = run("solve", "patkau-one-fold", "--alpha", "71", "--beta", repr(NEAR))
    assert proc.returncode == 0, proc.stderr
    lines = [w for w in proc.stderr.splitlines() if "no mitre" in w]
    assert len(lines) == 1 and lines[0].startswith("onefold: warning: no STEP solid: alpha:")
    # a design that can have its solid stands as it
    ok = _design(89.0)
    assert solid_problem(ok, fold_design(ok)) is None
    assert resting_placement(ok, fold_design(ok)).body == "solid"
