"""An allocation that fails (MemoryError, numpy's among them) anywhere in a
command is one line on stderr, exit 2, no traceback and no file written."""

from __future__ import annotations

import onefold_cad.fabrication.flat_pattern as flat_pattern_module
from onefold_cad.cli.build import _worker

NUMPY = (
    "Unable to allocate 5.96 GiB for an array with shape (20000, 19998, 2) and data type float64"
)


def no_memory(*args, **kwargs):
    raise MemoryError(NUMPY)


def one_error(err: str) -> str:
    lines = [ln for ln in err.splitlines() if not ln.startswith("onefold: warning: ")]
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def test_solve_out_of_memory_is_one_line(cli, monkeypatch):
    monkeypatch.setattr(flat_pattern_module, "ruling_folds", no_memory)
    rc, out, err = cli("solve", "--model", "paper", "--divisions", "40")
    assert rc == 2 and out == ""
    line = one_error(err)
    assert line.startswith("onefold: error: out of memory (Unable to allocate 5.96 GiB")
    assert "divisions" in line


def test_build_out_of_memory_is_one_line_and_writes_nothing(cli, monkeypatch, tmp_path):
    monkeypatch.setattr(flat_pattern_module, "ruling_folds", no_memory)
    out = tmp_path / "out"
    out.mkdir()
    rc, _, err = cli("build", "--model", "paper", "--formats", "dxf,json", "-o", str(out), "-q")
    assert rc == 2
    assert one_error(err).startswith("onefold: error: out of memory (")
    assert list(out.iterdir()) == []


def test_a_worker_out_of_memory_sends_the_line():
    """``build -j N``: numpy's MemoryError cannot be rebuilt from its pickle in
    the parent; the worker sends the line instead."""
    status, (kind, text) = _worker(no_memory, None)
    assert (status, kind) == ("error", "memory")
    assert text.startswith("out of memory (Unable to allocate 5.96 GiB")
