"""``onefold sweep`` refuses bad input with one line naming it, exit status
2, no traceback and no output folder, before any design runs."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

from onefold_cad.cli.main import main

ONEFOLD = str(Path(sys.executable).parent / "onefold")


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--vary", "colour=1,2"], "--vary colour=1,2: 'colour' is not a design flag (one of:"),
        (["--vary", "alpha=80:10:5"], "--vary alpha=80:10:5: empty range"),
        (
            ["--vary", "alpha=10:95:5"],
            "--vary alpha=10:95:5: --alpha: must be in (0, 90) deg, got 95",
        ),
        (["--vary", "hc=-90,0"], "--hc: H must lie strictly inside the f-line"),
        (["--vary", "alpha=oops"], "--vary alpha=oops: alpha 'oops' is not a number"),
        ([], "--vary: at least one NAME=SPEC is needed"),
        (["--vary", "alpha=30,40", "--objectives", "max:volume"], "no number column 'volume'"),
        (["--vary", "alpha=30,40", "--objectives", "min:mass"], "it needs --measure mass"),
        (["--vary", "alpha=30,40", "--measure", "bends,volume"], "'volume' is not a measure"),
        (["--vary", "alpha=30:40", "--sampler", "halton"], "--sampler: must be one of grid, lhs"),
        (["--vary", "alpha=30,40", "-j", "0"], "--jobs: must be at least 1"),
        (["--vary", "alpha=30,40", "--alpha", "20"], "--alpha is also given as a fixed flag"),
        (["--vary", "alpha=30,40", "--mesh", "coarse"], "--mesh: is a setting of --measure simu"),
        (["--vary", "alpha=30,40", "--no-check"], "--check/--no-check: is a setting of --measure"),
        (["--vary", "alpha=30,40", "--mesh", "medium", "--measure", "simulate"], "--mesh: "),
        (
            ["--vary", "alpha=30,40", "--measure", "simulate"],
            "--measure simulate: model: simulate needs the exact model",
        ),
        (
            ["--vary", "alpha=30,40", "--measure", "simulate", "--model", "exact"],
            "--measure simulate: thickness: simulate needs a sheet with thickness > 0",
        ),
    ],
)
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, capfd, args, says):
    out = tmp_path / "sweep"
    rc = main(["sweep", "table1-row1", "-o", str(out), *args])
    _, err = capfd.readouterr()
    assert rc == 2 and err.startswith("onefold: error: ") and says in err, err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert not out.exists()


def test_without_dask_the_scheduler_says_what_to_install(tmp_path, capfd, monkeypatch):
    real = importlib.util.find_spec

    def find_spec(name, *args):
        return None if name == "distributed" else real(name, *args)

    monkeypatch.setattr(importlib.util, "find_spec", find_spec)
    for scheduler in (["--scheduler", "tcp://10.0.0.1:8786"], []):
        if not scheduler:
            monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "tcp://10.0.0.1:8786")
        rc = main(
            ["sweep", "table1-row1", "--vary", "alpha=30,40", "-o", str(tmp_path / "s"), *scheduler]
        )
        _, err = capfd.readouterr()
        assert rc == 2 and err.count("\n") == 1
        assert "pip install 'onefold_cad[cluster]'" in err
    assert not (tmp_path / "s").exists()


@pytest.mark.parametrize(
    ("address", "says"),
    [
        ("nan", "--scheduler nan: not a scheduler's address (missing port number"),
        ("foo://x:1", "--scheduler foo://x:1: not a scheduler's address (unknown address scheme"),
        ("", "--scheduler: empty; give PROTOCOL://HOST:PORT"),
    ],
)
def test_an_address_dask_cannot_read_is_one_line(tmp_path, capfd, address, says):
    out = tmp_path / "s"
    rc = main(["sweep", "table1-row1", "--vary", "alpha=30,40", "-o", str(out),
               "--scheduler", address])  # fmt: skip
    _, err = capfd.readouterr()
    assert rc == 2 and err == f"onefold: error: {err[16:]}" and says in err, err
    assert err.count("\n") == 1 and not out.exists()


def test_the_installed_command_exits_2_with_one_line(tmp_path):
    proc = subprocess.run(
        [ONEFOLD, "sweep", "--vary", "beta=0:45:4", "-o", str(tmp_path / "s")],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr == (
        "onefold: error: --vary beta=0:45:4: --beta: must be in (0, 90) deg, got 0\n"
    )
    assert not (tmp_path / "s").exists()
