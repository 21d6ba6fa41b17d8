"""Issue 37 item 3: the first build a user runs ends without a warning; the
FOLD file's crease is the design's, so there is nothing to note."""

from __future__ import annotations

import json

import pytest

from tests.cli.test_main import no_traceback, run


@pytest.mark.parametrize(
    "args", [("build", "patkau-one-fold", "-o", "out"), ("build", "-o", "out", "--quiet")]
)
def test_the_first_build_prints_no_warning(tmp_path, args):
    """`onefold build patkau-one-fold -o out` (the README's first build) and
    the default build: exit 0, no `onefold: warning:` line (before: the .fold
    file's crease, 66.86 against the design's 82.82 deg, on every run), no
    note in the report or the FOLD file."""
    proc = run(*args, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    no_traceback(proc)
    assert "warning" not in proc.stderr, proc.stderr
    report = json.loads((tmp_path / "out" / "patkau-one-fold.json").read_text(encoding="utf-8"))
    assert report["warnings"] == []
    fold = json.loads((tmp_path / "out" / "patkau-one-fold.fold").read_text(encoding="utf-8"))
    assert fold["onefold:notes"] == []


def test_paper_squares_file_is_written_without_a_note(tmp_path):
    """`build paper-square --formats fold,json -o out --quiet`: nothing on
    stderr (before: "the .fold file folds a graded fan of 16 divisions ...
    106.35 / 106.35 deg, the design's 107.44 / 107.44 deg"); the file's
    crease is the design's, so neither it nor the report has a note."""
    proc = run("build", "paper-square", "--formats", "fold,json", "-o", "out", "--quiet",
               cwd=tmp_path)  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    report = json.loads((tmp_path / "out" / "paper-square.json").read_text(encoding="utf-8"))
    fold = json.loads((tmp_path / "out" / "paper-square.fold").read_text(encoding="utf-8"))
    assert report["warnings"] == [] and fold["onefold:notes"] == []
    design = [c["fold_angle_deg"] for c in report["crease"].values()]
    assert fold["onefold:crease"][0]["fold_angle_deg"] == pytest.approx(design[0], abs=1e-9)
