"""The steps of a commit of staged files (:class:`onefold_cad.export.atomic.Staging`).

A commit's journal (:func:`write_journal`) lists what to remove and what to
move; :func:`apply_journal` carries it out in four phases for every
:class:`FileSet` (the files of one design, of any format): *mark* (the marker
``NAME.incomplete`` appears), *retire* (every file of the set that an earlier
build left is removed), *install* (the new files are renamed into place),
*unmark* (the markers go). Every step is idempotent, so
:func:`recover_locked` finishes the commit of a run that died anywhere in it
by carrying out its journal again, and removes the staging folders of dead
runs that had not begun one. :func:`pause_point` is where the tests stop or
kill a command.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import shutil
import signal
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from onefold_cad.errors import ExportError

__all__ = [
    "INIT",
    "INIT_GRACE_S",
    "JOURNAL",
    "LOCK",
    "MARKER_SUFFIX",
    "PARTIAL",
    "PREFIX",
    "FileSet",
    "apply_journal",
    "fsync_dir",
    "pause_point",
    "recover_locked",
    "write_journal",
]

#: A staging folder is ``PREFIX + random + PARTIAL`` (``INIT`` while it is made).
PREFIX = ".onefold-"
PARTIAL = ".partial"
INIT = ".init"
JOURNAL = "commit.json"
LOCK = "lock"
#: What a set's marker adds to its name (``NAME.incomplete``).
MARKER_SUFFIX = ".incomplete"
#: A staging folder still being set up (``.init``) older than this (s) is a leftover.
INIT_GRACE_S = 600.0


def fsync_dir(path: Path) -> None:
    """Make the folder ``path``'s entries durable (its renames and removals)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def pause_point(point: str) -> None:
    """Fault-injection point for the tests. ``ONEFOLD_TEST_PAUSE`` naming
    ``point``: say so on stderr and wait for a line on stdin (the test sends a
    signal meanwhile); ``*``: name every point passed on stderr, waiting for
    none. ``ONEFOLD_TEST_KILL`` naming ``point``: the process sends itself
    SIGKILL there. Does nothing otherwise."""
    pause = os.environ.get("ONEFOLD_TEST_PAUSE")
    if pause == "*":
        os.write(2, f"onefold-test: point {point}\n".encode())
    elif pause == point:
        os.write(2, f"onefold-test: paused at {point}\n".encode())
        sys.stdin.buffer.readline()
    if os.environ.get("ONEFOLD_TEST_KILL") == point:
        os.kill(os.getpid(), signal.SIGKILL)


@dataclass(frozen=True)
class FileSet:
    """The files one design (or one site) may have in the output folder: a
    commit retires every one of them an earlier build left, and its marker
    stands beside them while they are replaced.

    Attributes:
        stem: the design's (or the site's) name; the marker is ``STEM.incomplete``.
        names: every file name the set can hold, of any format.
        folder: the set's folder inside the output folder (``""``: the folder itself).
    """

    stem: str
    names: tuple[str, ...]
    folder: str = ""

    def _inside(self, name: str) -> str:
        return f"{self.folder}/{name}" if self.folder else name

    @property
    def marker(self) -> str:
        """The marker's path relative to the output folder."""
        return self._inside(self.stem + MARKER_SUFFIX)

    def paths(self) -> list[str]:
        """The set's file names relative to the output folder."""
        return [self._inside(n) for n in self.names]


def write_journal(stage: Path, journal: dict[str, object]) -> None:
    """Write ``stage/commit.json`` atomically and durably."""
    tmp = stage / (JOURNAL + ".tmp")
    with open(tmp, "w", encoding="utf-8") as fh:
        json.dump(journal, fh)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, stage / JOURNAL)
    fsync_dir(stage)


def _marker_text(outdir: Path, stage: Path) -> str:
    return (
        "onefold is replacing the files of this name: while this file is here they are "
        f"incomplete. If no onefold runs (pid {os.getpid()} wrote this), the next "
        f"onefold build, site or simulate into {str(outdir)!r} completes them from "
        f"{stage.name}.\n"
    )


def apply_journal(
    stage: Path, outdir: Path, journal: dict[str, Any], recovery: bool
) -> tuple[list[Path], list[Path]]:
    """Carry out the journalled commit of ``stage`` in ``outdir``: mark, retire,
    install, unmark (the module's phases). Every step is idempotent, so a
    commit that stopped anywhere is finished by running this again; a step
    already done is skipped (a staged file no longer staged has been moved;
    then the file at its target is the new one and is not retired).

    Args:
        recovery: finishing a dead run's commit (a staged file that is gone
            was moved before the run died); else a commit (whose steps pass
            the tests' pause points).

    Returns:
        The files moved into place, and the files of the sets removed and
        not replaced.

    Raises:
        ExportError: a step failed; the message names the file.
    """
    point = _ignore if recovery else pause_point
    moves = [(stage / src, outdir / dst) for src, dst in journal["moves"]]
    incoming = {dst: src for src, dst in moves}
    folders = {outdir, *(dst.parent for _, dst in moves)}
    markers = [outdir / m for m in journal.get("markers", [])]
    markers = [m for m in markers if m.parent.is_dir()]  # no folder: no file of the set there
    try:
        for k, marker in enumerate(markers, 1):
            marker.write_text(_marker_text(outdir, stage), encoding="utf-8")
            point(f"mark:{k}")
        for folder in {m.parent for m in markers}:
            fsync_dir(folder)
        removed = []
        for name in journal.get("retire", []):
            path = outdir / name
            if not (path.is_file() or path.is_symlink()):
                continue  # not there, or not a file of ours (a folder)
            if path in incoming and not incoming[path].exists():
                continue  # moved in already: the new file
            path.unlink()
            removed.append(path)
            point(f"retire:{len(removed)}")
    except OSError as exc:
        raise ExportError(
            f"cannot replace the files in {str(outdir)!r}: {exc.filename or ''}: "
            f"{exc.strerror or exc}; the new files wait in {stage.name} and the next build "
            "into this folder moves them once the obstacle is gone"
        ) from exc
    done = []
    for k, (src, dst) in enumerate(moves, 1):
        if recovery and not src.exists():
            continue  # moved before the run died
        try:
            os.replace(src, dst)
        except OSError as exc:
            raise ExportError(
                f"cannot move {dst.name!r} into {str(outdir)!r}: "
                f"{exc.strerror or exc}; {k - 1} of {len(moves)} files are in place, the "
                f"rest wait in {stage.name} and the next build into this folder "
                "moves them once the obstacle is gone"
            ) from exc
        done.append(dst)
        point(f"commit:{k}")
    for folder in folders:
        fsync_dir(folder)
    for k, marker in enumerate(markers, 1):
        marker.unlink(missing_ok=True)
        point(f"unmark:{k}")
    for folder in {m.parent for m in markers}:
        fsync_dir(folder)
    replaced = set(incoming)
    return done, [p for p in removed if p not in replaced]


def _ignore(text: str) -> None:
    """A pause point or a line to say that nobody wants."""


def _size_text(path: Path) -> str:
    total = 0
    for root, _, files in os.walk(path):
        for f in files:
            with contextlib.suppress(OSError):
                total += os.lstat(os.path.join(root, f)).st_size
    if total < 1000:
        return f"{total} bytes"
    return f"{total / 1e6:.1f} MB" if total >= 100_000 else f"{total / 1e3:.1f} kB"


def recover_locked(out: Path, say: Callable[[str], None] | None) -> list[Path]:
    """:func:`recover`'s work, the folder's lock already held."""
    moved: list[Path] = []
    tell = say if say is not None else _ignore
    for stage in sorted(out.glob(f"{PREFIX}*{PARTIAL}")):
        try:
            fd = os.open(stage / LOCK, os.O_RDWR)
        except FileNotFoundError:
            size = _size_text(stage)
            shutil.rmtree(stage, ignore_errors=True)  # no lock: never a live run's
            tell(f"removed {str(stage)!r} ({size}), a staging folder without a lock")
            continue
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                continue  # a live run
            if (stage / JOURNAL).exists():
                journal = json.loads((stage / JOURNAL).read_text(encoding="utf-8"))
                try:
                    done, _ = apply_journal(stage, out, journal, recovery=True)
                except ExportError as exc:
                    raise ExportError(f"cannot finish an earlier build's commit: {exc}") from exc
                moved += done
                shutil.rmtree(stage, ignore_errors=True)
                n = len(journal["moves"])
                tell(
                    f"finished an interrupted earlier build into {str(out)!r}: {len(done)} of "
                    f"its {n} files moved in now, its staging folder {stage.name} removed"
                )
            else:
                size = _size_text(stage)
                shutil.rmtree(stage, ignore_errors=True)
                tell(
                    f"removed {str(stage)!r} ({size}), the staging folder of an earlier run "
                    "that stopped before its commit"
                )
        finally:
            os.close(fd)
    now = time.time()
    for init in out.glob(f"{PREFIX}*{INIT}"):
        with contextlib.suppress(OSError):
            if now - init.stat().st_mtime > INIT_GRACE_S:
                shutil.rmtree(init, ignore_errors=True)
                tell(f"removed {str(init)!r}, a staging folder of a run that died creating it")
    return moved
