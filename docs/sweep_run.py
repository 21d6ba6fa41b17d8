"""What the sweep studies of docs/sweep.md share (``make_sweep_study.py``,
``make_sweep_steel.py``): their command line (``--scheduler``, ``-j``), the
run of their ``onefold sweep`` line from the repository root, and writing
their block into docs/sweep.md."""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent


def run_study(
    description: str,
    command: Sequence[str],
    out: Path,
    block: Callable[[float | None], str],
    name: str,
    argv: list[str] | None = None,
) -> str:
    """Run ``command`` (``onefold sweep ...``, into ``out``) with this
    script's ``--scheduler`` and ``-j``, then write ``block(seconds)`` into
    docs/sweep.md as block ``name`` (seconds: the run's wall time when it
    started afresh, None when it resumed an earlier run). Returns the text."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--scheduler", help="a Dask scheduler's address (default: the process pool)")
    ap.add_argument("-j", "--jobs", help="worker processes")
    args = ap.parse_args(argv)
    extra = (["--scheduler", args.scheduler] if args.scheduler else []) + (
        ["-j", args.jobs] if args.jobs else []
    )
    fresh = not (out / "journal.jsonl").exists()
    exe = str(Path(sys.executable).parent / "onefold")
    t0 = time.perf_counter()
    subprocess.run([exe, *command[1:], *extra], cwd=ROOT, check=True)
    seconds = time.perf_counter() - t0
    sys.path.insert(0, str(DOCS))
    from make_reference import write_block

    text = block(seconds if fresh else None)
    write_block(DOCS / "sweep.md", name, text)
    return text
