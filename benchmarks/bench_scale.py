"""Issue 24's three speed targets in one command: the default template's
solid resting placement (at most 10 ms), the sweep on this machine's 2 cores
(at least 100 designs/s) and the explorer's update (at most 50 ms), each by
its own benchmark, which writes its own block of docs/benchmarks.md
(``bench_rest``, ``bench_sweep``, ``bench_explore``); then a summary block
(``bench_scale``) with each target's verdict line, read back from those
blocks, so the summary and the tables come from the same run.

Run from the repository root (about 10 minutes on 2 cores)::

    .venv/bin/python benchmarks/bench_scale.py [--write-docs] [--baseline COMMIT]

Without ``--write-docs`` the three run and print; nothing is written.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import DOCS, ROOT, machine_line, write_block  # noqa: E402

HERE = Path(__file__).resolve().parent

#: (benchmark, its arguments, the docs block it writes, the target in words)
RUNS = (
    ("bench_rest.py", ["--rounds", "21"], "bench_rest", "resting placement <= 10 ms"),
    (
        "bench_sweep.py",
        ["--designs", "200", "--rounds", "3"],
        "bench_sweep",
        "sweep >= 100 designs/s on 2 cores",
    ),
    (
        "bench_explore.py",
        ["--moves", "20", "--only", "patkau-one-fold"],
        "bench_explore",
        "explorer update <= 50 ms",
    ),
)


def verdict_lines(block: str) -> list[str]:
    """The lines of a generated block that carry a PASS or FAIL."""
    return [line for line in block.splitlines() if re.search(r"\b(PASS|FAIL)\b", line)]


def block_text(name: str, path: Path = DOCS) -> str:
    """The body of generated block ``name`` of ``path``."""
    m = re.search(rf"<!-- BEGIN {re.escape(name)} -->\n(.*?)<!-- END {re.escape(name)} -->",
                  path.read_text(), re.S)  # fmt: skip
    if m is None:
        raise SystemExit(f"{path}: no block {name!r}")
    return m.group(1)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--write-docs", action="store_true")
    ap.add_argument("--baseline", default=None, help="the explorer's --baseline COMMIT")
    args = ap.parse_args(argv)
    rows = ["| target | benchmark | verdict lines |", "|---|---|---|"]
    for script, extra, block, target in RUNS:
        cmd = [sys.executable, str(HERE / script), *extra]
        if script == "bench_explore.py" and args.baseline:
            cmd += ["--baseline", args.baseline]
        if args.write_docs:
            cmd.append("--write-docs")
        print("$", " ".join(cmd[1:]), flush=True)
        out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
        print(out, flush=True)
        found = verdict_lines(block_text(block) if args.write_docs else out)
        rows.append(f"| {target} | `{script}` | " + "<br>".join(found or ["(no verdict)"]) + " |")
    body = machine_line() + " The three benchmarks one after the other.\n\n" + "\n".join(rows)
    print(body)
    if args.write_docs:
        extra = f" --baseline {args.baseline}" if args.baseline else ""
        write_block("bench_scale", body, f"python benchmarks/bench_scale.py --write-docs{extra}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
