"""The commands: a server stopped by a signal says it stopped; fit's default
template and progress."""

from __future__ import annotations

import json
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


@pytest.mark.parametrize("quiet", [False, True])
def test_fit_starts_from_the_default_template_and_shows_its_progress(capfd, quiet):
    """`onefold fit --height H --span S` (no template) fits the default
    template, as solve and build default to it, and says each step of its
    search on stderr (-q: nothing), one line each, before the result."""
    from onefold_cad.cli.main import main

    capfd.readouterr()
    assert main(["solve", "--json"]) == 0
    rest = json.loads(capfd.readouterr().out)["resting"]
    height, span = rest["height"], rest["span"]
    argv = ["fit", "--height", f"{height:.6g}", "--span", f"{span:.6g}"]
    assert main(argv + (["-q"] if quiet else [])) == 0
    out, err = capfd.readouterr()
    assert out.startswith("patkau-one-fold: alpha ")
    if quiet:
        assert err == ""
        return
    lines = err.splitlines()
    assert all(line.startswith("[fit] patkau-one-fold: ") for line in lines), lines
    assert "grid (h_c kept)" in lines[0] and "frames stand" in lines[0]
    assert any("refining seed 1/" in line for line in lines)
    assert lines[-1].startswith("[fit] patkau-one-fold: found after ")
