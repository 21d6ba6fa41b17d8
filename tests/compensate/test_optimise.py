"""The compensation loop against a stand-in steel whose answer is known
(tests/compensate/fake_steel.py: the steel opens alpha and beta by SPRING)."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.compensate import optimise, parallel
from onefold_cad.compensate.parallel import Evaluator
from onefold_cad.compensate.run import compensate
from onefold_cad.compensate.target import Target, make_target
from onefold_cad.design import fold_design
from onefold_cad.geometry.resting.placement import rest_form
from onefold_cad.templates import find_template, load_template
from tests.compensate.fake_steel import OVERBEND, PER_OVERBEND, SPRING, fake_standing


@pytest.fixture
def fake(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)


FOLD = ("alpha", "beta", "h_c")


def test_design_target_forms_the_fold_more_by_the_springback(fake: None) -> None:
    design = load_template(find_template("broken-vault"))
    lines: list[str] = []
    with Evaluator(1) as ev:
        result = compensate(design, make_target(design, "design"), ev, lines.append, knobs=FOLD)
    f, f0 = result.compensated.frame, design.frame
    # the fake steel opens the fold by SPRING: the answer is the design plus SPRING
    assert f.alpha == pytest.approx(f0.alpha + SPRING[0], abs=0.05)
    assert f.beta == pytest.approx(f0.beta + SPRING[1], abs=0.05)
    assert result.reached
    assert result.after.max_deviation < 0.01 * result.before.max_deviation
    assert any("ETA" in line for line in lines)
    assert result.compensated.name == "broken-vault-compensated"
    # the crease is formed to the compensated fold's angle
    assert {c["half"] for c in result.crease} == {"plus_x", "minus_x"}
    data = result.to_data()
    assert data["simulations"] == len(result.found.candidates) + 2
    assert set(data["sensitivity"]) == set(FOLD)
    # opening alpha lowers the fake steel (a flatter vault): height per deg > 0
    assert data["sensitivity"]["alpha"]["height"] > 0


def test_size_target_is_met_by_the_steel(fake: None) -> None:
    design = load_template(find_template("broken-vault"))
    f0 = design.frame
    # the fake steel of the fold (alpha + 1, beta + 1) has this size: the target
    aim = design.with_changes(frame=f0.with_changes(alpha=f0.alpha + 1.0, beta=f0.beta + 1.0))
    steel = fake_standing(aim, "coarse")
    # the loop alone (make_target's reach check is tests/cli/test_compensate.py's)
    target = Target("size", design, height=steel.height, span=steel.span)
    with Evaluator(1) as ev:
        result = compensate(design, target, ev, lambda s: None)
    assert result.reached, result.verdict
    assert result.after.height == pytest.approx(steel.height, rel=0.01)
    assert result.after.span == pytest.approx(steel.span, rel=0.01)
    assert result.found.knobs == ("alpha", "beta", "h_c", "overbend")


def test_the_crease_overbend_alone_compensates_and_sets_the_crease_past_the_fold(
    fake: None,
) -> None:
    from onefold_cad.design import fold_design

    design = load_template(find_template("broken-vault"))
    with Evaluator(1) as ev:
        result = compensate(design, make_target(design, "design"), ev, lambda s: None,
                            knobs=("overbend",))  # fmt: skip
    assert result.reached, result.verdict
    # the fake steel closes the fold by PER_OVERBEND a degree: OVERBEND undoes SPRING
    assert result.compensated.material.crease_overbend == pytest.approx(OVERBEND, abs=0.05)
    assert result.compensated.frame == design.frame  # the cones as designed
    data = result.to_data()
    assert data["compensated"]["overbend"] == result.compensated.material.crease_overbend
    assert data["start"]["overbend"] == 0.0
    # the crease is set to the fold's own angle plus the overbend
    angles = {c.name: c.fold_angle_deg for c in fold_design(design).crease}
    for c in result.crease:
        assert c["fold_to_deg"] == pytest.approx(angles[c["half"]] + OVERBEND, abs=0.05)


def test_every_knob_together_reaches_the_design(fake: None) -> None:
    # alpha, beta and the overbend repeat each other on the fake steel: any of
    # their combinations that closes the fold by SPRING is an answer
    design = load_template(find_template("broken-vault"))
    with Evaluator(1) as ev:
        result = compensate(design, make_target(design, "design"), ev, lambda s: None)
    assert result.found.knobs == ("alpha", "beta", "h_c", "overbend")
    assert result.reached, result.verdict
    assert result.after.max_deviation < 0.02 * result.before.max_deviation
    f, f0 = result.compensated.frame, design.frame
    ob = result.compensated.material.overbend_deg
    assert f.alpha + PER_OVERBEND[0] * ob == pytest.approx(f0.alpha + SPRING[0], abs=0.1)
    assert f.beta + PER_OVERBEND[1] * ob == pytest.approx(f0.beta + SPRING[1], abs=0.1)


def test_a_target_out_of_the_family_s_reach_says_what_limits_it(monkeypatch) -> None:
    # a steel lifted off its feet by 2 in cannot be brought back by any fold
    # (the measure allows a turn and shift on the ground, no lift)
    from dataclasses import replace

    def lifted(design, level, check=False, law="moment"):
        s = fake_standing(design, level, check, law)
        return replace(s, positions=s.positions + [0.0, 0.0, 2.0])

    monkeypatch.setattr(parallel, "simulate_standing", lifted)
    design = load_template(find_template("broken-vault"))
    with Evaluator(1) as ev:
        result = compensate(design, make_target(design, "design"), ev, lambda s: None)
    assert not result.reached
    assert result.verdict.startswith("not met: ")
    assert "within the family of folds" in result.verdict
    assert "singular values" in result.verdict and "least squares stopped" in result.verdict
    # no fold removes the lift (a fold can only tilt the surface under it)
    assert 1.5 < result.after.max_deviation < 3.0


def _not_standing_on(levels: tuple[str, ...]):
    from dataclasses import replace

    def steel(design, level, check=False, law="moment"):
        s = fake_standing(design, level, check, law)
        if level in levels:
            return replace(s, stands=False, reason="no equilibrium", positions=None)
        return s

    return steel


def test_a_start_that_does_not_stand_on_the_coarse_mesh_is_searched_on_the_normal(
    monkeypatch,
) -> None:
    # broken-vault's steel finds no standing equilibrium on the coarse mesh (only)
    monkeypatch.setattr(parallel, "simulate_standing", _not_standing_on(("coarse",)))
    design = load_template(find_template("broken-vault"))
    lines: list[str] = []
    with Evaluator(1) as ev:
        result = compensate(design, make_target(design, "design"), ev, lines.append, knobs=FOLD)
    assert result.reached
    assert result.compensated.frame.alpha == pytest.approx(design.frame.alpha + SPRING[0], abs=0.05)
    assert any("the search runs on the normal mesh" in line for line in lines)


def test_a_start_that_stands_on_no_mesh_is_refused_in_one_line(monkeypatch) -> None:
    from onefold_cad.errors import InvalidParameterError

    monkeypatch.setattr(parallel, "simulate_standing", _not_standing_on(("coarse", "normal")))
    design = load_template(find_template("broken-vault"))
    with Evaluator(1) as ev, pytest.raises(InvalidParameterError, match="does not stand on the"):
        compensate(design, make_target(design, "design"), ev, lambda s: None)


def test_knob_strengths_weigh_each_knob_by_its_step() -> None:
    import numpy as np

    from onefold_cad.compensate.optimise import knob_strengths

    # per unit: alpha moves residual 1, beta residual 2, h_c (a fraction of its
    # range) residual 2 a hundred times as fast; per step (0.5 deg, 0.5 deg, 0.01)
    # the columns are (0.5, 0), (0, 0.5), (0, 1): A A^T = diag(0.25, 1.25), so
    # the singular values are sqrt(1.25) and 0.5, and the third is absent
    jac = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 100.0]])
    got = knob_strengths(jac, np.array([0.5, 0.5, 0.01]))
    assert got == pytest.approx([1.0, 0.5 / np.sqrt(1.25)])
    # two knobs that repeat each other per step leave a zero direction
    same = knob_strengths(np.array([[2.0, 1.0], [4.0, 2.0]]), np.array([0.5, 1.0]))
    assert same == pytest.approx([1.0, 0.0], abs=1e-12)


def test_a_design_target_s_residual_ends_with_its_size_penalty() -> None:
    # the fake steel of broken-vault stands as the fold opened by SPRING: its
    # residual's last two rows are its height's and span's relative misses
    # against the design as it rests, less SIZE_SLACK, times SIZE_WEIGHT and
    # the mean of the design's height and span
    design = load_template(find_template("broken-vault"))
    steel = fake_standing(design, "coarse")
    rest = rest_form(fold_design(design), None)
    problem = optimise._Problem(make_target(design, "design"), None, optimise.Search(), print)
    rows, _, _ = problem.residual(steel)
    assert steel.height is not None and steel.span is not None
    want = []
    length = (rest.height + rest.width) / 2
    for got, design_size in ((steel.height, rest.height), (steel.span, rest.width)):
        beyond = abs(got / design_size - 1) - optimise.SIZE_SLACK
        sign = 1 if got > design_size else -1
        want.append(optimise.SIZE_WEIGHT * length * max(beyond, 0.0) * sign)
    assert any(w != 0.0 for w in want)  # a miss past the slack to see
    assert rows[-2:] == pytest.approx(want, rel=1e-12)
    assert len(rows) == len(steel.flat) + 2


@pytest.mark.parametrize("off", [-0.004, 0.0, 0.0049])
def test_a_size_within_the_slack_costs_nothing(off: float) -> None:
    sizes = {"height": 100.0, "span": 250.0}
    assert list(optimise.size_rows(100.0 * (1 + off), 250.0 * (1 - off), sizes)) == [0.0, 0.0]


def test_a_size_past_the_slack_costs_its_relative_excess_signed() -> None:
    # 2 % high and 1 % narrow: 1.5 % and 0.5 % past the slack, each weighed
    # on the mean of the design's height and span (175)
    sizes = {"height": 100.0, "span": 250.0}
    assert optimise.SIZE_SLACK == 0.005
    rows = optimise.size_rows(102.0, 247.5, sizes)
    w = optimise.SIZE_WEIGHT * 175.0
    assert rows == pytest.approx([0.015 * w, -0.005 * w], rel=1e-9)


def test_a_fold_build_would_refuse_is_not_simulated_where_the_start_is_buildable() -> None:
    """patkau's 6 mm bends leave its blank too wide across one half once h_c
    folds the halves apart (a compensate -j 2 --law j2 search ended there,
    and -o then failed to write): such a candidate is refused unsimulated,
    at an infinite cost, so the search steps back from it."""
    start = load_template(find_template("patkau-one-fold"))
    names = ("alpha", "beta", "h_c", "overbend")
    fixed = optimise.knob_values(start)
    bad = optimise._design_at(start, names, np.array([36.86, 36.68, 0.7252, -0.74]), fixed)
    assert optimise.bend_refusal(start) is None and bad.frame.h_c > 50.0  # the premise

    class Recording:
        def __init__(self) -> None:
            self.seen: list[object] = []

        def map(self, designs, level):
            self.seen += designs
            return ["stand-in"] * len(designs)  # refused by the steel too: no residual

    ev = Recording()
    problem = optimise._Problem(make_target(start, "design"), ev, optimise.Search(), print)
    problem.buildable = True
    problem.evaluate([start, bad], "coarse")
    assert ev.seen == [start]
    refused = problem.found.candidates[1]
    assert isinstance(refused.standing, str) and refused.cost == float("inf")
    assert refused.standing.startswith("not buildable: bend_radius: ")
    problem.buildable = False  # a start build refuses: the search is not held to it
    problem.evaluate([bad], "coarse")
    assert ev.seen == [start, bad]


def test_a_jacobian_step_onto_an_unbuildable_fold_steps_the_other_way(
    fake: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Folds past the answer's alpha cannot be built (a stand-in for build's
    refusal): the forward differences there step back instead of taking the
    penalty's slope, and the search still lands on the answer."""
    design = load_template(find_template("broken-vault"))
    wall = design.frame.alpha + SPRING[0] + 0.2  # the answer's alpha, then a wall
    monkeypatch.setattr(
        optimise, "bend_refusal", lambda d: "not buildable" if d.frame.alpha > wall else None
    )
    with Evaluator(1) as ev:
        result = compensate(design, make_target(design, "design"), ev, lambda s: None, knobs=FOLD)
    refused = [c for c in result.found.candidates if c.standing == "not buildable"]
    assert refused  # the premise: the search met the wall
    f = result.compensated.frame
    assert f.alpha == pytest.approx(design.frame.alpha + SPRING[0], abs=0.05)
    assert f.beta == pytest.approx(design.frame.beta + SPRING[1], abs=0.05)
    assert result.reached
