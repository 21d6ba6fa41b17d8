"""The help layout every ``onefold`` command's parser shares (100 columns,
options aligned at 30)."""

from __future__ import annotations

import argparse
import textwrap

__all__ = ["fill", "formatter", "raw_formatter"]

#: Help text width (columns).
WIDTH = 100


def formatter(prog: str) -> argparse.HelpFormatter:
    """argparse's formatter, 100 columns, options aligned at column 30."""
    return argparse.HelpFormatter(prog, max_help_position=30, width=WIDTH)


def raw_formatter(prog: str) -> argparse.HelpFormatter:
    """Like :func:`formatter`, the description and epilog kept as written."""
    return argparse.RawDescriptionHelpFormatter(prog, max_help_position=30, width=WIDTH)


def fill(text: str) -> str:
    """``text`` wrapped for a raw help description (100 columns, words whole)."""
    return textwrap.fill(text, WIDTH, break_on_hyphens=False)
