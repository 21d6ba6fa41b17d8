"""Run a sweep: the designs not yet in the journal, in batches, on a backend.

:func:`run_sweep` reads the folder's journal, skips every design it holds
finished (same key, the measures asked for with their settings, its
thumbnail if asked for), hands the others to the backend in batches and
journals each row as its batch comes back (a thumbnail first goes to
``img/KEY.png``). Batches grow to about :data:`BATCH_SECONDS` of work each
(from the time designs took so far), so a worker gets few messages and a
stopped sweep loses little. The files are rebuilt from the journal at the
end, and also when the run is stopped (Ctrl-C, SIGTERM) or fails.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Generator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from onefold_cad.export.atomic import atomic_output
from onefold_cad.sweep.backends import (
    DaskSession,
    dask_rows,
    default_workers,
    inline_rows,
    pool_rows,
)
from onefold_cad.sweep.evaluate import Batch
from onefold_cad.sweep.journal import JOURNAL, Journal, read_journal
from onefold_cad.sweep.outputs import SweepFiles, write_outputs
from onefold_cad.sweep.plan import SweepPlan, input_values
from onefold_cad.sweep.progress import Progress

__all__ = ["BATCH_SECONDS", "MAX_BATCH", "SweepRun", "is_finished", "run_sweep"]

#: About how long one batch should take a worker (s).
BATCH_SECONDS = 0.5
#: The most designs in one batch.
MAX_BATCH = 256


@dataclass(frozen=True)
class SweepRun:
    """What a run did.

    Attributes:
        designs: the sweep's designs.
        skipped: finished by an earlier run.
        evaluated: evaluated by this run.
        failed: designs of the sweep whose row is an error.
        rate: designs per second this run evaluated (wall clock).
        files: the files written.
    """

    designs: int
    skipped: int
    evaluated: int
    failed: int
    rate: float
    files: SweepFiles


def is_finished(row: dict[str, Any] | None, plan: SweepPlan, folder: Path) -> bool:
    """Whether a journal row finishes its design for ``plan``."""
    if row is None or row.get("status") not in ("ok", "error"):
        return False
    if not set(plan.measure_tags) <= set(row.get("measures", ())):
        return False
    if plan.images and row["status"] == "ok":
        return bool(row.get("img")) and (folder / row["img"]).is_file()
    return True


class _Batches:
    """Hands out the designs to do in batches sized from the time designs take."""

    def __init__(self, plan: SweepPlan, todo: list[int], workers: int) -> None:
        self.plan, self.todo, self.workers = plan, todo, workers
        self.next = 0
        self.seconds = 0.0
        self.timed = 0

    def record(self, rows: list[dict[str, Any]]) -> None:
        for r in rows:
            self.seconds += float(r.get("seconds") or 0.0)
            self.timed += 1

    def size(self) -> int:
        left = len(self.todo) - self.next
        if not self.timed:
            return 1
        per = max(self.seconds / self.timed, 1e-4)
        # No worker waits for another's long batch: the rest shared among the
        # batches in flight (two a worker) and the one this process evaluates.
        share = -(-left // (2 * self.workers + 1))
        return max(1, min(int(BATCH_SECONDS / per), MAX_BATCH, share))

    def __call__(self) -> Batch | None:
        if self.next >= len(self.todo):
            return None
        idx = self.todo[self.next : self.next + self.size()]
        self.next += len(idx)
        p = self.plan
        designs = tuple((p.keys[i], p.flags_of(i)) for i in idx)
        return Batch(p.template, p.raw, p.implicit, designs, p.measures, p.images, p.simulation)


def _backend(
    batches: _Batches, jobs: int, session: DaskSession | None
) -> Generator[list[dict[str, Any]], None, None]:
    if session is not None:
        return dask_rows(batches, session)
    if jobs <= 1:
        return inline_rows(batches)
    return pool_rows(batches, jobs)


def run_sweep(
    plan: SweepPlan,
    folder: str | os.PathLike[str],
    *,
    jobs: int | None = None,
    scheduler: str | None = None,
    quiet: bool = False,
) -> SweepRun:
    """Run the designs of ``plan`` not yet finished in ``folder`` and write
    the sweep's files there.

    Args:
        plan: the checked plan (:func:`onefold_cad.sweep.plan.make_plan`).
        folder: the output folder (made if missing).
        jobs: worker processes (default: every core); 1 runs in this process.
        scheduler: a Dask scheduler's address, or 'local' for a new
            LocalCluster (None: the process pool).
        quiet: no progress on stderr.
    """
    out = Path(folder)
    workers = jobs or default_workers()
    index = {k: i for i, k in enumerate(plan.keys)}
    if scheduler and _todo(plan, out, read_journal(out / JOURNAL)):
        session: Any = DaskSession(scheduler, jobs)  # before any file: an address may not answer
    else:
        session = contextlib.nullcontext()
    with session, Journal(out) as journal:
        todo = _todo(plan, out, read_journal(journal.path))
        skipped = len(plan.keys) - len(todo)
        progress = Progress(len(plan.keys), skipped, quiet)
        lanes = session.slots if isinstance(session, DaskSession) else workers
        batches = _Batches(plan, todo, lanes)
        dask = session if isinstance(session, DaskSession) else None
        try:
            if todo:
                with contextlib.closing(_backend(batches, workers, dask)) as results:
                    for rows in results:
                        batches.record(rows)
                        for r in rows:
                            journal.append(_journal_row(plan, index[r["key"]], r, out))
                        progress.add(len(rows), sum(r["status"] != "ok" for r in rows))
        finally:
            files = write_outputs(plan, out)
    progress.finish()
    failed = files.rows - files.ok
    return SweepRun(len(plan.keys), skipped, progress.done, failed, progress.rate, files)


def _todo(plan: SweepPlan, out: Path, known: dict[str, dict[str, Any]]) -> list[int]:
    """The designs of ``plan`` the journal's rows ``known`` do not finish."""
    return [i for i, k in enumerate(plan.keys) if not is_finished(known.get(k), plan, out)]


def _journal_row(plan: SweepPlan, i: int, row: dict[str, Any], out: Path) -> dict[str, Any]:
    """The journal's row of design ``i``: its inputs, measures and outputs; a
    thumbnail's bytes written to ``img/KEY.png`` and named in ``img``."""
    png = row.pop("png", None)
    if png is not None:
        (out / "img").mkdir(exist_ok=True)
        name = f"img/{row['key']}.png"
        with atomic_output(out / name) as tmp:
            tmp.write_bytes(png)
        row["img"] = name
    return {**input_values(plan.points[i]), "measures": list(plan.measure_tags), **row}
