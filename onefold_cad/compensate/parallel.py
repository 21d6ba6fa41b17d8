"""Where a compensation's simulations run: this process (``-j 1``), a local
process pool of ``-j N`` workers, or a Dask cluster (``--scheduler``; the
sweep's :class:`~onefold_cad.sweep.backends.DaskSession`).

The finite differences of one step are independent simulations: they run
side by side. Each task is :func:`run_one`, a module-level function taking a
design and the mesh level and returning plain data (a
:class:`~onefold_cad.compensate.evaluate.Standing`, or the one line of the
error that refused it).
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Sequence
from typing import Any

from onefold_cad.compensate.evaluate import Standing, simulate_standing
from onefold_cad.design import Design
from onefold_cad.errors import OneFoldError

__all__ = ["Evaluator", "run_one"]


def run_one(design: Design, level: str, check: bool = False, law: str = "moment") -> Standing | str:
    """Simulate one candidate with the bending ``law``; a refused or
    unconverged one gives its error's one line instead (the optimiser steps
    back from it)."""
    try:
        return simulate_standing(design, level, check, law)
    except OneFoldError as exc:
        return " ".join(str(exc).split())


def _worker_start(parent: int) -> None:
    """A pool worker leaves Ctrl-C to the command (which stops the pool), and
    leaves when the command's process is gone (even SIGKILLed: a killed
    compensation leaves no worker simulating on)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)

    def watch() -> None:
        while True:
            time.sleep(0.5)
            if os.getppid() != parent and not _alive(parent):
                os._exit(1)

    threading.Thread(target=watch, daemon=True, name="onefold-compensate-watch").start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


class Evaluator:
    """Runs batches of simulations (a context manager: the pool or cluster
    lives as long as the compensation).

    Args:
        workers: processes side by side (1: in this process).
        scheduler: a Dask scheduler's address, 'local', or None.
        law: the bending law of every simulation (``simulate``'s ``law``).
    """

    def __init__(self, workers: int = 1, scheduler: str | None = None, law: str = "moment") -> None:
        from onefold_cad.choices import Law

        self.law = Law.parse(law).value
        self.workers = max(1, int(workers))
        self.scheduler = scheduler
        #: CPU seconds of the simulations run in other processes (the pool's
        #: workers, the cluster's): beyond this process's resource usage
        self.worker_cpu_s = 0.0
        self._pool: Any = None
        self._dask: Any = None
        if scheduler is not None:
            from onefold_cad.sweep.backends import DaskSession

            self._dask = DaskSession(scheduler, workers if workers > 1 else None)
            self.workers = self._dask.slots
        elif self.workers > 1:
            from concurrent.futures import ProcessPoolExecutor

            methods = multiprocessing.get_all_start_methods()
            ctx = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
            if "forkserver" in methods:
                ctx.set_forkserver_preload(["onefold_cad.compensate.parallel"])
            self._pool = ProcessPoolExecutor(
                self.workers, mp_context=ctx, initializer=_worker_start, initargs=(os.getpid(),)
            )

    def __enter__(self) -> Evaluator:
        return self

    def __exit__(self, kind: object, *exc: object) -> None:
        self.close(wait=kind is None)

    def close(self, wait: bool = True) -> None:
        """Stop the pool or leave the cluster. ``wait``: let the workers finish
        and leave (their CPU time is then this process's children's); else
        terminate them (a stopped command does not wait for a simulation)."""
        if self._pool is not None:
            if not wait:  # stopped (Ctrl-C, SIGTERM, an error): no simulation runs on
                for proc in list(getattr(self._pool, "_processes", {}).values()):
                    proc.terminate()
            self._pool.shutdown(wait=wait, cancel_futures=True)
            self._pool = None
        if self._dask is not None:
            self._dask.close()
            self._dask = None

    def map(
        self, designs: Sequence[Design], level: str, check: bool = False
    ) -> list[Standing | str]:
        """Simulate ``designs`` (side by side when there are workers), in order."""
        if self._dask is not None:
            client = self._dask.client
            futures = [
                client.submit(run_one, d, level, check, self.law, pure=False) for d in designs
            ]
            return self._elsewhere(client.gather(futures))
        n = len(designs)
        if self._pool is not None and n > 1:
            args = ([level] * n, [check] * n, [self.law] * n)
            return self._elsewhere(self._pool.map(run_one, designs, *args))
        return [run_one(d, level, check, self.law) for d in designs]

    def _elsewhere(self, results: Any) -> list[Standing | str]:
        """``results`` of another process, their CPU time counted."""
        out = list(results)
        self.worker_cpu_s += sum(s.cpu_s for s in out if not isinstance(s, str))
        return out
