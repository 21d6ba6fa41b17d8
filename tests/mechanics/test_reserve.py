"""The coarse preview never contradicts the normal mesh on "stands":
patkau-one-fold at t = 3 mm does not stand on the normal mesh (its load path
ends at 0.906 of the weight with the moment law, docs/mechanics.md, and at
0.875 with J2: `onefold simulate patkau-one-fold --thickness 3 --no-check`),
and the coarse preview of either law, whose
triangles are stiffer, stands there only with a reserve below
``COARSE_RESERVE``: it answers "uncertain", never a yes. A sheet with a
reserve well past it (6 mm) is a plain yes."""

from __future__ import annotations

from dataclasses import replace

import pytest

from onefold_cad.design import fold_design
from onefold_cad.mechanics.reserve import COARSE_RESERVE
from onefold_cad.mechanics.simulate import run
from onefold_cad.mechanics.verdicts import RESERVE_PENDING
from onefold_cad.templates import load_template


def _patkau(thickness: float):
    design = load_template("patkau-one-fold")
    design = replace(design, material=design.material.with_changes(thickness=thickness))
    return design, fold_design(design)


LAWS = pytest.mark.parametrize("law", ["moment", "j2"])


@LAWS
def test_a_coarse_stand_near_its_limit_is_uncertain_not_yes(law):
    sim = run(*_patkau(3.0), level="coarse", law=law)
    s = sim.standing
    assert s.stands and s.verdict == "uncertain"
    assert s.reserve == 1.0  # not shown to carry more (the normal mesh does not carry 1)
    assert "run --mesh normal" in s.uncertain
    assert any(w.startswith("whether it stands is uncertain") for w in sim.warnings)
    assert sim.to_data()["standing"]["verdict"] == "uncertain"


@LAWS
def test_a_coarse_stand_with_a_large_reserve_is_a_yes(law):
    sim = run(*_patkau(6.0), level="coarse", law=law)
    assert sim.standing.verdict == "stands" and sim.standing.reserve == COARSE_RESERVE


def test_j2_s_check_left_out_is_uncertain_never_a_yes():
    """``reserve=False`` (the convergence check's coarse run, the explorer's
    Steel view) leaves J2's check for later: the 6 mm sheet, a yes with it,
    is "uncertain" until it runs (tests/mechanics/test_verdicts.py settles it)."""
    sim = run(*_patkau(6.0), level="coarse", law="j2", reserve=False)
    assert sim.standing.stands and sim.standing.verdict == "uncertain"
    assert sim.standing.uncertain == RESERVE_PENDING and sim.pending_reserve is not None
    assert sim.pending_reserve.law == "j2"
