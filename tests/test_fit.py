"""Inverse design, ``onefold fit``: the answer, rebuilt with ``onefold solve``,
stands as high and as wide as asked; unreachable targets are a one-line error."""

from __future__ import annotations

import json
import warnings

import pytest

from onefold_cad.cli.main import main
from onefold_cad.fit import FIT_TOLERANCE, OutOfReachError, fit_design
from onefold_cad.templates import find_template, load_template


def _cli(capfd, *args: str) -> tuple[int, str, str]:
    """Status, stdout and stderr without fit's progress lines ('[fit] ...',
    one a step of the search; -q leaves them out)."""
    code = main(list(args))
    out, err = capfd.readouterr()
    return code, out, "".join(x for x in err.splitlines(True) if not x.startswith("[fit] "))


def _solve(capfd, template: str, *flags: str) -> dict:
    """The resting form as ``onefold solve --json`` reports it."""
    code, out, err = _cli(capfd, "solve", template, *flags, "--json")
    assert code == 0, err
    return json.loads(out)["resting"]


def _frame_flags(frame: dict) -> list[str]:
    return [
        "--alpha",
        repr(frame["alpha"]),
        "--beta",
        repr(frame["beta"]),
        "--hc",
        repr(frame["h_c"]),
    ]


@pytest.mark.parametrize(
    ("template", "alpha", "beta"),
    [("table1-row1", 52.0, 38.0), ("paper-square", 28.0, 61.0)],
)
def test_reachable_target_comes_back_within_half_a_percent(capfd, template, alpha, beta):
    # a target the template's sheet reaches: the form of another frame, by solve
    aim = _solve(capfd, template, "--alpha", str(alpha), "--beta", str(beta))
    height, span = aim["height"], aim["footprint"]["width"]
    code, out, err = _cli(
        capfd, "fit", template, "--height", repr(height), "--span", repr(span), "--json"
    )
    assert code == 0, err
    found = json.loads(out)
    assert set(found["frame"]) == {"alpha", "beta", "h_c"}
    assert found["achieved"]["height"] == pytest.approx(height, rel=FIT_TOLERANCE)
    # rebuilt with solve from the printed frame: the same form, within 0.5 %
    got = _solve(capfd, template, *_frame_flags(found["frame"]))
    assert abs(got["height"] - height) <= FIT_TOLERANCE * height
    assert abs(got["footprint"]["width"] - span) <= FIT_TOLERANCE * span
    assert got["height"] == pytest.approx(found["achieved"]["height"], rel=1e-12)
    assert got["tipping_margin_deg"] == pytest.approx(
        found["achieved"]["tipping_margin_deg"], abs=1e-9
    )


def test_depth_and_minimum_tipping_margin_are_met(capfd):
    design = load_template(find_template("table1-row1"))
    aim = _solve(capfd, "table1-row1", "--alpha", "30", "--beta", "45")
    assert aim["tipping_margin_deg"] > 20.0
    result = fit_design(
        design,
        aim["height"],
        aim["footprint"]["width"],
        depth=aim["footprint"]["depth"],
        min_tipping_margin=20.0,
    )
    assert all(e <= FIT_TOLERANCE for e in result.errors.values())
    assert set(result.errors) == {"height", "span", "depth"}
    got = _solve(capfd, "table1-row1", *_frame_flags(result.design.frame.__dict__))
    assert (
        abs(got["footprint"]["depth"] - aim["footprint"]["depth"])
        <= FIT_TOLERANCE * aim["footprint"]["depth"]
    )
    assert got["tipping_margin_deg"] >= 20.0


def test_unreachable_target_exits_2_with_one_line(capfd):
    # a 300 mm square cannot stand ten times its own size high
    code, out, err = _cli(capfd, "fit", "table1-row1", "--height", "3000", "--span", "300")
    assert code == 2 and out == ""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("onefold: error: ")
    assert "out of reach" in lines[0] and "height" in lines[0] and " to " in lines[0]
    # with -q there is no progress: the refusal is stderr's one line
    assert main(["fit", "table1-row1", "--height", "3000", "--span", "300", "-q"]) == 2
    assert capfd.readouterr().err.splitlines() == lines
    with pytest.raises(OutOfReachError) as info:
        fit_design(load_template(find_template("table1-row1")), 3000.0, 300.0)
    low, high = info.value.reachable["height"]
    assert 0.0 < low < high < 3000.0


@pytest.mark.parametrize(("height", "span"), [("1e300", "1e-300")])
def test_targets_at_the_ends_of_the_floats_are_one_line(capfd, height, span):
    """A span of 1e-300 made relative errors of 1e303 whose squares overflowed:
    six numpy RuntimeWarnings on stderr before the error. The refusal is its
    one line, with the ranges reached."""
    with warnings.catch_warnings(record=True) as caught:  # as a user's stderr would show them
        warnings.simplefilter("always")
        code, out, err = _cli(capfd, "fit", "table1-row1", "--height", height, "--span", span)
    assert [str(w.message) for w in caught] == []
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "out of reach" in err, err


def test_bad_targets_are_clear_errors(capfd):
    for args in (("--height", "-1", "--span", "300"), ("--height", "200", "--span", "nan")):
        code, out, err = _cli(capfd, "fit", "table1-row1", *args)
        assert code == 2 and out == "" and len(err.splitlines()) == 1
    code, _, err = _cli(capfd, "fit", "table1-row1", "--height", "200")
    assert code == 2 and "--span" in err


def test_outdir_builds_the_found_design(capfd, tmp_path):
    aim = _solve(capfd, "table1-row1", "--alpha", "45", "--beta", "50")
    height, span = aim["height"], aim["footprint"]["width"]
    code, out, err = _cli(
        capfd,
        "fit",
        "table1-row1",
        "--height",
        repr(height),
        "--span",
        repr(span),
        "-o",
        str(tmp_path),
    )
    assert code == 0, err
    lines = out.splitlines()  # the build's files, then the fit
    assert any(line.startswith("table1-row1: alpha ") for line in lines)
    assert str(tmp_path / "table1-row1-fit.step") in lines  # named after the template
    report = json.loads((tmp_path / "table1-row1-fit.json").read_text())
    assert abs(report["resting"]["height"] - height) <= FIT_TOLERANCE * height
    assert (tmp_path / "table1-row1-fit.step").is_file()


def test_the_out_of_reach_example_of_docs_design_space_md_is_what_the_command_prints(capfd):
    from pathlib import Path

    page = (Path(__file__).resolve().parents[1] / "docs" / "design-space.md").read_text()
    after = page.split("A target the sheet cannot reach", 1)[1]
    command = after.split("```sh\n", 1)[1].split("\n```", 1)[0].strip()
    shown = after.split("```text\n", 1)[1].split("\n```", 1)[0].strip()
    argv = command.split()
    assert argv[:2] == ["onefold", "fit"]
    code, out, err = _cli(capfd, *argv[1:])
    assert code == 2 and out == ""
    assert err.strip() == shown
