"""The steel view's rule on the server: only the latest design is simulated.

With the page's "Steel" view on, every slider release asks ``/api/steel``
(the query of ``/api/state``) for the new design's coarse simulation
(:func:`onefold_cad.explore.simulation.simulation_state`). A release that
comes while a simulation runs makes every earlier steel request stale: a
stale request still waiting for the simulation before it never starts, and
the one running is given up at its next Newton step (a stale run's answer is
``ok: false, superseded: true``, which the page drops). So the server never
works through a queue of designs the user has already left; the Simulate
button's requests are never given up.

The rule is per server (:class:`LatestOnly`, one ticket per request), not
per page: with two pages open on one explorer, the latest steel request of
either wins.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

__all__ = ["LatestOnly"]


class LatestOnly:
    """Numbered tickets: a ticket is stale as soon as a newer one is issued."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._latest = 0

    def ticket(self) -> Callable[[], bool]:
        """A new ticket, the latest from now on: the returned function says
        whether a newer ticket has been issued since (thread-safe)."""
        with self._lock:
            self._latest += 1
            mine = self._latest
        return lambda: self._latest != mine
