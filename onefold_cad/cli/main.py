"""The ``onefold`` command's entry: build, solve, templates, explore, fit,
hops, sweep, simulate, site, compensate and loads (:data:`onefold_cad.cli.commands.COMMANDS`).

``main(argv=None) -> int`` is the entry point (``onefold`` and ``python -m
onefold_cad``), so tests can call it directly. Every error of the package,
every usage error, every OSError and every MemoryError (an allocation that
failed) becomes one line ``onefold: error: ...`` on stderr and exit status
2; warnings are lines ``onefold: warning: ...``, printed when the command
succeeds (a refused command prints only its error).
``build`` stages every file and commits the whole set at once
(:mod:`onefold_cad.export.atomic`); Ctrl-C and SIGTERM leave the output
folder as it was.

The parser is the standard library's ``argparse``: the command starts in a
few milliseconds, and nothing heavier than numpy is imported before a
command needs it (``solve``: numpy and the geometry core; ``build``: the
writers of the chosen formats).
"""

from __future__ import annotations

import contextlib
import gc
import os
import signal
import sys
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING

from onefold_cad.errors import OneFoldError, memory_message

if TYPE_CHECKING:
    pass
from onefold_cad.cli.build import STATE, interrupted_text
from onefold_cad.cli.commands import COMMANDS
from onefold_cad.cli.output import held_warnings, one_line, os_message
from onefold_cad.cli.parser import build_parser
from onefold_cad.flags.parser import UsageError

__all__ = ["main"]


class Interrupted(BaseException):
    """SIGTERM or SIGHUP, raised like KeyboardInterrupt is for SIGINT."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _raise_interrupted(signum: int, frame: object) -> None:
    raise Interrupted(signum)


@contextlib.contextmanager
def _signal_handlers() -> Iterator[None]:
    """SIGTERM and SIGHUP raise :class:`Interrupted` (as SIGINT raises
    KeyboardInterrupt) while the command runs; the old handlers come back
    afterwards. Only in the main thread (where Python delivers signals)."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {s: signal.signal(s, _raise_interrupted) for s in (signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``onefold`` command with ``argv`` (default: ``sys.argv[1:]``).

    Called without ``argv``, as the ``onefold`` program and ``python -m
    onefold_cad`` call it, it runs as the process's own command: a build moves
    the modules its writers import out of the cyclic garbage collector's way
    (:func:`_freeze_imports`), and every command freezes what is left when it
    is done, so that the interpreter's collection at exit does not walk them
    once more (0.8 s after a default build, whose output is complete by then).
    A caller passing ``argv`` (the tests, another program) keeps its collector
    as it was.

    Returns:
        The exit status: 0 on success (warnings included), 2 on bad input or a
        file that cannot be written (one line on stderr), 130 on Ctrl-C and
        128 + the signal's number on SIGTERM or SIGHUP (nothing written).
    """
    args = list(sys.argv[1:] if argv is None else argv)
    parsers = build_parser()
    STATE["process"] = argv is None
    try:
        with _signal_handlers():
            if not args or args[0] not in COMMANDS:
                if args and not args[0].startswith("-"):
                    raise UsageError(
                        f"unknown command {args[0]!r} (choose from {', '.join(COMMANDS)})"
                    )
                parsers[""].parse_args(args or ["--help"])  # --help, --version or an error
                *first, last = COMMANDS
                raise UsageError(f"a command is needed: {', '.join(first)} or {last}")
            ns = parsers[args[0]].parse_intermixed_args(args[1:])
            with held_warnings():  # printed when the command succeeds
                return COMMANDS[args[0]](ns)
    except SystemExit as exc:  # --help, --version
        return exc.code if isinstance(exc.code, int) else 0
    except (OneFoldError, UsageError) as exc:
        _error(str(exc))
        return 2
    except OSError as exc:
        _error(os_message(exc))
        return 2
    except MemoryError as exc:  # an allocation failed: one line, not a traceback
        _error(memory_message(exc))
        return 2
    except KeyboardInterrupt:
        _error(f"interrupted; {interrupted_text()}", prefix="")
        return 130
    except Interrupted as exc:
        _error(f"stopped by {exc}; {interrupted_text()}", prefix="")
        return 128 + exc.signum
    finally:
        if STATE.get("process"):
            gc.freeze()  # the process ends: its objects need no collecting
        STATE.clear()


def _error(text: str, prefix: str = "error: ") -> None:
    sys.stdout.flush()
    os.write(2, f"onefold: {prefix}{one_line(text)}\n".encode())
