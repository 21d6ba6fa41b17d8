"""The page's Compensate action: one compensation job per server, in the background.

``/api/compensate/start?...`` (the query of ``/api/state``) checks the
design as ``onefold compensate`` does before any simulation (the target:
the design's own form, standing as designed; a design without steel data
or that cannot be simulated is refused in one line) and answers at once
with a job number; a thread then runs
:func:`onefold_cad.compensate.run.compensate` itself, the function the
command calls, as a **coarse preview**: the search and its two checks on
the coarse mesh (:data:`LEVEL`, the Simulate button's), without the mesh
convergence check. It takes about a minute of one core for a 10 x 24 ft
sheet where the command's method (coarse search, normal-mesh finish and
checks) takes minutes; the page says so and names the command for the
normal mesh.

``/api/compensate/progress?job=N`` answers the lines the compensation said
so far, its ETA, the simulations done and, once finished, its result (the
report's ``compensation`` section, :meth:`Compensation.to_data`, with
``values`` and ``start_values``: the page's control texts of the compensated
and the start design, the job's query with alpha, beta and hc_fraction
replaced) or its error line. ``/api/compensate/cancel?job=N`` stops it
at its next simulation at the latest.

The simulations run in the server's process, one at a time
(:class:`_Watched`, an in-process :class:`~onefold_cad.compensate.parallel.Evaluator`):
a compensation takes one core and leaves the other to the page's Simulate and
Steel view; a cancel needs no worker process stopped (there is none), and
no simulation starts after it. One job runs at a time: a second start while
one runs is refused in one line (it may be another tab's: a start never
throws away minutes of someone's run). Finished jobs are kept
:data:`KEEP_S` seconds, the last :data:`KEEP_JOBS` of them.
"""

from __future__ import annotations

import math
import re
import sys
import threading
import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from http import HTTPStatus
from typing import Any
from urllib.parse import parse_qsl

from onefold_cad.compensate.evaluate import Standing
from onefold_cad.compensate.parallel import Evaluator, run_one
from onefold_cad.design import Design
from onefold_cad.errors import OneFoldError, memory_message
from onefold_cad.explore.controls import ParameterProblem, QueryError, page_values, parse_query
from onefold_cad.explore.simulation import steel_law

__all__ = ["KEEP_JOBS", "KEEP_S", "LEVEL", "MAX_LINES", "Compensations"]

#: The mesh of the explorer's compensation: search and checks (the Simulate button's).
LEVEL = "coarse"
#: Finished jobs kept: for this many seconds, and at most this many.
KEEP_S = 900.0
KEEP_JOBS = 4
#: Progress lines kept per job (the last ones).
MAX_LINES = 200
#: The page's controls a compensation changes.
KNOBS = ("alpha", "beta", "hc_fraction")
#: What the search moves: the sliders' knobs only (the page has no crease
#: overbend to load an answer's into).
SEARCHED = ("alpha", "beta", "h_c")

_ETA = re.compile(r"ETA (.+)$")


class _Cancelled(Exception):
    """Raised in the job's thread at the simulation after a cancel."""


@dataclass
class _Job:
    """One compensation (mutable: its thread fills it under the jobs' lock)."""

    number: int
    params: dict[str, str]
    started: float
    state: str = "running"  # running, done, failed, cancelled
    lines: list[str] = field(default_factory=list)
    simulations: int = 0
    ended: float | None = None
    result: dict[str, Any] | None = None
    error: str | None = None
    stop: threading.Event = field(default_factory=threading.Event)


class _Watched(Evaluator):
    """This process's evaluator, one simulation at a time, that counts them
    and starts none once its job is cancelled."""

    def __init__(self, job: _Job, lock: threading.Lock, law: str) -> None:
        super().__init__(1, law=law)
        self.job, self.lock = job, lock

    def map(
        self, designs: Sequence[Design], level: str, check: bool = False
    ) -> list[Standing | str]:
        """Simulate ``designs`` in order (:func:`run_one`, as the command's)."""
        out = []
        for d in designs:
            if self.job.stop.is_set():
                raise _Cancelled
            out.append(run_one(d, level, check, self.law))
            with self.lock:
                self.job.simulations += 1
        return out


def _line(text: object) -> str:
    return " ".join(str(text).split())


def _plain(x: Any) -> Any:
    """JSON-ready: floats as floats (not finite: None, "not available"), tuples as lists."""
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if isinstance(x, bool) or x is None or isinstance(x, (str, int)):
        return x
    v = float(x)
    return v if math.isfinite(v) else None


def _knobs(design: Design) -> dict[str, str]:
    values = page_values(design)["values"]
    return {k: values[k] for k in KNOBS}


def _job_number(query: str) -> int:
    """The ``job=N`` of a progress or cancel query (nothing else accepted)."""
    try:
        pairs = parse_qsl(query, keep_blank_values=True, strict_parsing=True, max_num_fields=2)
    except ValueError as exc:
        raise QueryError(f"malformed query ({_line(exc)})") from None
    names = [k for k, _ in pairs]
    if names != ["job"]:
        other = [k for k in names if k != "job"]
        raise QueryError(f"unknown parameter {other[0][:40]!r}" if other else "job: give one job=N")
    text = pairs[0][1]
    if not (text.isdigit() and len(text) <= 12):
        raise QueryError(f"job: must be a job number, got {text[:40]!r}")
    return int(text)


class Compensations:
    """The server's compensation jobs (thread-safe)."""

    def __init__(self, clock: Callable[[], float] = time.monotonic) -> None:
        self._lock = threading.Lock()
        self._jobs: dict[int, _Job] = {}
        self._count = 0
        self._clock = clock

    def answer(
        self, action: str, query: str, design_of: Callable[[str], Design]
    ) -> tuple[int, dict[str, Any]]:
        """The HTTP status and JSON of ``/api/compensate/<action>?<query>``.

        Raises:
            QueryError: a malformed query or an unknown parameter (HTTP 400).
        """
        if action == "start":
            params = parse_query(query)
            params.pop("mesh", None)
            try:
                design = design_of(query)
            except ParameterProblem as exc:
                return HTTPStatus.UNPROCESSABLE_ENTITY, _refused(exc.message)
            return self.start(design, params)
        if action in ("progress", "cancel"):
            number = _job_number(query)
            with self._lock:
                self._forget()
                job = self._jobs.get(number)
                if job is None:
                    return HTTPStatus.NOT_FOUND, _refused(
                        f"job: no compensation {number} (finished ones are kept "
                        f"{KEEP_S / 60:g} min, the last {KEEP_JOBS})"
                    )
                if action == "cancel" and job.state == "running":
                    job.stop.set()
                return HTTPStatus.OK, self._progress(job)
        return HTTPStatus.NOT_FOUND, _refused("not found")

    def start(self, design: Design, params: dict[str, str]) -> tuple[int, dict[str, Any]]:
        """Check ``design`` and start its compensation (see the module docstring)."""
        from onefold_cad.compensate.target import make_target

        with self._lock:
            running = [j.number for j in self._jobs.values() if j.state == "running"]
        if running:
            return HTTPStatus.CONFLICT, _refused(
                f"compensation {running[0]} is running: cancel it or wait for it (one at a time)"
            )
        try:
            target = make_target(design, "design")  # no simulation: the CLI's checks
        except OneFoldError as exc:
            return HTTPStatus.UNPROCESSABLE_ENTITY, _refused(
                f"cannot compensate this design: {_line(exc)}"
            )
        with self._lock:
            if any(j.state == "running" for j in self._jobs.values()):
                return HTTPStatus.CONFLICT, _refused("a compensation is running: one at a time")
            self._count += 1
            job = _Job(self._count, dict(params), self._clock())
            self._jobs[job.number] = job
            self._forget()
        threading.Thread(
            target=self._run, args=(job, design, target), daemon=True, name="onefold-compensate"
        ).start()
        return HTTPStatus.OK, self._progress(job)

    def close(self) -> None:
        """Cancel the running job (the server stops)."""
        with self._lock:
            for job in self._jobs.values():
                job.stop.set()

    def _say(self, job: _Job) -> Callable[[str], None]:
        def say(text: str) -> None:
            with self._lock:
                job.lines.append(_line(text))
                del job.lines[:-MAX_LINES]

        return say

    def _run(self, job: _Job, design: Design, target: Any) -> None:
        from onefold_cad.compensate.run import compensate

        state, result, error = "done", None, None
        try:
            with _Watched(job, self._lock, steel_law(design)) as evaluator:
                c = compensate(design, target, evaluator, self._say(job), coarse=LEVEL,
                               fine=LEVEL, check=False, knobs=SEARCHED)  # fmt: skip
            result = _plain(c.to_data()) | {"law": evaluator.law}
            start = {k: v for k, v in job.params.items() if k != "template"}
            result["values"] = {**start, **_knobs(c.compensated)}
            result["start_values"] = {**start, **_knobs(c.start)}
        except _Cancelled:
            state, error = "cancelled", "cancelled"
        except OneFoldError as exc:
            state, error = "failed", f"cannot compensate this design: {_line(exc)}"
        except MemoryError as exc:
            state, error = "failed", memory_message(exc)
        except Exception as exc:  # the page shows this line; the log has the traceback
            traceback.print_exc(file=sys.stderr)
            state, error = "failed", f"internal error ({type(exc).__name__}: {_line(exc)})"
        with self._lock:
            job.state, job.result, job.error, job.ended = state, result, error, self._clock()

    def _forget(self) -> None:
        """Drop finished jobs older than :data:`KEEP_S` or beyond the last
        :data:`KEEP_JOBS` (under the lock)."""
        now = self._clock()
        done = [j for j in self._jobs.values() if j.ended is not None]
        done.sort(key=lambda j: j.number)
        for i, j in enumerate(done):
            assert j.ended is not None
            if now - j.ended > KEEP_S or i < len(done) - KEEP_JOBS:
                del self._jobs[j.number]

    def _progress(self, job: _Job) -> dict[str, Any]:
        """The job as the page reads it (under the lock)."""
        eta = None
        if job.state == "running":
            found = [m for m in (_ETA.search(t) for t in job.lines[-1:]) if m]
            eta = found[0].group(1) if found else None
        end = job.ended if job.ended is not None else self._clock()
        return {
            "ok": job.state != "failed",
            "job": job.number,
            "state": job.state,
            "level": LEVEL,
            "design": dict(job.params),
            "lines": list(job.lines),
            "eta": eta,
            "simulations": job.simulations,
            "elapsed_s": end - job.started,
            "result": job.result,
            "error": job.error,
        }


def _refused(text: str) -> dict[str, Any]:
    return {"ok": False, "error": _line(text)}
