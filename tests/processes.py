"""Helpers for tests that run the command in a child process."""

from __future__ import annotations

import signal


def interruptible() -> None:
    """``preexec_fn`` for a child that a test stops with SIGINT: the default
    disposition, as a terminal's Ctrl+C finds it. A test run started in the
    background (``pytest ... &``) inherits SIGINT ignored, and Python keeps an
    ignored SIGINT ignored: the child would never see the test's Ctrl+C."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
