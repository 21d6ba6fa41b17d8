"""All-or-nothing file output.

:func:`atomic_output` writes one file: a temporary file in the target's
folder, renamed over the target only when writing succeeded.

:class:`Staging` writes a *set* of files (everything ``onefold build``
produces in one call) so that no reader of the output folder ever sees the
files of one design from two builds:

1. The files are written into a private staging folder inside the output
   folder, ``.onefold-XXXXXXXX.partial/``, whose ``lock`` file the writing
   process holds locked (``flock``) for as long as it lives; the kernel drops
   the lock when the process dies, however it dies.
2. :meth:`Staging.commit` checks every target first (a folder where a file
   must go, two files with one name), then writes the commit's journal
   atomically and durably and carries it out
   (:mod:`onefold_cad.export.commit_steps`): for every :class:`FileSet` (the
   files of one design, of any format) a marker ``NAME.incomplete`` appears,
   the old files go, the new ones are renamed in, the marker goes. So at
   every instant the files of a set are a subset of the old set or of the
   new one, never a mixture, and a set that is not complete has its marker
   beside it. SIGINT, SIGTERM and SIGHUP are held back from the journal to
   the last step (and acted on afterwards), so only SIGKILL or a power cut
   can stop a commit half way.
3. :func:`recover`, run by every build before it writes and by every commit
   (under the folder's lock, before its own steps), finishes the commit of
   any staging folder whose owner is dead (its lock is free) and that has a
   journal (each step is idempotent), and removes the staging folders of
   dead runs without one, one line each to ``say``.

The steps of one commit never interleave with another process's commit: both
hold an ``flock`` on the output folder meanwhile.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import signal
import tempfile
import threading
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

from onefold_cad.errors import ExportError
from onefold_cad.export.commit_steps import (
    INIT,
    LOCK,
    MARKER_SUFFIX,
    PARTIAL,
    PREFIX,
    FileSet,
    apply_journal,
    pause_point,
    recover_locked,
    write_journal,
)

__all__ = [
    "MARKER_SUFFIX",
    "FileSet",
    "Staging",
    "atomic_output",
    "check_targets",
    "pause_point",
    "recover",
]

_HELD = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; replace ``path`` with it on success.

    On any error the temporary file is removed and ``path`` is left as it
    was; an OSError becomes :class:`ExportError` naming the file.
    """
    out = Path(path)
    if not out.parent.is_dir():
        raise ExportError(f"cannot write {out}: directory {out.parent} does not exist")
    try:
        fd, name = tempfile.mkstemp(prefix=f".{out.stem}.", suffix=out.suffix, dir=out.parent)
    except OSError as exc:
        raise ExportError(f"cannot write {out}: {exc.strerror or exc}") from exc
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        os.chmod(tmp, _file_mode())
        os.replace(tmp, out)
    except OSError as exc:
        raise ExportError(f"cannot write {out}: {exc}") from exc
    finally:
        tmp.unlink(missing_ok=True)


def _file_mode() -> int:
    """The mode a new file gets under the current umask (temp files are 0600)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


@contextlib.contextmanager
def _folder_lock(path: Path) -> Iterator[None]:
    """Hold an exclusive ``flock`` on the folder ``path`` (commits and recovery
    into one folder take turns)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT, SIGTERM and SIGHUP back: while the block runs they are only
    recorded; afterwards the previous handlers are restored and the recorded
    signals raised again (so Ctrl-C still stops the program, after the block).

    Python runs signal handlers in the main thread whichever thread the kernel
    picked (numpy's BLAS threads block nothing), so a recording handler, not a
    signal mask, is what holds them back. Outside the main thread: no effect.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending: list[signal.Signals] = []

    def record(signum: int, frame: object) -> None:
        pending.append(signal.Signals(signum))

    old = {s: signal.signal(s, record) for s in _HELD}
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        for s in dict.fromkeys(pending):
            signal.raise_signal(s)


def check_targets(outdir: Path, names: Sequence[str]) -> None:
    """Raise :class:`ExportError` naming the path if a file of ``names`` cannot
    take its place in ``outdir``: a folder (or anything but a file) is in the
    way, or two files share a name."""
    seen: set[str] = set()
    for name in names:
        if name in seen:
            raise ExportError(f"two files of this build are named {str(outdir / name)!r}")
        seen.add(name)
        target = outdir / name
        if target.is_symlink() or not target.exists():
            continue
        if not target.is_file():
            kind = "a folder" if target.is_dir() else "not a regular file"
            raise ExportError(
                f"cannot write {str(target)!r}: {kind} is in the way (remove or rename it)"
            )


class Staging:
    """A private staging folder inside ``outdir`` for one set of files.

    Use as a context manager: files are written under :attr:`path`, then
    :meth:`commit` moves them into ``outdir``. Leaving the block without a
    commit (an error, Ctrl-C, SIGTERM) removes the folder and everything in
    it; the output folder is untouched.

    Args:
        outdir: the output folder (it exists).
        say: called with one line for each leftover of a dead run that a
            commit finds and cleans (:func:`recover`); None: silently.
    """

    def __init__(
        self, outdir: str | os.PathLike[str], say: Callable[[str], None] | None = None
    ) -> None:
        self.outdir = Path(outdir)
        self.committed = False
        #: Files of the sets that the commit removed and nothing replaced.
        self.removed: list[Path] = []
        self._say = say
        self._keep = False
        try:
            init = Path(tempfile.mkdtemp(prefix=PREFIX, suffix=INIT, dir=self.outdir))
        except OSError as exc:
            raise ExportError(
                f"cannot write into {str(self.outdir)!r}: {exc.strerror or exc}"
            ) from exc
        try:
            self._lock = os.open(init / LOCK, os.O_RDWR | os.O_CREAT, 0o600)
            fcntl.flock(self._lock, fcntl.LOCK_EX)
            self.path = init.with_name(init.name.removesuffix(INIT) + PARTIAL)
            os.rename(init, self.path)  # only now may others see it (locked)
        except OSError as exc:
            shutil.rmtree(init, ignore_errors=True)
            raise ExportError(f"cannot write into {str(self.outdir)!r}: {exc}") from exc

    def __enter__(self) -> Staging:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Remove the staging folder (unless a commit left work for recovery)
        and release its lock."""
        if not self._keep:
            shutil.rmtree(self.path, ignore_errors=True)
        if self._lock >= 0:
            os.close(self._lock)
            self._lock = -1

    def commit(
        self,
        files: Sequence[Path],
        targets: Sequence[str] | None = None,
        sets: Sequence[FileSet] = (),
    ) -> list[Path]:
        """Move ``files`` (inside :attr:`path`) into ``outdir`` under their
        own names (or under ``targets``, paths relative to ``outdir`` whose
        folders are made as needed: ``onefold site``'s DIR/NAME/...), all or
        nothing, replacing each of ``sets`` whole (the module's phases);
        return the paths written. :attr:`removed` lists the files of
        ``sets`` removed and not replaced.

        Raises:
            ExportError: a target is blocked (nothing moved), or a step failed
                (the journal stays, and the next build into ``outdir``
                finishes the commit once the obstacle is gone); the message
                names the path.
        """
        names = [Path(f).name for f in files] if targets is None else list(targets)
        moves = [(Path(f), self.outdir / name) for f, name in zip(files, names, strict=True)]
        for src, _ in moves:
            if self.path not in src.parents:
                raise ValueError(f"{src} is not inside the staging folder {self.path}")
        retire = list(dict.fromkeys(p for s in sets for p in s.paths()))
        markers = [s.marker for s in sets]
        mode = _file_mode()
        with _folder_lock(self.outdir), _signals_held():
            recover_locked(self.outdir, self._say)  # a dead run's commit goes first
            check_targets(self.outdir, [*names, *markers])
            try:
                for src, dst in moves:
                    os.chmod(src, mode)
                    dst.parent.mkdir(parents=True, exist_ok=True)
                journal = {
                    "version": 2,
                    "moves": [
                        [str(s.relative_to(self.path)), n]
                        for (s, _), n in zip(moves, names, strict=True)
                    ],
                    "retire": retire,
                    "markers": markers,
                }
                write_journal(self.path, journal)
            except OSError as exc:
                raise ExportError(f"cannot write {exc.filename or self.path}: {exc}") from exc
            self._keep = True  # from here on the journal decides
            done, self.removed = apply_journal(self.path, self.outdir, journal, recovery=False)
            self.committed = True
            self._keep = False
        return done


def recover(outdir: str | os.PathLike[str], say: Callable[[str], None] | None = None) -> list[Path]:
    """Finish or remove the staging folders that dead runs left in ``outdir``.

    A staging folder whose lock is free belongs to a process that has died:
    with a journal, its commit is finished (:func:`apply_journal` again); without
    one, it is removed. Folders of live runs are left alone.

    Args:
        say: called with one line for each folder finished or removed.

    Returns:
        The files moved into place by finished commits.
    """
    out = Path(outdir)
    if not out.is_dir():
        return []
    with _folder_lock(out):
        return recover_locked(out, say)
