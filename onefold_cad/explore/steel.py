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

A steel answer is the standing form first: its reserve check (whether the
coarse preview may say a plain "stands") is left for ``/api/steel/check``,
which the page asks once the form is drawn (:class:`LastSteel`: the server
keeps the last steel simulation only, for that check). A check is given up
like a steel run when a newer steel request comes, and takes no ticket
itself: it never makes a steel request stale.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from onefold_cad.design import Design
from onefold_cad.explore.simulation import check_state, simulation_state, steel_law
from onefold_cad.mechanics.results import Simulation

__all__ = ["NOT_LAST", "LastSteel", "LatestOnly"]

#: The check answer's ``error`` when the server's last steel simulation is of
#: another design (a newer release, or another page of this explorer).
NOT_LAST = "superseded: the server's last steel simulation is of another design"


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

    def watch(self) -> Callable[[], bool]:
        """No new ticket: the returned function says whether a ticket has been
        issued since (thread-safe)."""
        with self._lock:
            now = self._latest
        return lambda: self._latest != now


class LastSteel:
    """The server's steel requests: each takes a ticket of ``latest``; the last
    steel simulation is kept by its design's key (one only: bounded memory)
    for its reserve check."""

    def __init__(self, latest: LatestOnly) -> None:
        self._latest = latest
        self._lock = threading.Lock()
        self._last: tuple[object, Simulation] | None = None

    def simulate(self, key: object, design: Design) -> dict[str, Any]:
        """``design``'s steel answer (a new ticket: the latest request), its
        reserve check left for :meth:`check`."""
        cancelled = self._latest.ticket()

        def keep(sim: Simulation) -> None:
            with self._lock:
                self._last = (key, sim) if sim.pending_reserve is not None else None

        return simulation_state(
            design, cancelled, law=steel_law(design), check_later=True, keep=keep
        )

    def check(self, key: object, design: Design | None = None) -> dict[str, Any]:
        """The reserve check of the last steel simulation if it is of ``key``'s
        design (otherwise ``superseded`` and ``gone``: the page asks for
        its steel again), given up (``superseded``) when a steel request
        comes meanwhile (it takes no ticket itself). ``design`` (the
        route's) is not needed: the check is of the simulation kept."""
        cancelled = self._latest.watch()
        with self._lock:
            last = self._last
        if last is None or last[0] != key:
            return {"ok": False, "superseded": True, "gone": True, "error": NOT_LAST}
        state = check_state(last[1], cancelled)
        if state["ok"]:
            with self._lock:
                if self._last is last:
                    self._last = None  # done: a given-up check stays, to be asked again
        return state
