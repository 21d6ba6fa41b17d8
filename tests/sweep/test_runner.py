"""The runner: the same rows in this process, on the process pool and on a
Dask LocalCluster; a sweep killed half way and rerun keeps every row once;
a rerun skips what is done."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from onefold_cad.sweep import runner
from onefold_cad.sweep.journal import JOURNAL, read_journal
from onefold_cad.sweep.plan import make_plan
from onefold_cad.sweep.runner import is_finished, run_sweep
from tests.sweep.conftest import SMALL, table_rows

ONEFOLD = str(Path(sys.executable).parent / "onefold")


def values(rows):
    """Rows without their timing (the one column that differs between runs)."""
    return [{k: v for k, v in r.items() if k != "seconds"} for r in rows]


def test_a_sweep_in_this_process_has_one_row_per_design(small_run):
    plan, folder, run = small_run
    rows = table_rows(folder)
    assert [r["key"] for r in rows] == list(plan.keys)
    assert run.designs == run.evaluated == 4 and run.skipped == 0 and run.failed == 0
    assert {r["status"] for r in rows} == {"ok"} and all(r["height"] > 0 for r in rows)


@pytest.mark.parametrize("where", ["pool", "local cluster"])
def test_the_pool_and_a_local_cluster_give_the_same_rows(small_run, tmp_path, where):
    plan, folder, _ = small_run
    if where == "pool":
        run = run_sweep(plan, tmp_path, jobs=2, quiet=True)
    else:
        pytest.importorskip("distributed")
        run = run_sweep(plan, tmp_path, jobs=2, scheduler="local", quiet=True)
    assert run.evaluated == 4
    assert values(table_rows(tmp_path)) == values(table_rows(folder))


def test_a_rerun_skips_the_designs_done_and_does_the_new_ones(small_run, tmp_path):
    plan, folder, _ = small_run
    for name in ("journal.jsonl",):
        (tmp_path / name).write_bytes((folder / name).read_bytes())
    again = run_sweep(plan, tmp_path, jobs=1, quiet=True)
    assert (again.skipped, again.evaluated) == (4, 0)
    wider = make_plan(
        SMALL[0], ["alpha=30:50:3", "beta=30,40"], measures=["bends", "mass"], images=False
    )
    more = run_sweep(wider, tmp_path, jobs=1, quiet=True)
    assert (more.skipped, more.evaluated) == (4, 2)  # alpha 40 is new
    # asking for a measure the journal's rows lack runs them again
    fewer = make_plan(SMALL[0], SMALL[1], measures=["bends"], images=False)
    rows = read_journal(tmp_path / JOURNAL)
    assert all(is_finished(rows[k], fewer, tmp_path) for k in fewer.keys)
    assert not is_finished(rows[plan.keys[0]], make_plan(*SMALL, images=True), tmp_path)


def _sweep_48(folder: Path, jobs: int) -> list[str]:
    """The command of a 48-design sweep into ``folder`` on ``jobs`` processes."""
    return [ONEFOLD, "sweep", SMALL[0], "--vary", "alpha=20:60:6", "--vary", "beta=20:60:8",
            "-o", str(folder), "-j", str(jobs), "--no-images"]  # fmt: skip


def _kill_half_way(folder: Path, jobs: int, mark: str) -> int:
    """Start a sweep of 48 designs, SIGKILL it once 3 rows are journaled;
    the rows journaled by then."""
    env = {**os.environ, "ONEFOLD_TEST_MARK": mark}
    cmd = [*_sweep_48(folder, jobs), "-q"]
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    journal = folder / JOURNAL
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if journal.exists() and journal.read_bytes().count(b"\n") >= 3:
            break
        time.sleep(0.01)
    assert proc.poll() is None, proc.stderr.read().decode()  # still running: kill it
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    proc.stderr.close()
    return len(read_journal(journal))


def _marked(mark: str) -> list[int]:
    """Processes whose environment carries ``mark`` (the killed sweep's workers)."""
    found = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                if f"ONEFOLD_TEST_MARK={mark}".encode() in (d / "environ").read_bytes():
                    found.append(int(d.name))
            except OSError:
                pass
    return found


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_killed_sweep_keeps_its_rows_and_a_rerun_ends_with_every_row_once(tmp_path, jobs):
    mark = uuid.uuid4().hex
    kept = _kill_half_way(tmp_path, jobs, mark)
    assert kept >= 3
    before = read_journal(tmp_path / JOURNAL)
    if jobs > 1:  # the pool's workers leave when the sweep is gone
        deadline = time.monotonic() + 10
        while _marked(mark) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _marked(mark) == []
    proc = subprocess.run(
        _sweep_48(tmp_path, jobs),
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert f"({len(before)} from an earlier run)" in proc.stderr
    rows = table_rows(tmp_path)
    keys = [r["key"] for r in rows]
    assert len(keys) == len(set(keys)) == 48
    lines = (tmp_path / JOURNAL).read_text().splitlines()
    assert len(lines) == 48 and all(json.loads(line) for line in lines)  # each row once
    after = read_journal(tmp_path / JOURNAL)
    assert all(after[k] == r for k, r in before.items())  # kept, not done again


def test_ctrl_c_keeps_the_rows_rebuilds_the_files_and_says_so(tmp_path):
    from tests.processes import interruptible

    cmd = [ONEFOLD, "sweep", SMALL[0], "--vary", "alpha=20:60:6", "--vary", "beta=20:60:8",
           "-o", str(tmp_path), "-j", "2", "--no-images", "-q"]  # fmt: skip
    proc = subprocess.Popen(
        cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        preexec_fn=interruptible,
    )  # fmt: skip
    journal = tmp_path / JOURNAL
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if journal.exists() and journal.read_bytes().count(b"\n") >= 3:
            break
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.splitlines()[-1] == (
        f"onefold: interrupted; the finished designs are kept in {journal} and the files "
        "rebuilt from them; rerun the same command to resume"
    )
    assert "Traceback" not in err
    kept = read_journal(journal)
    assert 3 <= len(kept) < 48
    assert sorted(r["key"] for r in table_rows(tmp_path)) == sorted(kept)


def test_the_last_batches_are_shared_among_every_batch_in_flight():
    # -j 2: two batches a worker in flight and one in the sweep's own process,
    # so 10 designs left go out two at a time, never five (a worker would
    # then finish its long last batch alone while the others wait)
    batches = runner._Batches(plan=None, todo=list(range(10)), workers=2)  # type: ignore[arg-type]
    assert batches.size() == 1  # nothing timed yet
    batches.record([{"seconds": 0.01}])
    assert batches.size() == 2
    batches.next = 8  # two left
    assert batches.size() == 1
