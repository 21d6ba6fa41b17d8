"""How the explorer's tests, its benchmark and the screenshot scripts start
Debian's Chromium under playwright: one list of flags for all of them."""

from __future__ import annotations

__all__ = ["CHROMIUM", "CHROMIUM_ARGS"]

#: Debian's Chromium (the Makefile's `programs` target installs it).
CHROMIUM = "/usr/bin/chromium"
#: As root: no sandbox; the machine's network is closed: no background
#: connections; software WebGL (SwiftShader through ANGLE).
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
