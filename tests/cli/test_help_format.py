"""The shared help layout (onefold_cad/cli/help_format.py): every command's
help fits 100 columns, raw descriptions keep their own line breaks."""

from __future__ import annotations

import pytest

from onefold_cad.cli.help_format import WIDTH, fill, raw_formatter
from onefold_cad.cli.parser import build_parser


def test_fill_wraps_at_the_width_and_keeps_words_whole() -> None:
    words = ["a-b-c-d-e-f"] * 40
    lines = fill(" ".join(words)).splitlines()
    assert len(lines) > 1
    assert all(len(line) <= WIDTH for line in lines)
    assert " ".join(lines).split() == words  # no word (nor hyphenated word) broken


@pytest.mark.parametrize("name", sorted(build_parser()))
def test_every_command_help_fits_the_width(name: str) -> None:
    text = build_parser()[name].format_help()
    assert max(len(line) for line in text.splitlines()) <= WIDTH


def test_the_raw_formatter_keeps_line_breaks() -> None:
    import argparse

    p = argparse.ArgumentParser(prog="x", description="one\ntwo", formatter_class=raw_formatter)
    assert "one\ntwo" in p.format_help()
