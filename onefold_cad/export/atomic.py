"""All-or-nothing file output.

:func:`atomic_output` writes one file: a temporary file in the target's
folder, renamed over the target only when writing succeeded.

:class:`Staging` writes a *set* of files (everything ``onefold build``
produces in one call) so that no signal leaves part of a set in the output
folder:

1. The files are written into a private staging folder inside the output
   folder, ``.onefold-XXXXXXXX.partial/``, whose ``lock`` file the writing
   process holds locked (``flock``) for as long as it lives; the kernel drops
   the lock when the process dies, however it dies.
2. :meth:`Staging.commit` checks every target first (a folder where a file
   must go, two files with one name), then writes the commit journal
   ``commit.json`` (the list of renames) atomically and durably (temporary
   file, fsync, rename, fsync of the folder), then renames the files into
   place. SIGINT, SIGTERM and SIGHUP are held back from the journal to the
   last rename (and acted on afterwards), so only SIGKILL or a power cut can
   stop a commit half way.
3. :func:`recover`, run by every build before it writes, finishes the
   commit of any staging folder whose owner is dead (its lock is free) and
   has a journal (the renames are idempotent: a file already moved is
   skipped), and removes staging folders of dead runs without one.

So the output folder holds the old set, or the new set, or (only after a
SIGKILL between the journal and the last rename) a mixture together with a
journal that the next build into that folder completes before doing
anything else. The renames of one commit never interleave with another
process's commit: both hold an ``flock`` on the output folder meanwhile.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

from onefold_cad.errors import ExportError

__all__ = ["Staging", "atomic_output", "check_targets", "pause_point", "recover"]

_PREFIX = ".onefold-"
_PARTIAL = ".partial"
_INIT = ".init"
_JOURNAL = "commit.json"
_LOCK = "lock"
#: A staging folder still being set up (``.init``) older than this (s) is a leftover.
_INIT_GRACE_S = 600.0
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


def _fsync_dir(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


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
    pending: list[int] = []

    def record(signum: int, frame: object) -> None:
        pending.append(signum)

    old = {s: signal.signal(s, record) for s in _HELD}
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        for s in dict.fromkeys(pending):
            signal.raise_signal(s)


def pause_point(point: str) -> None:
    """Fault-injection point for the tests: when ``ONEFOLD_TEST_PAUSE`` names
    ``point``, say so on stderr and wait for a line on stdin (the test sends
    a signal meanwhile). Does nothing otherwise."""
    if os.environ.get("ONEFOLD_TEST_PAUSE") != point:
        return
    os.write(2, f"onefold-test: paused at {point}\n".encode())
    sys.stdin.buffer.readline()


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
    """

    def __init__(self, outdir: str | os.PathLike[str]) -> None:
        self.outdir = Path(outdir)
        self.committed = False
        self._keep = False
        try:
            init = Path(tempfile.mkdtemp(prefix=_PREFIX, suffix=_INIT, dir=self.outdir))
        except OSError as exc:
            raise ExportError(
                f"cannot write into {str(self.outdir)!r}: {exc.strerror or exc}"
            ) from exc
        try:
            self._lock = os.open(init / _LOCK, os.O_RDWR | os.O_CREAT, 0o600)
            fcntl.flock(self._lock, fcntl.LOCK_EX)
            self.path = init.with_name(init.name.removesuffix(_INIT) + _PARTIAL)
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
        on_move: Callable[[Path], None] | None = None,
        targets: Sequence[str] | None = None,
    ) -> list[Path]:
        """Move ``files`` (inside :attr:`path`) into ``outdir`` under their
        own names (or under ``targets``, paths relative to ``outdir`` whose
        folders are made as needed: ``onefold site``'s DIR/NAME/...), all or
        nothing; return the paths written.

        Raises:
            ExportError: a target is blocked (nothing moved), or a rename
                failed (the journal stays, and the next build into
                ``outdir`` finishes the commit once the obstacle is gone);
                the message names the path.
        """
        names = [Path(f).name for f in files] if targets is None else list(targets)
        moves = [(Path(f), self.outdir / name) for f, name in zip(files, names, strict=True)]
        for src, _ in moves:
            if self.path not in src.parents:
                raise ValueError(f"{src} is not inside the staging folder {self.path}")
        mode = _file_mode()
        with _folder_lock(self.outdir), _signals_held():
            check_targets(self.outdir, names)
            try:
                for src, dst in moves:
                    os.chmod(src, mode)
                    dst.parent.mkdir(parents=True, exist_ok=True)
                _write_journal(
                    self.path,
                    [(s.relative_to(self.path), n) for (s, _), n in zip(moves, names, strict=True)],
                )
            except OSError as exc:
                raise ExportError(f"cannot write {exc.filename or self.path}: {exc}") from exc
            self._keep = True  # from here on the journal decides
            done = []
            for k, (src, dst) in enumerate(moves, 1):
                try:
                    os.replace(src, dst)
                except OSError as exc:
                    raise ExportError(
                        f"cannot move {dst.name!r} into {str(self.outdir)!r}: "
                        f"{exc.strerror or exc}; {k - 1} of {len(moves)} files are in place, the "
                        f"rest wait in {self.path.name} and the next build into this folder "
                        "moves them once the obstacle is gone"
                    ) from exc
                done.append(dst)
                if on_move is not None:
                    on_move(dst)
                pause_point(f"commit:{k}")
            _fsync_dir(self.outdir)
            self.committed = True
            self._keep = False
        return done


def _write_journal(stage: Path, moves: Sequence[tuple[Path, str]]) -> None:
    """Write ``stage/commit.json`` atomically and durably."""
    tmp = stage / (_JOURNAL + ".tmp")
    data = {"version": 1, "moves": [[str(src), dst] for src, dst in moves]}
    with open(tmp, "w", encoding="utf-8") as fh:
        json.dump(data, fh)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, stage / _JOURNAL)
    _fsync_dir(stage)


def _roll_forward(stage: Path, outdir: Path) -> list[Path]:
    """Finish the commit journalled in ``stage``: move each staged file that
    is still there into ``outdir``."""
    data = json.loads((stage / _JOURNAL).read_text(encoding="utf-8"))
    moved = []
    for src, dst in data["moves"]:
        staged = stage / src
        if staged.exists():
            try:
                (outdir / dst).parent.mkdir(parents=True, exist_ok=True)
                os.replace(staged, outdir / dst)
            except OSError as exc:
                raise ExportError(
                    f"cannot finish an earlier build's commit: moving {dst!r} into "
                    f"{str(outdir)!r} failed ({exc.strerror or exc}); remove the obstacle "
                    "and run again"
                ) from exc
            moved.append(outdir / dst)
    _fsync_dir(outdir)
    return moved


def recover(outdir: str | os.PathLike[str]) -> list[Path]:
    """Finish or remove the staging folders that dead runs left in ``outdir``.

    A staging folder whose lock is free belongs to a process that has died:
    with a journal, its commit is finished (:func:`_roll_forward`); without
    one, it is removed. Folders of live runs are left alone.

    Returns:
        The files moved into place by finished commits.
    """
    out = Path(outdir)
    moved: list[Path] = []
    if not out.is_dir():
        return moved
    with _folder_lock(out):
        for stage in sorted(out.glob(f"{_PREFIX}*{_PARTIAL}")):
            try:
                fd = os.open(stage / _LOCK, os.O_RDWR)
            except FileNotFoundError:
                shutil.rmtree(stage, ignore_errors=True)  # no lock: never a live run's
                continue
            try:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                except BlockingIOError:
                    continue  # a live run
                if (stage / _JOURNAL).exists():
                    moved += _roll_forward(stage, out)
                shutil.rmtree(stage, ignore_errors=True)
            finally:
                os.close(fd)
        now = time.time()
        for init in out.glob(f"{_PREFIX}*{_INIT}"):
            with contextlib.suppress(OSError):
                if now - init.stat().st_mtime > _INIT_GRACE_S:
                    shutil.rmtree(init, ignore_errors=True)
    return moved
