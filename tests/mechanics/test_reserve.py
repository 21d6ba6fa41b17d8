"""The coarse preview never contradicts the normal mesh on "stands":
patkau-one-fold at t = 3 mm does not stand on the normal mesh (its load path
ends at 0.906 of the weight, docs/mechanics.md), and the coarse preview, whose
triangles are stiffer, stands there only with a reserve below
``COARSE_RESERVE``: it answers "uncertain", never a yes. A sheet with a
reserve well past it (6 mm) is a plain yes."""

from __future__ import annotations

from dataclasses import replace

from onefold_cad.design import fold_design
from onefold_cad.mechanics.reserve import COARSE_RESERVE
from onefold_cad.mechanics.simulate import run
from onefold_cad.templates import load_template


def _patkau(thickness: float):
    design = load_template("patkau-one-fold")
    design = replace(design, material=design.material.with_changes(thickness=thickness))
    return design, fold_design(design)


def test_a_coarse_stand_near_its_limit_is_uncertain_not_yes():
    sim = run(*_patkau(3.0), level="coarse")
    s = sim.standing
    assert s.stands and s.verdict == "uncertain"
    assert s.reserve == 1.0  # not shown to carry more (the normal mesh does not carry 1)
    assert "run --mesh normal" in s.uncertain
    assert any(w.startswith("whether it stands is uncertain") for w in sim.warnings)
    assert sim.to_data()["standing"]["verdict"] == "uncertain"


def test_a_coarse_stand_with_a_large_reserve_is_a_yes():
    sim = run(*_patkau(6.0), level="coarse")
    assert sim.standing.verdict == "stands" and sim.standing.reserve == COARSE_RESERVE
