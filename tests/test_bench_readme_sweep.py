"""The README-sweep benchmark runs the README's command (correctness of its
helpers only, no timing) and its docs block is there."""

from __future__ import annotations

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "benchmarks"))

import bench_readme_sweep as bench  # noqa: E402


def test_it_runs_the_readmes_sweep_line_with_its_own_output_folder(tmp_path):
    lines = (REPO / "README.md").read_text().splitlines()
    line = next(ln for ln in lines if ln.startswith("onefold sweep "))
    args = bench.readme_sweep()
    assert " ".join(args) in line and "-o" in args and "#" not in args
    out = bench.with_output(args, tmp_path, None)
    assert out[out.index("-o") + 1] == str(tmp_path) and out[-1] == "--quiet"
    assert "-j" not in out  # as written: the pool
    assert bench.with_output(args, tmp_path, 1)[-3:] == ["-j", "1", "--quiet"]


def test_the_benchmark_s_block_is_in_the_benchmarks_page():
    page = (REPO / "docs" / "benchmarks.md").read_text()
    block = page.split("<!-- BEGIN bench_readme_sweep -->")[1].split("<!-- END ")[0]
    assert "this tree, -j 1" in block and "ec17278, as written" in block
