"""The flag parser's one-line errors: a mistyped flag gets a suggestion."""

from __future__ import annotations

import pytest

from onefold_cad.cli.parser import build_parser
from onefold_cad.flags.parser import UsageError, parse_design_flags


@pytest.mark.parametrize(
    ("argv", "want"),
    [
        (["--alpah", "40"], "no such option: --alpah (did you mean --alpha?)"),
        (["--bta=3"], "no such option: --bta (did you mean --beta?)"),
        (["--unit", "mm"], "no such option: --unit (did you mean --units?)"),
        (["--zzzz", "1"], "no such option: --zzzz"),  # nothing close: no guess
    ],
)
def test_a_mistyped_design_flag_names_the_closest_one(argv, want):
    with pytest.raises(UsageError) as err:
        parse_design_flags(argv)
    assert str(err.value) == want


def test_a_mistyped_command_flag_names_the_closest_one():
    with pytest.raises(UsageError, match=r"^no such option: --quite \(did you mean --quiet\?\)$"):
        build_parser()["build"].parse_intermixed_args(["--quite"])
