"""The command's text on stderr: progress lines, warnings, OS errors as one
line each (each one ``write``, so lines of parallel workers never mix)."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterable, Iterator

__all__ = ["held_warnings", "one_line", "os_message", "Progress", "warn", "wrote"]


# -- text output --------------------------------------------------------------------
class Progress:
    """Progress lines on stderr, ``[i/n] NAME: ...``; silent when quiet.

    Each line is one ``write`` (so lines of parallel workers never mix)."""

    def __init__(self, quiet: bool) -> None:
        self.quiet = quiet

    def line(self, i: int, n: int, name: str, text: str) -> None:
        if not self.quiet:
            os.write(2, f"[{i}/{n}] {name}: {text}\n".encode())


def wrote(paths: Iterable[object], quiet: bool) -> None:
    """Go through ``paths`` (a writer's generator writes as it yields) with a
    ``wrote PATH`` line on stderr for each, none when quiet."""
    for path in paths:
        if not quiet:
            os.write(2, f"wrote {path}\n".encode())


def warn(text: str) -> None:
    """One warning line on stderr (printed even with --quiet); held while a
    command runs (:func:`held_warnings`)."""
    line = f"onefold: warning: {one_line(text)}\n"
    if _HELD:
        _HELD[-1].append(line)
    else:
        os.write(2, line.encode())


_HELD: list[list[str]] = []


@contextlib.contextmanager
def held_warnings() -> Iterator[None]:
    """Hold the warnings of the block and print them when it ends without an
    error; drop them when it raises (a refusal is its one line on stderr,
    whenever in the command it comes: after the checks, at the output folder,
    in the CAD kernel)."""
    _HELD.append([])
    try:
        yield
    except BaseException:
        _HELD.pop()
        raise
    lines = _HELD.pop()
    if lines:
        os.write(2, "".join(lines).encode())


def one_line(text: str) -> str:
    return " ".join(str(text).split())


# -- entry point ---------------------------------------------------------------------
def os_message(exc: OSError) -> str:
    where = exc.filename if exc.filename is not None else ""
    what = exc.strerror or str(exc)
    return f"{where}: {what}" if where else what
