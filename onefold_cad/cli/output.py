"""The command's text on stderr: progress lines, warnings, OS errors as one
line each (each one ``write``, so lines of parallel workers never mix)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    pass

__all__ = ["one_line", "os_message", "Progress", "warn"]


# -- text output --------------------------------------------------------------------
class Progress:
    """Progress lines on stderr, ``[i/n] NAME: ...``; silent when quiet.

    Each line is one ``write`` (so lines of parallel workers never mix)."""

    def __init__(self, quiet: bool) -> None:
        self.quiet = quiet

    def line(self, i: int, n: int, name: str, text: str) -> None:
        if not self.quiet:
            os.write(2, f"[{i}/{n}] {name}: {text}\n".encode())


def warn(text: str) -> None:
    """One warning line on stderr (printed even with --quiet)."""
    os.write(2, f"onefold: warning: {one_line(text)}\n".encode())


def one_line(text: str) -> str:
    return " ".join(str(text).split())


# -- entry point ---------------------------------------------------------------------
def os_message(exc: OSError) -> str:
    where = exc.filename if exc.filename is not None else ""
    what = exc.strerror or str(exc)
    return f"{where}: {what}" if where else what
