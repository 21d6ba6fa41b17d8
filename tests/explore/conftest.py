"""Fixtures of the explorer's tests: one server per module, and Chromium for the page."""

from __future__ import annotations

import http.client
import io
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from onefold_cad.explore.server import ExploreServer, make_server

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from chromium import CHROMIUM, CHROMIUM_ARGS  # noqa: E402


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

    assert Path(CHROMIUM).is_file(), (
        "the browser tests need Debian's Chromium: run `make test` as root, "
        "or `sudo apt-get install -y chromium`"
    )
    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        try:
            yield b
        finally:
            b.close()


TIMEOUT_MS = 60_000


class Page:
    """A fresh tab on the explorer with the console's errors and the page's exceptions."""

    def __init__(self, page, url: str) -> None:
        self.page = page
        self.errors: list[str] = []
        self.foreign: list[str] = []  # requests to anywhere but the server: none (offline)
        origin = url.rstrip("/")

        def only_ours(route) -> None:
            if route.request.url.startswith(origin + "/") or route.request.url.startswith("blob:"):
                route.continue_()
            else:
                self.foreign.append(route.request.url)
                route.abort()

        page.route("**/*", only_ours)
        page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: self.errors.append(f"page error: {e}"))
        page.set_default_timeout(TIMEOUT_MS)
        page.goto(url)
        self.wait_for_update(1)

    def updates(self) -> int:
        return int(self.page.locator("body").get_attribute("data-updates") or 0)

    def wait_for_update(self, n: int) -> None:
        self.page.locator(f"body[data-updates='{n}']").wait_for(state="attached")

    def change(self, selector: str, value: str) -> None:
        """Set a control as a user would and wait until the page has drawn the answer."""
        n = self.updates()
        self.page.locator(selector).fill(value)
        self.wait_for_update(n + 1)

    def canvas(self) -> np.ndarray:
        png = self.page.locator("#view").screenshot()
        return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)

    def text(self, selector: str) -> str:
        return self.page.locator(selector).inner_text()


@contextmanager
def open_page(
    browser, server: ExploreServer, height: int = 860, **options: object
) -> Iterator[Page]:
    """A fresh tab on ``server`` in a browser context of its own (1400 px wide,
    ``height`` high; ``options`` to ``new_context``), closed after."""
    context = browser.new_context(viewport={"width": 1400, "height": height}, **options)
    try:
        yield Page(context.new_page(), server.url)
    finally:
        context.close()
