"""The journal: one flushed line per row, a line cut short dropped, the last
row of a key counting, one sweep per folder at a time."""

from __future__ import annotations

import pytest

from onefold_cad.flags.parser import UsageError
from onefold_cad.sweep.journal import JOURNAL, Journal, read_journal


def test_rows_are_on_disk_as_soon_as_they_are_appended(tmp_path):
    with Journal(tmp_path) as j:
        j.append({"key": "a", "x": 1.5, "y": float("nan")})
        # flushed: another reader sees it while the journal is still open
        rows = read_journal(tmp_path / JOURNAL)
        assert rows["a"]["x"] == 1.5 and rows["a"]["y"] != rows["a"]["y"]
        j.append({"key": "a", "x": 2.0})
        j.append({"key": "b", "x": 3.0})
    assert {k: r["x"] for k, r in read_journal(tmp_path / JOURNAL).items()} == {"a": 2.0, "b": 3.0}


def test_a_line_cut_short_by_a_kill_is_dropped_on_reopening(tmp_path):
    path = tmp_path / JOURNAL
    path.write_text('{"key": "a", "x": 1}\n{"key": "b", "x"')
    assert list(read_journal(path)) == ["a"]
    with Journal(tmp_path) as j:
        j.append({"key": "c", "x": 3})
    assert path.read_text() == '{"key": "a", "x": 1}\n{"key":"c","x":3}\n'
    path.write_text('{"key": "b"')  # nothing whole at all
    with Journal(tmp_path):
        pass
    assert path.read_text() == ""


def test_two_sweeps_never_write_into_one_folder(tmp_path):
    with Journal(tmp_path):
        with pytest.raises(UsageError, match="another sweep is writing into this folder"):
            with Journal(tmp_path):
                pass
    with Journal(tmp_path):  # free again
        pass


def test_an_absent_journal_has_no_rows(tmp_path):
    assert read_journal(tmp_path / JOURNAL) == {}
