"""The sweep's journal: ``DIR/journal.jsonl``, one JSON row per finished design.

Append-only: each row is one line, written with one ``write`` and flushed to
the operating system at once, so a sweep stopped any way (SIGKILL included)
keeps every row it had finished; the tables (results.parquet, data.csv) are
rebuilt from it. A line cut short by a kill (no newline at its end) is
dropped when the journal is opened again. A key written twice counts once,
its last row. While a sweep runs it holds an ``flock`` on the journal, so
two sweeps never write into one folder at once. Standard library only.
"""

from __future__ import annotations

import fcntl
import json
import os
from pathlib import Path
from typing import IO, Any

from onefold_cad.flags.parser import UsageError

__all__ = ["JOURNAL", "Journal", "read_journal"]

#: The journal's file name in the sweep's folder.
JOURNAL = "journal.jsonl"


def read_journal(path: str | os.PathLike[str]) -> dict[str, dict[str, Any]]:
    """The rows of the journal at ``path`` by key (the last row of a key wins;
    a line that does not parse, such as one cut short, is skipped). An absent
    journal has no rows."""
    rows: dict[str, dict[str, Any]] = {}
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        return rows
    for line in text.splitlines():
        try:
            row = json.loads(line)
        except ValueError:
            continue
        if isinstance(row, dict) and isinstance(row.get("key"), str):
            rows[row["key"]] = row
    return rows


class Journal:
    """The journal of a sweep, open for appending (a context manager).

    Opening it takes the folder's lock (a second sweep into the folder is an
    error) and drops a last line cut short.
    """

    def __init__(self, folder: str | os.PathLike[str]) -> None:
        self.path = Path(folder) / JOURNAL
        self._fh: IO[str] | None = None

    def __enter__(self) -> Journal:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fh = open(self.path, "a+", encoding="utf-8")  # noqa: SIM115 (closed in __exit__)
        try:
            fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.close()
            raise UsageError(
                f"{self.path.parent}: another sweep is writing into this folder"
            ) from None
        _drop_partial_line(fh)
        self._fh = fh
        return self

    def __exit__(self, *exc: object) -> None:
        if self._fh is not None:
            self._fh.flush()
            os.fsync(self._fh.fileno())
            self._fh.close()
            self._fh = None

    def append(self, row: dict[str, Any]) -> None:
        """Write ``row`` as one line and flush it (it survives a kill from now on)."""
        assert self._fh is not None, "the journal is not open"
        self._fh.write(json.dumps(row, allow_nan=True, separators=(",", ":")) + "\n")
        self._fh.flush()


def _drop_partial_line(fh: IO[str]) -> None:
    """Cut the file back to its last newline (a row cut short by a kill)."""
    fh.flush()
    fd = fh.fileno()
    size = os.fstat(fd).st_size
    if size == 0:
        return
    with open(fd, "rb", closefd=False) as raw:
        raw.seek(max(0, size - 1))
        if raw.read(1) == b"\n":
            return
        chunk, end = 65536, size
        while end > 0:
            start = max(0, end - chunk)
            raw.seek(start)
            data = raw.read(end - start)
            i = data.rfind(b"\n")
            if i >= 0:
                os.ftruncate(fd, start + i + 1)
                return
            end = start
        os.ftruncate(fd, 0)
