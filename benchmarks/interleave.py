"""Honest timing helpers shared by every benchmark here.

* :func:`interleave` times several in-process callables A B A B ... (the
  order rotated every round), so that a burst of load on a shared machine
  hits all of them alike, and reports per-call medians with their spread
  (25th and 75th percentile), in CPU time of this process by default.
* :func:`paired_ratio` gives the median and spread of the per-round ratios
  of two of them (baseline / ours), the number to quote.
* :func:`run_process` runs a whole command (imports included) and returns
  its wall time, CPU time and peak memory, measured by the OS (wait4).

Nothing here asserts: benchmarks print, tests never time.
"""

from __future__ import annotations

import math
import os
import statistics
import subprocess
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["Stats", "interleave", "paired_ratio", "ProcessRun", "run_process", "stats_of"]

CLOCKS: dict[str, Callable[[], float]] = {
    "cpu": time.process_time,
    "wall": time.perf_counter,
}


@dataclass(frozen=True)
class Stats:
    """Median and spread of repeated measurements (seconds, or a ratio).

    Attributes:
        median: the median.
        q1, q3: the 25th and 75th percentiles.
        n: how many measurements.
        samples: the measurements themselves, in the order taken.
    """

    median: float
    q1: float
    q3: float
    n: int
    samples: tuple[float, ...]

    def fmt(self, scale: float = 1.0, unit: str = "", digits: int = 3) -> str:
        """'median [q1, q3] unit' with every value multiplied by ``scale``."""
        m, a, b = (x * scale for x in (self.median, self.q1, self.q3))
        return f"{m:.{digits}g} [{a:.{digits}g}, {b:.{digits}g}]{unit}"


def stats_of(values: Sequence[float]) -> Stats:
    """:class:`Stats` of ``values`` (at least one)."""
    raw = tuple(float(x) for x in values)
    if not raw:
        raise ValueError("no measurements")
    if len(raw) == 1:
        return Stats(raw[0], raw[0], raw[0], 1, raw)
    q = statistics.quantiles(raw, n=4, method="inclusive")
    return Stats(statistics.median(raw), q[0], q[2], len(raw), raw)


def _calibrate(fn: Callable[[], Any], clock: Callable[[], float], batch_time: float) -> int:
    """How many calls make one batch last about ``batch_time`` seconds."""
    n = 1
    while True:
        t0 = clock()
        for _ in range(n):
            fn()
        dt = clock() - t0
        if dt >= batch_time or n >= 1 << 20:
            return max(1, math.ceil(n * batch_time / max(dt, 1e-9)))
        n *= 4


def interleave(
    cases: Mapping[str, Callable[[], Any]],
    *,
    rounds: int = 31,
    batch_time: float = 0.01,
    clock: str = "cpu",
) -> dict[str, Stats]:
    """Per-call time of each callable, measured interleaved.

    Each round runs one batch of every case (a batch is as many calls as
    last about ``batch_time`` s, calibrated once per case), in an order
    rotated every round: A B C, B C A, C A B, ... The per-call time of a
    batch is its time / its calls.

    Args:
        cases: name -> zero-argument callable.
        rounds: batches per case.
        batch_time: target duration of a batch (s).
        clock: 'cpu' (this process's CPU time, default) or 'wall'.

    Returns:
        name -> :class:`Stats` of the per-call times (s), in the order given.
    """
    tick = CLOCKS[clock]
    names = list(cases)
    for fn in cases.values():  # warm up (imports, caches)
        fn()
    calls = {k: _calibrate(cases[k], tick, batch_time) for k in names}
    times: dict[str, list[float]] = {k: [] for k in names}
    for i in range(rounds):
        order = names[i % len(names) :] + names[: i % len(names)]
        for k in order:
            fn, n = cases[k], calls[k]
            t0 = tick()
            for _ in range(n):
                fn()
            times[k].append((tick() - t0) / n)
    return {k: stats_of(times[k]) for k in names}


def paired_ratio(results: Mapping[str, Stats], baseline: str, ours: str) -> Stats:
    """Median and spread of the per-round ratios baseline / ours (rounds of
    :func:`interleave` run side by side, so each ratio shares its load)."""
    a, b = results[baseline].samples, results[ours].samples
    return stats_of([x / y for x, y in zip(a, b, strict=True)])


@dataclass(frozen=True)
class ProcessRun:
    """One run of a command: wall and CPU time (s), peak memory (bytes), exit status."""

    wall: float
    cpu: float
    peak_rss: int
    returncode: int


def run_process(
    argv: Sequence[str], *, env: Mapping[str, str] | None = None, cwd: str | None = None
) -> ProcessRun:
    """Run ``argv`` to completion (output discarded) and measure it with wait4:
    wall time, user + system CPU time and peak resident memory of the child."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        list(argv),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=None if env is None else dict(env),
        cwd=cwd,
    )
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    return ProcessRun(
        wall=wall,
        cpu=usage.ru_utime + usage.ru_stime,
        peak_rss=int(usage.ru_maxrss) * 1024,
        returncode=proc.returncode,
    )
