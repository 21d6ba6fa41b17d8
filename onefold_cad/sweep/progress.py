"""The sweep's progress on stderr: count, rate and time left.

On a terminal one line is rewritten in place (at most 5 times a second);
elsewhere (a log file, CI) a line is printed at most every 10 s. Each line
is one ``write``. ``--quiet`` prints nothing.
"""

from __future__ import annotations

import os
import sys
import time

__all__ = ["Progress", "duration"]


def duration(seconds: float) -> str:
    """``42 s``, ``3 min 5 s``, ``2 h 10 min``."""
    s = int(round(max(0.0, seconds)))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60} s"
    return f"{s // 3600} h {s % 3600 // 60} min"


class Progress:
    """Counts the designs of a sweep as they finish and says so on stderr.

    Args:
        total: the designs of the sweep.
        skipped: those finished by an earlier run (not counted in the rate).
        quiet: print nothing.
    """

    def __init__(self, total: int, skipped: int = 0, quiet: bool = False) -> None:
        self.total = total
        self.skipped = skipped
        self.quiet = quiet
        self.done = 0
        self.failed = 0
        self.start = time.perf_counter()
        self._last = 0.0
        self._tty = sys.stderr.isatty()
        self._every = 0.2 if self._tty else 10.0

    @property
    def rate(self) -> float:
        """Designs per second evaluated by this run."""
        elapsed = time.perf_counter() - self.start
        return self.done / elapsed if elapsed > 0 else 0.0

    def text(self) -> str:
        """The progress line (no newline)."""
        n = self.skipped + self.done
        rate = self.rate
        left = self.total - n
        eta = f", ETA {duration(left / rate)}" if rate > 0 and left else ""
        failed = f", {self.failed} failed" if self.failed else ""
        resumed = f" ({self.skipped} from an earlier run)" if self.skipped else ""
        return f"sweep: {n}/{self.total} designs{resumed}, {rate:.3g}/s{eta}{failed}"

    def _write(self, text: str) -> None:
        os.write(2, text.encode())

    def add(self, done: int, failed: int = 0) -> None:
        """``done`` more designs finished, ``failed`` of them with an error."""
        self.done += done
        self.failed += failed
        now = time.perf_counter()
        if self.quiet or now - self._last < self._every:
            return
        self._last = now
        self._write(f"\r{self.text()}\x1b[K" if self._tty else f"{self.text()}\n")

    def finish(self) -> None:
        """The last line: the whole run's count, rate and time."""
        if self.quiet:
            return
        line = f"{self.text()}; {duration(time.perf_counter() - self.start)}"
        self._write(f"\r{line}\x1b[K\n" if self._tty else f"{line}\n")
