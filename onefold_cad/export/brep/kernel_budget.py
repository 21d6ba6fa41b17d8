"""The CAD kernel's time budget for one part: a check the builders call between
kernel operations, raising a clear error when the part takes too long."""

from __future__ import annotations

import time

from onefold_cad.errors import ExportError

__all__ = ["KernelBudget"]


class KernelBudget:
    """A time budget (s) for the CAD kernel's work on one part; :meth:`check`
    raises ExportError naming ``advice`` once it is spent."""

    def __init__(self, seconds: float | None, advice: str) -> None:
        self.deadline = None if seconds is None else time.perf_counter() + seconds
        self.seconds = seconds
        self.advice = advice

    def check(self) -> None:
        if self.deadline is not None and time.perf_counter() > self.deadline:
            raise ExportError(
                f"the CAD kernel's time budget of {self.seconds:g} s ran out; {self.advice}"
            )
