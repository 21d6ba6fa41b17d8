"""The coarse preview's reserve check left for later (``run(..., reserve=False)``,
the explorer's Steel view shows the form first) gives, once
``settle_reserve`` ran it, the simulation ``run`` gives with the check in
line: every number, the verdict and the warnings equal (the same solves on
the same states); until then the standing is never a plain "stands". The
convergence check's change, measured from the finer mesh's value, and its
warning past 2 %."""

from __future__ import annotations

from dataclasses import replace

import pytest

from onefold_cad.design import fold_design
from onefold_cad.mechanics.reserve import COARSE_RESERVE
from onefold_cad.mechanics.simulate import run
from onefold_cad.mechanics.verdicts import (
    RESERVE_PENDING,
    convergence_report,
    past_converged,
    settle_reserve,
)
from onefold_cad.templates import load_template


def _patkau(thickness: float):
    design = load_template("patkau-one-fold")
    design = replace(design, material=design.material.with_changes(thickness=thickness))
    return design, fold_design(design)


def _report(sim) -> dict:
    data = sim.to_data()
    data.pop("timings_s")
    return data


@pytest.mark.parametrize(
    ("thickness", "reference", "law", "verdict", "reserve"),
    [
        (3.0, "flat", "moment", "uncertain", 1.0),  # tests/mechanics/test_reserve.py
        (6.0, "flat", "moment", "stands", COARSE_RESERVE),
        (6.0, "designed", "moment", "stands", COARSE_RESERVE),  # the structural check too
        # J2's check through the law, the stand's internal variables held (the
        # explorer's Steel view of cones formed past their springback)
        (3.0, "flat", "j2", "uncertain", 1.0),
        (6.0, "flat", "j2", "stands", COARSE_RESERVE),
    ],
)
def test_a_check_left_for_later_settles_to_the_run_with_it(
    thickness, reference, law, verdict, reserve
):
    design, folded = _patkau(thickness)
    inline = run(design, folded, level="coarse", reference=reference, law=law)
    later = run(design, folded, level="coarse", reference=reference, law=law, reserve=False)
    assert later.pending_reserve is not None and inline.pending_reserve is None
    assert later.standing.verdict == "uncertain" and later.standing.uncertain == RESERVE_PENDING
    assert later.standing.reserve is None
    settled = settle_reserve(later, later.pending_reserve)
    assert settled.pending_reserve is None and "reserve" in settled.timings_s
    assert settled.standing.verdict == inline.standing.verdict == verdict
    assert settled.standing.reserve == inline.standing.reserve == reserve
    assert settled.warnings == inline.warnings
    assert _report(settled) == _report(inline)
    # a warning added after the run (simulate()'s convergence check) stays, last
    extra = replace(later, warnings=(*later.warnings, "not mesh-converged: ..."))
    assert settle_reserve(extra, later.pending_reserve).warnings == (
        *inline.warnings,
        "not mesh-converged: ...",
    )


def test_a_change_past_two_percent_is_measured_from_the_first_value():
    assert past_converged(100.0, 103.0) == pytest.approx(0.03)
    assert past_converged(100.0, 98.5) is None  # 1.5 %: converged
    assert past_converged(0.0, 1.0) is None and past_converged(None, 1.0) is None


@pytest.mark.parametrize(("finer", "change"), [(True, 25 / 125), (False, 25 / 100)])
def test_the_check_measures_its_change_from_the_finer_meshs_value(finer, change):
    mesh = {"nodes": 1234, "triangles": 2300, "h_max": 0.3}
    data, warned = convergence_report(("max", 100.0), ("max", 125.0), finer, mesh, None)
    assert data["max_deviation_change"] == pytest.approx(change)
    assert data["check"] == ("finer" if finer else "coarser")
    assert warned == [
        f"not mesh-converged: max changes by {100 * change:.3g} % on a mesh of 1234 nodes "
        "(more than 2 %); a finer --mesh is closer"
    ]
    data, warned = convergence_report(("max", 100.0), ("max", 101.0), finer, mesh, None)
    assert warned == [] and data["max_deviation_change"] < 0.02
