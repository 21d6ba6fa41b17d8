"""The pool backend's scheduling: this process evaluates batches whenever
the workers have theirs in hand (while they start, and a small sweep), and
every batch comes back exactly once, from wherever it ran."""

from __future__ import annotations

import concurrent.futures
import threading
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
    monkeypatch.setattr(
        backends, "evaluate_batch", lambda batch: [{"key": batch.n, "where": "here"}]
    )
    SlowPool.given = []
    rows = [r for rows in backends.pool_rows(_batches(40), workers=2) for r in rows]
    assert sorted(r["key"] for r in rows) == list(range(40))  # each batch once
    pooled = [r["key"] for r in rows if r["where"] == "pool"]
    assert sorted(pooled) == sorted(SlowPool.given)
    # the pool holds two batches a worker; this process did the rest at once
    assert len(SlowPool.given) == 4
    assert sum(r["where"] == "here" for r in rows) == 36
