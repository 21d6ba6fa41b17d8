"""The README's sweep runs as written (its output folder aside), thumbnails
and all (``benchmarks/bench_readme_sweep.py`` times it against the code
before its thumbnails were reworked)."""

from __future__ import annotations

import csv
import json
import re
import shlex
import struct

from tests.cli.test_main import REPO, no_traceback, run


def test_the_readmes_sweep_runs_as_written_with_its_thumbnails(tmp_path):
    text = (REPO / "README.md").read_text(encoding="utf-8")
    (line,) = [ln for ln in text.splitlines() if re.match(r"onefold sweep .*--vary", ln)]
    args = shlex.split(line, comments=True)[1:]
    out = tmp_path / "sweep"
    args[args.index("-o") + 1] = str(out)
    proc = run(*args)
    no_traceback(proc)
    assert proc.returncode == 0, proc.stderr
    rows = [json.loads(r) for r in (out / "journal.jsonl").read_text().splitlines()]
    assert len(rows) == 45 and {r["status"] for r in rows} == {"ok"}
    with (out / "data.csv").open(newline="") as f:
        images = [r["img"] for r in csv.DictReader(f)]
    assert sorted(images) == sorted(f"img/{r['key']}.png" for r in rows)
    for name in images:
        data = (out / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n"
        assert struct.unpack(">II", data[16:24]) == (240, 180)
