"""The commands' stop messages: a server stopped by a signal says it stopped."""

from __future__ import annotations

import signal
import subprocess

import pytest

from tests.processes import interruptible

from .test_main import ONEFOLD


@pytest.mark.parametrize(
    ("argv", "ready", "what"),
    [
        (["explore", "--no-browser", "--port", "0"], "onefold explore:", "the explorer"),
        (["hops", "--port", "0"], "onefold hops:", "the Hops server"),
    ],
)
def test_sigterm_stops_a_server_saying_it_stopped_not_that_nothing_was_written(argv, ready, what):
    proc = subprocess.Popen(
        [ONEFOLD, *argv],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        preexec_fn=interruptible,
    )
    try:
        assert proc.stderr is not None
        first = proc.stderr.readline().decode()  # it serves once it has said where
        assert first.startswith(ready) and "http://127.0.0.1:" in first, first
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 128 + signal.SIGTERM
    assert err.decode().splitlines() == [
        f"onefold: stopped by SIGTERM; {what} has stopped (it writes no files)"
    ]
