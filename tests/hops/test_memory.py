"""A request the machine cannot afford (an allocation that fails) is answered
with one line saying so, and the server goes on answering."""

from __future__ import annotations

import onefold_cad.design
from onefold_cad.hops.inputs import SOLVE_INPUTS, hops_request
from tests.hops.client import post

SOLVE = {"template": "paper-square", "alpha": 40.0, "beta": 35.0}
#: numpy's message for the flat pattern's old (2n, 2n, 2) array at 10 000 divisions
NUMPY = (
    "Unable to allocate 5.96 GiB for an array with shape (20000, 19998, 2) and data type float64"
)


def test_a_request_without_the_memory_is_an_error_answer_and_the_server_goes_on(
    url, monkeypatch, capfd
):
    real = onefold_cad.design.fold_design

    def no_memory(*args, **kwargs):
        raise MemoryError(NUMPY)

    body = hops_request("onefold/solve", SOLVE_INPUTS, SOLVE)
    monkeypatch.setattr(onefold_cad.design, "fold_design", no_memory)
    status, answer = post(f"{url}/solve", body)
    assert status == 500 and answer["values"] == []
    (text,) = answer["errors"]
    assert text.startswith("out of memory (Unable to allocate 5.96 GiB") and "divisions" in text
    assert "\n" not in text and "internal error" not in text
    log = capfd.readouterr().err
    assert "Traceback" not in log and "out of memory" in log

    monkeypatch.setattr(onefold_cad.design, "fold_design", real)
    status, answer = post(f"{url}/solve", body)
    assert status == 200 and answer["errors"] == [] and answer["values"]
