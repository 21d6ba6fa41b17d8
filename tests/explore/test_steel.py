"""The steel view's server side: /api/steel simulates only the latest design,
the form first and its verdict on /api/steel/check, and the designs the page
asks for are kept by their query."""

from __future__ import annotations

import json
import threading
from urllib.parse import urlencode

import pytest

import onefold_cad.design as design_module
import onefold_cad.mechanics.reserve as mechanics_reserve
import onefold_cad.mechanics.simulate as mechanics_simulate
from onefold_cad.design import fold_design
from onefold_cad.explore.controls import design_from_params
from onefold_cad.explore.server import RECENT_DESIGNS
from onefold_cad.explore.simulation import SUPERSEDED
from onefold_cad.explore.steel import NOT_LAST, LatestOnly
from tests.counting import count_calls
from tests.explore.conftest import get


def _ask(server, route: str, params: dict[str, str]) -> tuple[int, dict]:
    status, headers, body = get(server, f"/api/{route}?{urlencode(params)}")
    assert headers["content-type"] == "application/json"
    return status, json.loads(body)


class Watched:
    """``simulate`` of the mechanics, recording each call's alpha (deg) and
    setting ``started`` when one begins (the next request then finds it running)."""

    def __init__(self, monkeypatch) -> None:
        self.real = mechanics_simulate.simulate
        self.alphas: list[float] = []
        self.started = threading.Event()
        monkeypatch.setattr(mechanics_simulate, "simulate", self)

    def __call__(self, design, folded, **kwargs):
        self.alphas.append(round(design.frame.alpha, 6))
        self.started.set()
        return self.real(design, folded, **kwargs)


def _in_thread(fn, *args) -> tuple[threading.Thread, list]:
    out: list = []
    thread = threading.Thread(target=lambda: out.append(fn(*args)), daemon=True)
    thread.start()
    return thread, out


def test_a_ticket_is_stale_once_a_newer_one_is_issued():
    latest = LatestOnly()
    first = latest.ticket()
    assert first() is False
    second = latest.ticket()
    assert first() is True and second() is False


def test_a_running_steel_simulation_is_given_up_for_a_newer_design(server, monkeypatch):
    """alpha 31 runs; alpha 32 is asked meanwhile: 31 answers 'superseded' (it
    stops at its next Newton step), 32 is simulated and answered."""
    watched = Watched(monkeypatch)
    first, out = _in_thread(_ask, server, "steel", {"alpha": "31"})
    assert watched.started.wait(60)
    status, second = _ask(server, "steel", {"alpha": "32"})
    first.join(60)
    assert out[0] == (200, {"ok": False, "superseded": True, "error": SUPERSEDED})
    assert status == 200 and second["ok"] is True
    assert watched.alphas == [31.0, 32.0]


def test_only_the_latest_waiting_steel_request_runs_and_simulate_is_never_given_up(
    server, monkeypatch
):
    """The Simulate button's alpha 33 runs; steel requests for 34 and then 35
    come meanwhile: 33 is answered in full, 34 never starts, 35 is simulated,
    and its numbers are those of simulate() called here for that design."""
    watched = Watched(monkeypatch)
    button, button_out = _in_thread(_ask, server, "simulate", {"alpha": "33"})
    assert watched.started.wait(60)
    issued = threading.Event()
    ticket = server.steel.ticket

    def watched_ticket():
        out = ticket()
        issued.set()
        return out

    monkeypatch.setattr(server.steel, "ticket", watched_ticket)
    stale, stale_out = _in_thread(_ask, server, "steel", {"alpha": "34"})
    assert issued.wait(60)  # 34 is asked (and waits for 33's run) before 35
    status, latest = _ask(server, "steel", {"alpha": "35"})
    button.join(60)
    stale.join(60)
    assert button_out[0][0] == 200 and button_out[0][1]["ok"] is True
    assert stale_out[0][1] == {"ok": False, "superseded": True, "error": SUPERSEDED}
    assert status == 200 and latest["ok"] is True
    assert watched.alphas == [33.0, 35.0]  # 34 was never simulated

    design = design_from_params({"alpha": "35"}, server.templates, server.initial)
    sim = watched.real(design, fold_design(design), level="coarse", convergence=False)
    n = latest["numbers"]
    assert n["max_deviation"] == pytest.approx(sim.standing.max_deviation, rel=1e-9)
    assert n["height"] == pytest.approx(sim.standing.height, rel=1e-9)
    assert n["nodes"] == sim.nodes
    assert latest["queued_ms"] <= latest["server_ms"]
    assert 0 < latest["cpu_ms"]


def test_the_design_a_state_request_built_is_reused_and_the_memory_bounded(server, monkeypatch):
    """/api/state then /api/steel of one design fold it once (the steel request
    is given up before it simulates: a newer ticket is taken first); at most
    RECENT_DESIGNS designs are kept; a bad value is never kept."""
    folds = count_calls(monkeypatch, design_module, "fold")
    server.design_of.cache_clear()
    assert _ask(server, "state", {"alpha": "36.5"})[1]["ok"] is True
    assert len(folds) == 1
    ticket = server.steel.ticket
    monkeypatch.setattr(server.steel, "ticket", lambda: (ticket(), ticket())[0])
    assert _ask(server, "steel", {"alpha": "36.5"})[1]["superseded"] is True
    assert len(folds) == 1  # the same design object: its fold was kept
    monkeypatch.undo()

    for k in range(RECENT_DESIGNS + 3):
        assert _ask(server, "state", {"alpha": str(40 + k)})[1]["ok"] is True
    assert server.design_of.cache_info().currsize == RECENT_DESIGNS
    for _ in range(2):
        _, bad = _ask(server, "state", {"alpha": "95"})
        assert (
            bad["ok"] is False and "--alpha: must be in (0, 90) deg" in bad["messages"][0]["text"]
        )
    assert server.design_of.cache_info().currsize == RECENT_DESIGNS


def test_steel_is_refused_like_every_route(server):
    assert get(server, "/api/steel", {"Host": "evil.example"})[0] == 403
    assert get(server, "/api/steel", method="POST")[0] == 405
    assert get(server, "/api/steel?nonsense=1")[0] == 400
    status, data = _ask(server, "steel", {"model": "paper"})
    assert status == 200 and data["ok"] is False
    assert data["error"].startswith("cannot simulate this design: model: simulate needs the exact")


def test_the_form_comes_first_and_its_check_gives_the_verdict_of_simulate(server):
    """/api/steel answers the standing form with ``checking: true`` (never a
    plain "stands" yet); /api/steel/check of that design then answers the
    verdict and warnings simulate() gives with the check in line; a check of
    another design than the last steel one is refused as superseded."""
    status, form = _ask(server, "steel", {"alpha": "34"})
    assert status == 200 and form["ok"] is True
    assert form["numbers"]["checking"] is True and form["numbers"]["uncertain"]
    assert set(form["stages_ms"]) == {"mesh", "formed", "released", "standing"}
    assert _ask(server, "steel/check", {"alpha": "33"})[1] == {
        "ok": False,
        "superseded": True,
        "gone": True,
        "error": NOT_LAST,
    }
    status, check = _ask(server, "steel/check", {"alpha": "34"})
    assert status == 200 and check["ok"] is True
    design = design_from_params({"alpha": "34"}, server.templates, server.initial)
    sim = mechanics_simulate.simulate(
        design, fold_design(design), level="coarse", convergence=False
    )
    n = check["numbers"]
    assert n["checking"] is False
    assert (n["stands"], n["uncertain"]) == (sim.standing.stands, sim.standing.uncertain)
    assert check["warnings"] == [" ".join(w.split()) for w in sim.warnings]
    assert n["max_deviation"] == form["numbers"]["max_deviation"] == sim.standing.max_deviation
    assert "reserve" in check["stages_ms"] and check["cpu_ms"] > 0
    # done: the server keeps no check of it any more
    assert _ask(server, "steel/check", {"alpha": "34"})[1]["error"] == NOT_LAST


def test_a_running_check_is_given_up_for_a_newer_steel_request(server, monkeypatch):
    """alpha 31's check runs; a steel request for 32 comes: the check answers
    superseded at its next Newton step, 32 is simulated (the check took no
    ticket: it made no steel request stale)."""
    assert _ask(server, "steel", {"alpha": "31"})[1]["numbers"]["checking"] is True
    started, issued = threading.Event(), threading.Event()
    real, ticket = mechanics_reserve.ReserveCheck.carried, server.steel.ticket

    def watched(*args, **kwargs):  # the check starts once 32's ticket is issued
        started.set()
        assert issued.wait(60)
        return real(*args, **kwargs)

    def watched_ticket():
        out = ticket()
        issued.set()
        return out

    monkeypatch.setattr(mechanics_reserve.ReserveCheck, "carried", watched)
    monkeypatch.setattr(server.steel, "ticket", watched_ticket)
    checking, out = _in_thread(_ask, server, "steel/check", {"alpha": "31"})
    assert started.wait(60)
    status, second = _ask(server, "steel", {"alpha": "32"})
    checking.join(60)
    assert out[0] == (200, {"ok": False, "superseded": True, "error": SUPERSEDED})
    assert status == 200 and second["ok"] is True and second["numbers"]["checking"] is True


def test_cones_formed_past_their_springback_are_steel_by_j2(server):
    """The moment law cannot form such cones (``simulate --law moment``
    refuses them): the Steel view simulates them with J2, as Simulate does,
    and gives simulate's own numbers."""
    params = {"cone_forming": "compensated"}
    status, form = _ask(server, "steel", params)
    assert status == 200 and form["ok"] is True, form
    assert form["numbers"]["law"] == "j2"
    design = design_from_params(params, server.templates, server.initial)
    sim = mechanics_simulate.simulate(
        design, fold_design(design), level="coarse", convergence=False, law="j2"
    )
    assert form["numbers"]["max_deviation"] == sim.standing.max_deviation
    # formed to the design, the view stays with the moment law
    assert _ask(server, "steel", {"cone_forming": "design"})[1]["numbers"]["law"] == "moment"
