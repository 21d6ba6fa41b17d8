"""The pool backend's scheduling: this process evaluates batches whenever
the workers have theirs in hand (while they start, and a small sweep), and
every batch comes back exactly once, from wherever it ran."""

from __future__ import annotations

import concurrent.futures
import threading
import time
from types import SimpleNamespace

from onefold_cad.sweep import backends


class SlowPool:
    """A stand-in for ProcessPoolExecutor whose workers take ``delay`` seconds
    to answer (a pool still importing), and that records what it was given."""

    delay = 0.3
    given: list[int] = []

    def __init__(self, *args, **kwargs) -> None:
        pass

    def submit(self, fn, batch):
        fut: concurrent.futures.Future = concurrent.futures.Future()
        SlowPool.given.append(batch.n)

        def answer() -> None:
            fut.set_result([{"key": batch.n, "where": "pool"}])

        threading.Timer(self.delay, answer).start()
        return fut

    def shutdown(self, wait=True, cancel_futures=False) -> None:
        pass


def _batches(n: int):
    it = iter(range(n))

    def next_batch():
        k = next(it, None)
        return None if k is None else SimpleNamespace(n=k, images=False)

    return next_batch


def test_this_process_works_while_the_pool_starts(monkeypatch):
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", SlowPool)
    monkeypatch.setattr(backends, "_context", lambda images: None)

    def evaluate(batch):
        deadline = time.monotonic() + 5.0
        while not SlowPool.given and time.monotonic() < deadline:
            time.sleep(0.001)  # the pool's start (on its own thread) has its first batch
        time.sleep(0.001)  # a design takes time (and lets that thread end)
        return [{"key": batch.n, "where": "here"}]

    monkeypatch.setattr(backends, "evaluate_batch", evaluate)
    SlowPool.given = []
    rows = [r for rows in backends.pool_rows(_batches(40), workers=2) for r in rows]
    assert sorted(r["key"] for r in rows) == list(range(40))  # each batch once
    pooled = [r["key"] for r in rows if r["where"] == "pool"]
    assert sorted(pooled) == sorted(SlowPool.given)
    # the pool holds two batches a worker; this process did the rest at once
    assert len(SlowPool.given) == 4
    assert sum(r["where"] == "here" for r in rows) == 36


class BlockingStartPool(SlowPool):
    """A pool whose first submit blocks until this process has evaluated
    batches (as the first worker's start waits on the forkserver's imports),
    for at most ``patience`` seconds; records whether it had to give up."""

    patience = 5.0
    started = threading.Event()
    gave_up = False

    def submit(self, fn, batch):
        if not SlowPool.given:
            BlockingStartPool.gave_up = not self.started.wait(self.patience)
        return super().submit(fn, batch)


def test_this_process_works_while_the_first_worker_starts(monkeypatch):
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", BlockingStartPool)
    monkeypatch.setattr(backends, "_context", lambda images: None)
    here: list[int] = []

    def evaluate(batch):
        here.append(batch.n)
        if len(here) == 3:  # the worker's start can end now
            BlockingStartPool.started.set()
        return [{"key": batch.n, "where": "here"}]

    monkeypatch.setattr(backends, "evaluate_batch", evaluate)
    SlowPool.given, BlockingStartPool.gave_up = [], False
    BlockingStartPool.started.clear()
    rows = [r for rows in backends.pool_rows(_batches(40), workers=2) for r in rows]
    assert not BlockingStartPool.gave_up  # this process did not wait on the start
    assert sorted(r["key"] for r in rows) == list(range(40))
    assert here[:3] == [1, 2, 3]  # batch 0 went to the starting worker
