"""Where a sweep's batches run: this process, a local process pool, or a Dask
cluster. Each backend takes batches from ``next_batch`` (None: no more),
keeps about two per worker in flight and yields the rows of each batch as
it finishes; the runner journals them.

* :func:`inline_rows`: in this process, one batch at a time (``-j 1``).
* :func:`pool_rows`: a ``concurrent.futures`` process pool of ``-j N``
  workers, started once (a forkserver that has imported the evaluation
  code, and with thumbnails what they draw with: no worker imports
  anything per design). This process evaluates batches too whenever the
  workers have theirs (two each) in hand: while they start (a second or two
  of imports, waited for on a thread of their own) the sweep is not idle,
  and a small sweep is done before a pool would have paid off. Workers
  ignore Ctrl-C (the sweep stops them) and leave when the sweep's process
  is gone.
* :func:`dask_rows`: a Dask distributed cluster, ``Client(address)`` with
  futures and ``as_completed``; ``local`` starts a ``LocalCluster`` of ``-j
  N`` worker processes. dask is imported here only.

A batch whose worker died (a crash, not an exception of a design: those are
rows) comes back as rows of status ``lost``, which a rerun runs again.
"""

from __future__ import annotations

import importlib.util
import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Callable, Generator
from typing import Any

from onefold_cad.errors import not_installed
from onefold_cad.flags.parser import UsageError
from onefold_cad.sweep.evaluate import Batch, evaluate_batch

__all__ = [
    "INSTALL_CLUSTER",
    "DaskSession",
    "check_dask",
    "dask_rows",
    "default_workers",
    "inline_rows",
    "lost_rows",
    "pool_rows",
]

NextBatch = Callable[[], Batch | None]
Rows = list[dict[str, Any]]

#: What to install for ``--scheduler``.
INSTALL_CLUSTER = "pip install 'onefold_cad[cluster]'"


def default_workers() -> int:
    """The cores this process may run on."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not Linux
        return max(1, os.cpu_count() or 1)


def check_dask() -> None:
    """Raise :class:`UsageError` (one line: what to install) without dask.distributed."""
    if importlib.util.find_spec("distributed") is None:
        raise UsageError(not_installed("--scheduler (a Dask cluster)", ["distributed"], "cluster"))


def lost_rows(batch: Batch, why: BaseException) -> Rows:
    """Rows of status ``lost`` for the designs of a batch whose worker died."""
    text = " ".join(f"{type(why).__name__}: {why}".split())
    return [
        {"key": key, "name": None, "status": "lost", "error": f"worker lost: {text}",
         "seconds": 0.0}
        for key, _ in batch.designs
    ]  # fmt: skip


def inline_rows(next_batch: NextBatch) -> Generator[Rows, None, None]:
    """Evaluate the batches in this process, one after the other."""
    while (batch := next_batch()) is not None:
        yield evaluate_batch(batch)


def _worker_start(parent: int) -> None:
    """A pool worker's start: Ctrl-C is the sweep's to handle, and the worker
    leaves when the process that started the pool is gone (even SIGKILLed)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)

    def watch() -> None:
        while True:
            time.sleep(0.5)
            try:
                os.kill(parent, 0)
            except ProcessLookupError:
                os._exit(1)
            except PermissionError:
                pass

    threading.Thread(target=watch, daemon=True, name="onefold-sweep-parent-watch").start()


#: What the forkserver also imports when the designs get thumbnails.
_PICTURES = "onefold_cad.export.pictures.preload"


def _context(images: bool) -> Any:
    if "forkserver" in multiprocessing.get_all_start_methods():
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["onefold_cad.sweep.evaluate", *([_PICTURES] * images)])
        return ctx
    return multiprocessing.get_context("spawn")


def pool_rows(next_batch: NextBatch, workers: int) -> Generator[Rows, None, None]:
    """Evaluate the batches on a local pool of ``workers`` processes."""
    from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
    from concurrent.futures.process import BrokenProcessPool

    first = next_batch()
    if first is None:
        return
    images = first.images  # the workers start with what thumbnails draw with

    def start() -> ProcessPoolExecutor:
        ctx = _context(images)
        return ProcessPoolExecutor(
            workers, mp_context=ctx, initializer=_worker_start, initargs=(os.getpid(),)
        )

    # The first submit starts the first worker, and it waits for the
    # forkserver's imports (matplotlib's with thumbnails: 0.7 s on a quiet
    # machine, 1.5 s under load): a thread waits for them while this
    # process evaluates.
    pool = start()
    launched: list[Future[Rows]] = []
    failed: list[BaseException] = []

    def launch() -> None:
        try:
            launched.append(pool.submit(evaluate_batch, first))
        except BaseException as exc:  # handed to the sweep's thread below
            failed.append(exc)

    launcher = threading.Thread(target=launch, daemon=True, name="onefold-sweep-pool-start")
    launcher.start()
    try:
        while launcher.is_alive() and (batch := next_batch()) is not None:
            yield evaluate_batch(batch)
        launcher.join()
        if failed:
            raise failed[0]
        pending: dict[Future[Rows], Batch] = {launched[0]: first}
        while True:
            while len(pending) < 2 * workers and (batch := next_batch()) is not None:
                pending[pool.submit(evaluate_batch, batch)] = batch
            if not pending:
                return
            done, _ = wait(pending, timeout=0, return_when=FIRST_COMPLETED)
            if not done:  # the workers are busy (or still starting): evaluate here
                if (batch := next_batch()) is not None:
                    yield evaluate_batch(batch)
                    continue
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
            broken = False
            for fut in done:
                batch = pending.pop(fut)
                try:
                    yield fut.result()
                except BrokenProcessPool as exc:
                    broken = True
                    yield lost_rows(batch, exc)
            if broken:  # every batch in flight is lost with the pool: start another
                for batch in list(pending.values()):
                    yield lost_rows(batch, BrokenProcessPool("a worker of the pool died"))
                pending.clear()
                pool.shutdown(wait=False, cancel_futures=True)
                pool = start()
    finally:
        launcher.join()  # a shutdown would wait for the worker's start anyway
        pool.shutdown(wait=False, cancel_futures=True)


class DaskSession:
    """A connection to a Dask cluster (a context manager): ``Client(address)``,
    or a new ``LocalCluster`` of ``workers`` processes for ``address`` 'local'.
    Connecting is the first thing a sweep on a cluster does, so an address
    that answers nothing is an error before any file is written."""

    def __init__(self, address: str, workers: int | None) -> None:
        check_dask()
        from dask.distributed import Client, LocalCluster

        self.address, self.cluster = address, None
        if address == "local":
            self.cluster = LocalCluster(
                n_workers=workers or default_workers(), threads_per_worker=1, processes=True,
                dashboard_address=None, silence_logs=40,
            )  # fmt: skip
        try:
            self.client = Client(self.cluster or address, timeout="20s")
        except OSError as exc:
            self.close()
            raise UsageError(f"--scheduler {address}: no scheduler answers ({exc})") from None
        except (ValueError, TypeError) as exc:  # distributed's own parse of the address
            self.close()
            raise UsageError(
                f"--scheduler {address}: not a scheduler's address ({exc}); give "
                "PROTOCOL://HOST:PORT (tcp://10.0.0.5:8786) or local"
            ) from None
        self.slots = workers or max(1, sum(self.client.nthreads().values()))

    def __enter__(self) -> DaskSession:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        client = getattr(self, "client", None)  # None: Client() failed
        if client is not None:
            client.close()
            del self.client
        if self.cluster is not None:
            self.cluster.close()
            self.cluster = None


def dask_rows(next_batch: NextBatch, session: DaskSession) -> Generator[Rows, None, None]:
    """Evaluate the batches on the session's cluster: futures of
    :func:`evaluate_batch`, about two per worker in flight, taken as they
    complete (``as_completed``)."""
    from dask.distributed import as_completed

    client = session.client
    futures = as_completed()
    batches: dict[Any, Batch] = {}

    def submit() -> bool:
        batch = next_batch()
        if batch is None:
            return False
        fut = client.submit(evaluate_batch, batch, pure=False)
        batches[fut.key] = batch
        futures.add(fut)
        return True

    for _ in range(2 * session.slots):
        if not submit():
            break
    for fut in futures:
        batch = batches.pop(fut.key)
        try:
            rows = fut.result()
        except Exception as exc:  # the worker died (KilledWorker) or the task could not run
            rows = lost_rows(batch, exc)
        fut.release()
        yield rows
        submit()
