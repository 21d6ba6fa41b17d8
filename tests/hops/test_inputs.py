"""Hops values read back and turned into the command line ``onefold solve`` reads."""

from __future__ import annotations

import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.design_flags import DESIGN_FLAGS
from onefold_cad.flags.parser import UsageError, parse_design_flags
from onefold_cad.hops.inputs import (
    FIT_INPUTS,
    SOLVE_INPUTS,
    StaleInputsError,
    flag_args,
    hops_request,
    parse_solve_args,
    read_values,
)


def _tree(*items: tuple[str, str]) -> dict:
    return {"{0}": [{"type": t, "data": d} for t, d in items]}


def test_every_flag_input_is_a_design_flag_of_the_same_name():
    flags = {f.dest: f.flag for f in DESIGN_FLAGS}
    for inp in SOLVE_INPUTS:
        if inp.name in flags:
            assert inp.flag == flags[inp.name] and inp.flag in inp.description
    names = {i.name for i in SOLVE_INPUTS}
    assert {"alpha", "beta", "hc", "radius", "thickness", "bend_radius", "sheet"} <= names
    assert {"sheet_width", "sheet_height", "apex_fraction", "x_plus", "template"} <= names


def test_the_request_reads_back_to_its_values():
    values = {"alpha": 40.5, "divisions": 12, "model": "paper", "template": "paper-square"}
    body = hops_request("onefold/solve", SOLVE_INPUTS, values)
    got = read_values(SOLVE_INPUTS, body["values"])
    assert {k: v for k, v in got.items() if v is not None} == values
    assert isinstance(got["divisions"], int) and isinstance(got["alpha"], float)
    assert got["beta"] is None  # no data: the template's value


def test_hops_numbers_are_read_as_hops_writes_them():
    # Hops writes a double as JSON text ("30.0", "1E-05") and a string quoted
    values = [
        {"ParamName": "alpha", "InnerTree": _tree(("System.Double", "1E-05"))},
        {"ParamName": "divisions", "InnerTree": _tree(("System.Int32", "7"))},
        {"ParamName": "model", "InnerTree": _tree(("System.String", '"paper"'))},
        {"ParamName": "units", "InnerTree": _tree(("System.String", "in"))},  # bare text
        {"ParamName": "beta", "InnerTree": {"{0;1}": [{"type": "System.Double", "data": "2"}]}},
    ]
    got = read_values(SOLVE_INPUTS, values)
    assert got["alpha"] == 1e-5 and got["divisions"] == 7 and got["beta"] == 2.0
    assert got["model"] == "paper" and got["units"] == "in"


@pytest.mark.parametrize(
    ("name", "item", "words"),
    [
        ("alpha", ("System.String", '"steep"'), "must be a number"),
        ("alpha", ("System.Boolean", "true"), "must be a number"),
        ("divisions", ("System.Double", "2.5"), "whole number"),
        ("alpha", ("System.Double", "not json"), "cannot read"),
        ("sheet", ("System.Double", "3.0"), "must be a curve"),
    ],
)
def test_a_value_of_the_wrong_kind_is_refused_by_name(name, item, words):
    with pytest.raises(InvalidParameterError) as exc:
        read_values(SOLVE_INPUTS, [{"ParamName": name, "InnerTree": _tree(item)}])
    assert exc.value.parameter == name and words in str(exc.value)


def test_required_and_single_values():
    with pytest.raises(InvalidParameterError, match="^height: missing"):
        read_values(FIT_INPUTS, [{"ParamName": "height", "InnerTree": {}}])
    two = _tree(("System.Double", "1.0"), ("System.Double", "2.0"))
    with pytest.raises(InvalidParameterError, match="^alpha: takes one value per solve, got 2"):
        read_values(SOLVE_INPUTS, [{"ParamName": "alpha", "InnerTree": two}])
    with pytest.raises(StaleInputsError, match="gamma"):
        read_values(SOLVE_INPUTS, [{"ParamName": "gamma", "InnerTree": {}}])
    with pytest.raises(InvalidParameterError, match="^values: "):
        read_values(SOLVE_INPUTS, [{"ParamName": "alpha"}])


def test_flag_args_are_what_the_command_reads():
    values = {"alpha": 0.1 + 0.2, "divisions": 9, "sheet_width": 3048.0, "sheet_height": 7315.2,
              "model": "paper", "sheet": "1.0,0.0;0.0,1.0;-1.0,0.0"}  # fmt: skip
    args = flag_args(SOLVE_INPUTS, values)
    assert args == ["--rectangle=3048.0x7315.2", "--model=paper", "--alpha=0.30000000000000004",
                    "--divisions=9", "--polygon=1.0,0.0;0.0,1.0;-1.0,0.0"]  # fmt: skip
    flags, placement = parse_solve_args(args)
    assert flags == parse_design_flags(args) and placement == "rest"
    assert flags["alpha"] == 0.1 + 0.2  # every digit survives
    assert flag_args(SOLVE_INPUTS, {"sheet_height": 5.0}) == ["--rectangle=x5.0"]


def test_placement_is_read_like_build_s():
    assert parse_solve_args(["--placement=frame"])[1] == "frame"
    with pytest.raises(UsageError, match=r"^--placement: must be one of rest, frame, got 'up'$"):
        parse_solve_args(["--placement=up"])
