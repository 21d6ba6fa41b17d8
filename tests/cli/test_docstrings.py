"""The command's docstrings name every command it has."""

from __future__ import annotations

import pytest

import onefold_cad.cli
import onefold_cad.cli.main
from onefold_cad.cli.commands import COMMANDS


@pytest.mark.parametrize("module", [onefold_cad.cli, onefold_cad.cli.main])
def test_the_docstring_names_every_command(module):
    first = module.__doc__.split("\n\n")[0]
    assert [c for c in COMMANDS if c not in first] == []
