"""A server test's count of the connections its handler serves at once
(the explorer's and the Hops server's connection bounds)."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest


class Served:
    """How many requests a handler class serves now, and the most at once."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch, handler: type, timeout: float) -> None:
        self.lock = threading.Lock()
        self.now = 0
        self.peak = 0
        handle = handler.handle

        def counted(this: Any) -> None:
            with self.lock:
                self.now += 1
                self.peak = max(self.peak, self.now)
            try:
                handle(this)
            finally:
                with self.lock:
                    self.now -= 1

        monkeypatch.setattr(handler, "timeout", timeout)
        monkeypatch.setattr(handler, "handle", counted)

    def wait_for(self, count: int, seconds: float = 30.0) -> bool:
        """Wait until ``count`` are served (at most ``seconds``); whether they are."""
        deadline = time.monotonic() + seconds
        while self.now != count and time.monotonic() < deadline:
            time.sleep(0.01)
        return self.now == count
