"""/api/compensate: the Compensate action's background job on the server.

The full run (a real compensation of a 20 mm sheet on the coarse mesh, about
20 s of CPU) is the browser test's (test_compensate_page.py); here: the
refusals before any simulation, the bad queries, a cancel, and the bounds.
"""

from __future__ import annotations

import json
import threading
import time

import pytest

import onefold_cad.explore.compensation as compensation
from onefold_cad.explore.compensation import KEEP_JOBS, KEEP_S, Compensations
from onefold_cad.explore.controls import design_from_params
from tests.explore.conftest import get

#: A design whose coarse simulation is cheap (a thick sheet: few Newton steps).
CHEAP = "thickness=20"


def _answer(server, target: str, headers: dict[str, str] | None = None) -> tuple[int, dict]:
    status, hdrs, body = get(server, target, headers)
    assert hdrs["content-type"] == "application/json"
    return status, json.loads(body)


def _wait(server, job: int, until, limit_s: float = 120.0) -> dict:
    """Poll the job's progress until ``until(progress)`` (bounded)."""
    end = time.monotonic() + limit_s
    while True:
        status, p = _answer(server, f"/api/compensate/progress?job={job}")
        assert status == 200, p
        if until(p) or time.monotonic() > end:
            return p
        time.sleep(0.05)


def _workers() -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name == "onefold-compensate"]


@pytest.fixture
def counted(monkeypatch):
    """Every simulation the job's evaluator starts, counted (they still run)."""
    calls: list[str] = []
    real = compensation.run_one

    def run_one(design, level, check=False, law="j2"):
        assert law == "moment"  # the page's preview law, not simulate's default
        calls.append(level)
        return real(design, level, check, law)

    monkeypatch.setattr(compensation, "run_one", run_one)
    return calls


@pytest.mark.parametrize(
    ("query", "error"),
    [
        ("template=paper-square", "cannot compensate this design: youngs_modulus: simulate needs"),
        ("model=paper", "cannot compensate this design: model: simulate needs the exact model"),
        ("thickness=0", "cannot compensate this design: thickness: simulate needs a sheet"),
        ("alpha=95", "--alpha: must be in (0, 90) deg, got 95"),
    ],
    ids=["no-steel-data", "paper-model", "no-thickness", "bad-value"],
)
def test_a_design_that_cannot_be_compensated_is_refused_before_any_simulation(
    server, counted, query, error
):
    status, data = _answer(server, f"/api/compensate/start?{query}")
    assert status == 422 and data == {"ok": False, "error": data["error"]}
    assert data["error"].startswith(error) and "\n" not in data["error"]
    assert counted == [] and _workers() == []


@pytest.mark.parametrize(
    "target",
    [
        "/api/compensate/start?bogus=1",
        "/api/compensate/start?alpha=1&alpha=2",
        "/api/compensate/progress?job=1&alpha=2",
        "/api/compensate/progress",
        "/api/compensate/progress?job=x1",
        "/api/compensate/cancel?job=-1",
    ],
)
def test_a_bad_query_is_refused_in_one_line(server, counted, target):
    status, _, body = get(server, target)
    assert status == 400 and body.startswith(b"bad request: ") and body.count(b"\n") == 1
    assert counted == []


def test_an_unknown_job_or_action_is_one_line(server):
    status, data = _answer(server, "/api/compensate/progress?job=999")
    assert status == 404 and data["error"].startswith("job: no compensation 999")
    assert get(server, "/api/compensate/restart?job=1")[0] == 404


@pytest.mark.parametrize("route", ["start?thickness=20", "progress?job=1", "cancel?job=1"])
def test_a_foreign_host_is_refused(server, counted, route):
    status, _, body = get(server, f"/api/compensate/{route}", {"Host": "evil.example"})
    assert status == 403 and b"Host" in body
    assert counted == []


def test_cancel_stops_the_job_at_its_next_simulation(server, counted):
    status, started = _answer(server, f"/api/compensate/start?{CHEAP}")
    assert status == 200 and started["state"] == "running" and started["level"] == "coarse"
    job = started["job"]
    # one at a time: a second start is refused while this one runs
    status, second = _answer(server, f"/api/compensate/start?{CHEAP}")
    assert status == 409 and second["error"].startswith(f"compensation {job} is running")
    p = _wait(server, job, lambda p: len(p["lines"]) >= 1)
    assert p["lines"][0].startswith("1 simulations (coarse, best on coarse max deviation")
    status, at_cancel = _answer(server, f"/api/compensate/cancel?job={job}")
    assert status == 200
    begun = len(counted)  # simulations started before the cancel
    done = _wait(server, job, lambda p: p["state"] != "running")
    assert done["state"] == "cancelled" and done["result"] is None
    for _ in range(50):  # the job's thread ends with its run
        if not _workers():
            break
        time.sleep(0.05)
    assert _workers() == []
    # no simulation started after the cancel; the one under way (if any) ended
    assert len(counted) == begun
    assert at_cancel["simulations"] <= done["simulations"] == begun
    time.sleep(0.5)
    assert _answer(server, f"/api/compensate/progress?job={job}")[1]["simulations"] == begun


def test_finished_jobs_are_kept_for_a_bounded_time_and_count(server, monkeypatch):
    """Jobs that fail at once (every simulation refused: the search's own
    error) are finished jobs as cheap as they come."""
    monkeypatch.setattr(compensation, "run_one", lambda design, level, *rest: "refused")
    now = [0.0]
    jobs = Compensations(clock=lambda: now[0])
    design = design_from_params({}, server.templates, server.initial)

    def run() -> int:
        status, p = jobs.start(design, {})
        assert status == 200
        for _ in range(200):
            status, q = jobs.answer("progress", f"job={p['job']}", lambda q: design)
            if q["state"] != "running":
                break
            time.sleep(0.01)
        assert q["state"] == "failed" and q["ok"] is False
        assert q["error"].startswith("cannot compensate this design: target: the fold as given")
        return int(p["job"])

    numbers = [run() for _ in range(KEEP_JOBS + 1)]
    known = [jobs.answer("progress", f"job={n}", lambda q: design)[0] for n in numbers]
    assert known == [404] + [200] * KEEP_JOBS  # the oldest beyond the count is gone
    now[0] += KEEP_S + 1.0
    assert jobs.answer("progress", f"job={numbers[-1]}", lambda q: design)[0] == 404


def test_cones_formed_past_their_springback_are_compensated_with_j2(server, monkeypatch):
    laws: list[str] = []
    real = compensation.run_one

    def run_one(design, level, check=False, law="moment"):
        laws.append(law)
        return real(design, level, check, law)

    monkeypatch.setattr(compensation, "run_one", run_one)
    status, started = _answer(server, f"/api/compensate/start?{CHEAP}&cone_forming=compensated")
    assert status == 200, started
    job = started["job"]
    _wait(server, job, lambda p: p["simulations"] >= 1)
    _answer(server, f"/api/compensate/cancel?job={job}")
    assert _wait(server, job, lambda p: p["state"] != "running")["state"] == "cancelled"
    assert laws and set(laws) == {"j2"}
