"""Fixtures of the explorer's tests: one server per module, and Chromium for the page."""

from __future__ import annotations

import http.client
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from onefold_cad.explore.server import ExploreServer, make_server

CHROMIUM = Path("/usr/bin/chromium")
#: How the explorer's tests start Debian's Chromium (as root: no sandbox; the
#: machine's network is closed: no background connections; software WebGL).
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
]


@pytest.fixture(scope="module")
def server() -> Iterator[ExploreServer]:
    """The explorer of the default template on a free port of 127.0.0.1."""
    srv = make_server(None, port=0)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    try:
        yield srv
    finally:
        srv.shutdown()
        srv.server_close()
        thread.join(timeout=10)


def get(
    srv: ExploreServer, target: str, headers: dict[str, str] | None = None, method: str = "GET"
) -> tuple[int, dict[str, str], bytes]:
    """One request to ``srv`` (Host: 127.0.0.1:port unless ``headers`` give one)."""
    conn = http.client.HTTPConnection("127.0.0.1", srv.port, timeout=60)
    try:
        hdrs = {"Host": f"127.0.0.1:{srv.port}", **(headers or {})}
        conn.putrequest(method, target, skip_host=True, skip_accept_encoding=True)
        for k, v in hdrs.items():
            conn.putheader(k, v)
        conn.endheaders()
        res = conn.getresponse()
        return res.status, {k.lower(): v for k, v in res.getheaders()}, res.read()
    finally:
        conn.close()


@pytest.fixture(scope="module")
def browser(server: ExploreServer) -> Iterator[object]:
    """Debian's Chromium driven by playwright (never skipped: `make test` installs it)."""
    from playwright.sync_api import sync_playwright

    assert CHROMIUM.is_file(), (
        "the browser tests need Debian's Chromium: run `make test` as root, "
        "or `sudo apt-get install -y chromium`"
    )
    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        try:
            yield b
        finally:
            b.close()
