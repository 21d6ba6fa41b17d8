"""All-or-nothing output: one file (atomic_output) and a set of files (Staging, recover)."""

from __future__ import annotations

import fcntl
import json
import os
import signal
import time
from pathlib import Path

import pytest

from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import (
    FileSet,
    Staging,
    _signals_held,
    atomic_output,
    check_targets,
    recover,
)


def names(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_atomic_output_replaces_only_on_success(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_output(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("writer failed")
    assert target.read_text() == "old" and names(tmp_path) == ["a.txt"]
    with atomic_output(target) as tmp:
        tmp.write_text("new")
    assert target.read_text() == "new" and names(tmp_path) == ["a.txt"]
    with pytest.raises(ExportError, match="does not exist"), atomic_output(tmp_path / "no" / "b"):
        pass


def staged_set(staging: Staging, *files: str) -> list[Path]:
    (staging.path / "1").mkdir()
    out = []
    for f in files:
        p = staging.path / "1" / f
        p.write_text(f"new {f}")
        out.append(p)
    return out


def test_commit_moves_the_whole_set_with_the_usual_mode(tmp_path):
    (tmp_path / "a.json").write_text("old a")
    old = os.umask(0o027)
    try:
        with Staging(tmp_path) as staging:
            assert staging.path.parent == tmp_path and staging.path.name.endswith(".partial")
            moved = staging.commit(staged_set(staging, "a.json", "a.dxf"))
    finally:
        os.umask(old)
    assert moved == [tmp_path / "a.json", tmp_path / "a.dxf"]
    assert names(tmp_path) == ["a.dxf", "a.json"]  # the staging folder is gone
    assert (tmp_path / "a.json").read_text() == "new a.json"
    assert (tmp_path / "a.dxf").stat().st_mode & 0o777 == 0o640  # 0o666 under umask 027


def test_leaving_without_a_commit_removes_everything(tmp_path):
    with pytest.raises(KeyboardInterrupt), Staging(tmp_path) as staging:
        staged_set(staging, "a.json")
        raise KeyboardInterrupt
    assert names(tmp_path) == []


def test_check_targets_refuses_a_folder_and_duplicate_names(tmp_path):
    (tmp_path / "a.json").mkdir()
    with pytest.raises(ExportError, match="a folder is in the way"):
        check_targets(tmp_path, ["a.dxf", "a.json"])
    with pytest.raises(ExportError, match="two files of this build"):
        check_targets(tmp_path, ["b.dxf", "b.dxf"])
    (tmp_path / "c.json").write_text("a file may be replaced")
    os.symlink(tmp_path / "nowhere", tmp_path / "d.json")  # so may a (dangling) link
    check_targets(tmp_path, ["c.json", "d.json", "e.json"])


def test_a_blocked_target_moves_nothing(tmp_path):
    (tmp_path / "a.json").mkdir()
    with Staging(tmp_path) as staging, pytest.raises(ExportError, match="in the way"):
        staging.commit(staged_set(staging, "a.dxf", "a.json"))
    assert names(tmp_path) == ["a.json"]


def dead_run(tmp_path: Path, fail_at: int, *files: str, sets: tuple[FileSet, ...] = ()) -> Path:
    """A commit that stopped after ``fail_at - 1`` moves and whose process then
    died (its lock released): what a SIGKILL between the moves leaves."""
    real, count = os.replace, []

    def replace(src, dst):
        if Path(dst).parent == tmp_path:
            count.append(dst)
            if len(count) == fail_at:
                raise OSError(5, "Input/output error")
        return real(src, dst)

    import onefold_cad.export.atomic as atomic

    atomic.os.replace = replace
    try:
        staging = Staging(tmp_path)
        with pytest.raises(ExportError, match="cannot move"):
            staging.commit(staged_set(staging, *files), sets=sets)
        staging.close()  # the journal stays; the lock goes, as when a process dies
    finally:
        atomic.os.replace = real
    return staging.path


def test_recover_finishes_a_dead_run_s_commit(tmp_path):
    stage = dead_run(tmp_path, 2, "a.dxf", "a.json", "b.json")
    assert json.loads((stage / "commit.json").read_text())["moves"] == [
        ["1/a.dxf", "a.dxf"], ["1/a.json", "a.json"], ["1/b.json", "b.json"],
    ]  # fmt: skip
    assert names(tmp_path) == sorted(["a.dxf", stage.name])
    assert recover(tmp_path) == [tmp_path / "a.json", tmp_path / "b.json"]
    assert names(tmp_path) == ["a.dxf", "a.json", "b.json"]
    assert (tmp_path / "b.json").read_text() == "new b.json"
    assert recover(tmp_path) == []  # idempotent


A_SET = FileSet("a", ("a.step", "a.dxf", "a-cut.dxf", "a.json"))


def old_set(folder: Path, *files: str) -> None:
    for f in files:
        (folder / f).write_text(f"old {f}")


def test_a_commit_replaces_each_set_whole(tmp_path):
    """Issue 38: the files of a set that the new build does not write (here
    a-cut.dxf) go too, and the marker only stands while the set changes;
    files outside the sets (the user's, another design's) stay."""
    old_set(tmp_path, "a.dxf", "a-cut.dxf", "a.json", "b.json", "mine.txt")
    with Staging(tmp_path) as staging:
        moved = staging.commit(staged_set(staging, "a.dxf", "a.json"), sets=[A_SET])
    assert moved == [tmp_path / "a.dxf", tmp_path / "a.json"]
    assert staging.removed == [tmp_path / "a-cut.dxf"]
    assert names(tmp_path) == ["a.dxf", "a.json", "b.json", "mine.txt"]
    assert [(tmp_path / f).read_text() for f in ("a.dxf", "b.json", "mine.txt")] == [
        "new a.dxf", "old b.json", "old mine.txt"
    ]  # fmt: skip


def test_a_set_s_folder_in_the_way_of_its_marker_is_refused(tmp_path):
    (tmp_path / "a.incomplete").mkdir()
    with Staging(tmp_path) as staging, pytest.raises(ExportError, match="in the way"):
        staging.commit(staged_set(staging, "a.json"), sets=[A_SET])
    assert names(tmp_path) == ["a.incomplete"]


def test_a_stopped_commit_is_marked_and_never_mixed(tmp_path):
    """A commit that died after its first move: the old set is gone whole
    (the retire step comes before any move), the marker stands beside the
    partial new set; recovery moves the rest without retiring the new file
    already in place, and removes the marker."""
    old_set(tmp_path, "a.dxf", "a-cut.dxf", "a.json")
    stage = dead_run(tmp_path, 2, "a.dxf", "a.json", sets=(A_SET,))
    assert names(tmp_path) == sorted(["a.dxf", "a.incomplete", stage.name])
    assert (tmp_path / "a.dxf").read_text() == "new a.dxf"
    assert "incomplete" in (tmp_path / "a.incomplete").read_text()
    said: list[str] = []
    assert recover(tmp_path, say=said.append) == [tmp_path / "a.json"]
    assert names(tmp_path) == ["a.dxf", "a.json"]
    assert [(tmp_path / f).read_text() for f in ("a.dxf", "a.json")] == ["new a.dxf", "new a.json"]
    assert said == [
        f"finished an interrupted earlier build into {str(tmp_path)!r}: 1 of its 2 files moved "
        f"in now, its staging folder {stage.name} removed"
    ]


def test_recover_finishes_a_journal_of_the_first_version(tmp_path):
    """A run of an older onefold (journal version 1: the moves only) that died
    half way is finished all the same."""
    stage = tmp_path / ".onefold-older000.partial"
    (stage / "1").mkdir(parents=True)
    (stage / "lock").write_text("")
    (stage / "1" / "b.json").write_text("new b.json")
    (stage / "commit.json").write_text(
        json.dumps({"version": 1, "moves": [["1/b.json", "b.json"]]})
    )
    old_set(tmp_path, "a.json")
    assert recover(tmp_path) == [tmp_path / "b.json"]
    assert names(tmp_path) == ["a.json", "b.json"]


def test_a_commit_finishes_a_dead_run_s_commit_before_its_own(tmp_path):
    """A run that died while this one was writing: its journal is carried
    out first, under the folder's lock, so the newer files win."""
    said: list[str] = []
    with Staging(tmp_path, say=said.append) as staging:
        files = staged_set(staging, "a.json")
        dead = dead_run(tmp_path, 2, "a.dxf", "a.json", sets=(A_SET,))
        staging.commit(files, sets=[A_SET])
    assert names(tmp_path) == ["a.json"]  # the dead run's a.dxf is retired by this set
    assert (tmp_path / "a.json").read_text() == "new a.json"
    assert len(said) == 1 and dead.name in said[0]


def test_recover_says_what_it_removes(tmp_path):
    nolock = tmp_path / ".onefold-nolock00.partial"
    nolock.mkdir()
    (nolock / "x").write_bytes(b"x" * 5000)
    old_init = tmp_path / ".onefold-old00000.init"
    old_init.mkdir()
    past = time.time() - 3600
    os.utime(old_init, (past, past))
    said: list[str] = []
    recover(tmp_path, say=said.append)
    assert said == [
        f"removed {str(nolock)!r} (5.0 kB), a staging folder without a lock",
        f"removed {str(old_init)!r}, a staging folder of a run that died creating it",
    ]
    assert names(tmp_path) == []


def test_recover_leaves_a_live_run_alone_and_removes_dead_ones(tmp_path):
    with Staging(tmp_path) as live:
        staged_set(live, "x.json")
        dead = tmp_path / ".onefold-abcdefgh.partial"
        (dead / "1").mkdir(parents=True)
        (dead / "lock").write_text("")
        nolock = tmp_path / ".onefold-nolock00.partial"
        nolock.mkdir()
        old_init = tmp_path / ".onefold-old00000.init"
        new_init = tmp_path / ".onefold-new00000.init"
        old_init.mkdir()
        new_init.mkdir()
        past = time.time() - 3600
        os.utime(old_init, (past, past))
        assert recover(tmp_path) == []
        assert names(tmp_path) == sorted([live.path.name, new_init.name])
        assert (live.path / "1" / "x.json").exists()


def test_recover_waits_for_nothing_it_cannot_lock(tmp_path):
    stage = tmp_path / ".onefold-held0000.partial"
    stage.mkdir()
    (stage / "lock").write_text("")
    with open(stage / "lock") as fh:  # another process's lock, as far as flock can tell
        fcntl.flock(fh, fcntl.LOCK_EX)
        recover(tmp_path)
        assert stage.exists()
    recover(tmp_path)
    assert not stage.exists()


def test_signals_are_held_back_until_the_block_ends(tmp_path):
    seen: list[int] = []
    old = signal.signal(signal.SIGTERM, lambda s, f: seen.append(s))
    try:
        with _signals_held():
            os.kill(os.getpid(), signal.SIGTERM)
            os.kill(os.getpid(), signal.SIGTERM)
            assert seen == []
        assert seen == [signal.SIGTERM]  # delivered once, after the block
    finally:
        signal.signal(signal.SIGTERM, old)
