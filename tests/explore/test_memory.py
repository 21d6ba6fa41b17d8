"""A request the machine cannot afford (an allocation that fails) is answered
503 with one line saying so, and the explorer goes on answering."""

from __future__ import annotations

import json

import pytest

import onefold_cad.explore.server as explore_server
from tests.explore.conftest import get

NUMPY = (
    "Unable to allocate 5.96 GiB for an array with shape (20000, 19998, 2) and data type float64"
)


def no_memory(*args, **kwargs):
    raise MemoryError(NUMPY)


def message(path: str, body: bytes) -> str:
    if path.startswith("/download/"):
        return body.decode("utf-8")
    data = json.loads(body)
    return data["error"] if "error" in data else data["messages"][0]["text"]


@pytest.mark.parametrize(
    ("path", "function"),
    [
        ("/api/state?alpha=33", "design_state"),
        ("/api/simulate?alpha=33", "simulation_state"),
        ("/download/json?alpha=33", "make_download"),
    ],
)
def test_a_request_without_the_memory_is_answered_and_the_server_goes_on(
    server, monkeypatch, capfd, path, function
):
    monkeypatch.setattr(explore_server, function, no_memory)
    status, _, body = get(server, path)
    text = message(path, body)
    assert status == 503, (status, text)
    assert text.startswith("out of memory (Unable to allocate 5.96 GiB") and "divisions" in text
    assert "\n" not in text
    log = capfd.readouterr().err
    assert "Traceback" not in log and "out of memory" in log

    monkeypatch.undo()
    status, _, body = get(server, "/api/state?alpha=33")
    assert status == 200 and json.loads(body)["ok"]
