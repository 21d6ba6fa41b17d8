"""The parser of the design flags: an ``argparse`` parser whose errors are
one-line exceptions (:class:`UsageError`), the design flags added to it, and
their values read back. The ``onefold`` command and the explorer parse with
it, so a value reads the same in both.
"""

from __future__ import annotations

import argparse
import functools
import re
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, NoReturn

from onefold_cad.flags.design_flags import (
    DESIGN_FLAGS,
)

if TYPE_CHECKING:
    pass

__all__ = [
    "FlagParser",
    "UsageError",
    "add_design_flags",
    "design_flag_parser",
    "design_flag_values",
    "parse_design_flags",
]


class UsageError(Exception):
    """A command line the parser cannot read (one line, exit status 2)."""


# -- the parser --------------------------------------------------------------------
class FlagParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are exceptions (main prints one line)."""

    def error(self, message: str) -> NoReturn:
        if message.startswith("unrecognized arguments: "):
            words = message.split(": ", 1)[1].split()
            opts = [w for w in words if w.startswith("-")]
            message = (
                f"no such option: {opts[0].split('=')[0]}{self._did_you_mean(opts[0])}"
                if opts
                else f"unexpected argument {words[0]!r}"
            )
        if message.startswith("argument "):  # 'argument --alpha: ...' -> '--alpha: ...'
            message = message[len("argument ") :]
            flag, _, rest = message.partition(": ")
            message = f"{flag.split('/')[-1]}: {rest}"
        raise UsageError(message)

    def _did_you_mean(self, typed: str) -> str:
        """' (did you mean --alpha?)' for the option closest to ``typed``
        (``--alpah``), or '' when none is close (difflib's ratio >= 0.7)."""
        import difflib

        name = typed.split("=")[0]
        known = [o for o in self._option_string_actions if o.startswith("--")]
        close = difflib.get_close_matches(name, known, n=1, cutoff=0.7)
        return f" (did you mean {close[0]}?)" if close else ""


def add_design_flags(p: argparse.ArgumentParser) -> None:
    # A value may start with a minus sign ('--polygon -1,0;...', '--hc -5'):
    # argparse reads '-<digit>...' as a value, not as an option.
    p._negative_number_matcher = re.compile(r"^-\.?\d")
    groups: dict[str, Any] = {}
    for f in DESIGN_FLAGS:
        g = groups.get(f.group) or groups.setdefault(f.group, p.add_argument_group(f.group))
        g.add_argument(f.flag, dest=f.dest, type=f.kind, metavar=f.metavar, help=f.help)


# -- commands -------------------------------------------------------------------------
def design_flag_values(ns: argparse.Namespace) -> dict[str, Any]:
    return {f.dest: getattr(ns, f.dest) for f in DESIGN_FLAGS}


@functools.cache
def design_flag_parser() -> FlagParser:
    """A parser of the design flags alone (as ``onefold solve`` reads them)."""
    p = FlagParser(prog="onefold", allow_abbrev=False)
    add_design_flags(p)
    # formatted once: parse_intermixed_args formats the usage on every call unless
    # it is set (the explorer parses the page's values on every move of a slider)
    p.usage = p.format_usage().removeprefix("usage: ").rstrip("\n")
    return p


def parse_design_flags(args: Sequence[str]) -> dict[str, Any]:
    """The design flags of ``args`` (``["--alpha=40", ...]``), read as the
    command reads them: dest -> value (None for a flag not given).

    Raises:
        UsageError: a value the command refuses (its one-line message).
    """
    return design_flag_values(design_flag_parser().parse_intermixed_args(list(args)))
