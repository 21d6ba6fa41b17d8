"""Fixtures of the Hops server's tests: one server per module on a free port,
a client that posts what Hops posts, and ``main()`` in this process."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from onefold_cad.hops.inputs import FIT_INPUTS, SOLVE_INPUTS, hops_request
from onefold_cad.hops.server import make_server
from tests.hops.client import post


@pytest.fixture(scope="module")
def url() -> Iterator[str]:
    """The address of a Hops server on a free port of 127.0.0.1."""
    server = make_server("127.0.0.1", 0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()
        thread.join(5)


@pytest.fixture
def solve(url: str) -> Callable[..., tuple[int, Any]]:
    """Post ``onefold/solve`` as Hops does (``/solve``, the component in
    ``pointer``) with the inputs given by name; (status, answer)."""

    def call(model_units: str = "Millimeters", **values: Any) -> tuple[int, Any]:
        body = hops_request("onefold/solve", SOLVE_INPUTS, values, model_units)
        return post(f"{url}/solve", body)

    return call


@pytest.fixture
def fit(url: str) -> Callable[..., tuple[int, Any]]:
    """Post ``onefold/fit`` as Hops does; (status, answer)."""

    def call(**values: Any) -> tuple[int, Any]:
        return post(f"{url}/solve", hops_request("onefold/fit", FIT_INPUTS, values))

    return call
